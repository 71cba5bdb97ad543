// Ranking, tournament selection, crossover and initial candidates
// (master/evolution/operators.h).
#include "master/evolution/operators.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "common/base/rng.h"
#include "common/genome/genome.h"
#include "common/genome/random_genome.h"
#include "tests/evolution/stats.h"
#include "tests/genome_builder.h"
#include "tests/test_util.h"

namespace animat {
namespace {

std::vector<uint64_t> Ids(const std::vector<Scored>& members) {
  std::vector<uint64_t> ids;
  for (const Scored& s : members) ids.push_back(s.id);
  return ids;
}

Scored Member(uint64_t id, std::optional<double> fitness) {
  Scored s;
  s.id = id;
  s.fitness = fitness;
  return s;
}

// --- Rank -----------------------------------------------------------------

TEST(RankTest, HigherFitnessFirstFailuresLastTiesById) {
  const std::vector<Scored> members = {
      Member(5, 1.0), Member(2, 3.0),          Member(9, std::nullopt),
      Member(1, 1.0), Member(4, std::nullopt), Member(7, 0.0),
      Member(6, 3.0),
  };
  EXPECT_EQ(Ids(Rank(members)), (std::vector<uint64_t>{2, 6, 1, 5, 7, 4, 9}));
}

TEST(RankTest, NanFitnessRanksAsAFailure) {
  testing::FpTrapsOff traps_off;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Scored> members = {
      Member(3, nan), Member(8, std::nullopt), Member(1, -inf),
      Member(2, inf), Member(4, 0.5),
  };
  EXPECT_EQ(Ids(Rank(members)), (std::vector<uint64_t>{2, 4, 1, 3, 8}));
}

TEST(RankTest, ResultDoesNotDependOnInputOrder) {
  // Many ties and failures; every rotation and its reverse rank alike.
  std::vector<Scored> members;
  for (uint64_t id = 0; id < 40; ++id) {
    std::optional<double> fitness;
    if (id % 5 != 0) fitness = static_cast<double>((id * 7) % 4);
    members.push_back(Member(1000 - id * 3, fitness));
  }
  const std::vector<uint64_t> expected = Ids(Rank(members));
  for (size_t shift = 0; shift < members.size(); ++shift) {
    std::vector<Scored> permuted = members;
    std::rotate(permuted.begin(), permuted.begin() + shift, permuted.end());
    EXPECT_EQ(Ids(Rank(permuted)), expected);
    std::reverse(permuted.begin(), permuted.end());
    EXPECT_EQ(Ids(Rank(permuted)), expected);
  }
  // And the order is the documented one.
  const std::vector<Scored> ranked = Rank(members);
  for (size_t i = 1; i < ranked.size(); ++i) {
    const Scored& a = ranked[i - 1];
    const Scored& b = ranked[i];
    if (!a.fitness) {
      ASSERT_FALSE(b.fitness) << "a success after a failure at " << i;
      EXPECT_LT(a.id, b.id);
    } else if (b.fitness) {
      EXPECT_TRUE(*a.fitness > *b.fitness ||
                  (*a.fitness == *b.fitness && a.id < b.id))
          << "at " << i;
    }
  }
}

TEST(RankTest, EmptyStaysEmpty) { EXPECT_TRUE(Rank({}).empty()); }

// --- Tournament -----------------------------------------------------------

// P(winner = i) for `size` uniform draws with replacement among n, the
// lowest winning: ((n - i)^k - (n - i - 1)^k) / n^k.
std::vector<double> TournamentProbabilities(size_t n, int k) {
  std::vector<double> p(n);
  for (size_t i = 0; i < n; ++i) {
    const double hi = static_cast<double>(n - i) / static_cast<double>(n);
    const double lo = static_cast<double>(n - i - 1) / static_cast<double>(n);
    p[i] = std::pow(hi, k) - std::pow(lo, k);
  }
  return p;
}

std::vector<int64_t> TournamentCounts(size_t n, int k, int draws,
                                      uint64_t seed) {
  std::vector<int64_t> counts(n, 0);
  RandomStream stream(seed, 0, StreamPurpose::kSelection);
  for (int i = 0; i < draws; ++i) {
    const size_t winner = Tournament(n, k, stream);
    EXPECT_LT(winner, n);
    if (winner < n) ++counts[winner];
  }
  return counts;
}

TEST(TournamentTest, SizeOneIsUniform) {
  const size_t n = 12;
  const std::vector<int64_t> counts = TournamentCounts(n, 1, 24000, 11);
  const std::vector<double> uniform(n, 1.0 / static_cast<double>(n));
  EXPECT_LT(testing::ChiSquare(counts, uniform), testing::ChiSquareBound(n));
}

TEST(TournamentTest, WinnerFollowsTheMinimumOfKUniformDraws) {
  const size_t n = 8;
  const int draws = 12000;
  for (int k : {2, 3, 5}) {
    std::vector<int64_t> counts = TournamentCounts(n, k, draws, 20 + k);
    std::vector<double> p = TournamentProbabilities(n, k);
    // Better ranks win more often (checked where the expected counts are
    // far enough apart for noise not to matter).
    for (size_t i = 1; i < n; ++i) {
      if ((p[i - 1] - p[i]) * draws > 200) {
        EXPECT_GT(counts[i - 1], counts[i]) << "size " << k << " rank " << i;
      }
    }
    // Chi-square, pooling the worst ranks until each bin expects >= 20.
    testing::PoolTail(&counts, &p, 20.0);
    EXPECT_LT(testing::ChiSquare(counts, p), testing::ChiSquareBound(p.size()))
        << "size " << k;
  }
}

TEST(TournamentTest, UsesExactlySizeDrawsPerTournament) {
  // With a population of 300 the rejection in Below practically never
  // fires, so the stream advances by one draw per contestant.
  RandomStream stream(3, 7, StreamPurpose::kSelection);
  Tournament(300, 4, stream);
  EXPECT_EQ(stream.draws(), 4u);
}

TEST(TournamentTest, OneIndividualAlwaysWins) {
  RandomStream stream(1, 1, StreamPurpose::kSelection);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(Tournament(1, 3, stream), 0u);
}

// --- Crossover ------------------------------------------------------------

// n elements whose x is their index and y their parent (0 or 1), so a
// child's elements say where they came from.
Genome Tagged(size_t n, int parent) {
  Genome g;
  for (size_t i = 0; i < n; ++i) {
    g.elements.push_back(
        testing::P(static_cast<double>(i), static_cast<double>(parent)));
  }
  return g;
}

struct Origin {
  int parent;
  size_t index;
};

std::vector<Origin> Origins(const Genome& child) {
  std::vector<Origin> origins;
  for (const Element& e : child.elements) {
    origins.push_back({static_cast<int>(e.y), static_cast<size_t>(e.x)});
  }
  return origins;
}

// The documented rule written out independently: `points` fractions in
// (0, 1), sorted; parent of length n cut at the nearest integer to f * n;
// segments alternately from a and b.
Genome ExpectedCrossover(const Genome& a, const Genome& b, int points,
                         RandomStream stream) {
  std::vector<double> f;
  while (static_cast<int>(f.size()) < points) {
    const double u = stream.NextDouble();
    if (u > 0.0) f.push_back(u);
  }
  std::sort(f.begin(), f.end());
  auto cut = [](double fraction, size_t n) {
    return static_cast<size_t>(std::lround(fraction * static_cast<double>(n)));
  };
  Genome child;
  for (size_t s = 0; s <= f.size(); ++s) {
    const std::vector<Element>& p = (s % 2 == 0 ? a : b).elements;
    const size_t begin = s == 0 ? 0 : cut(f[s - 1], p.size());
    const size_t end = s == f.size() ? p.size() : cut(f[s], p.size());
    for (size_t i = begin; i < end; ++i) child.elements.push_back(p[i]);
  }
  return child;
}

TEST(CrossoverTest, EqualLengthParentsGiveEqualLengthChildMixedInPlace) {
  for (int points : {1, 2, 3, 7}) {
    for (uint64_t c = 0; c < 200; ++c) {
      RandomStream stream(5, c, StreamPurpose::kCrossover);
      const Genome child =
          Crossover(Tagged(30, 0), Tagged(30, 1), points, stream);
      ASSERT_EQ(child.elements.size(), 30u);
      const std::vector<Origin> o = Origins(child);
      int switches = 0;
      for (size_t i = 0; i < o.size(); ++i) {
        EXPECT_EQ(o[i].index, i);  // Element i comes from a[i] or b[i].
        if (i > 0 && o[i].parent != o[i - 1].parent) ++switches;
      }
      EXPECT_LE(switches, points);
      EXPECT_EQ(stream.draws(), static_cast<uint64_t>(points));
    }
  }
}

TEST(CrossoverTest, OnePointGivesAPrefixOfAThenASuffixOfB) {
  for (uint64_t c = 0; c < 300; ++c) {
    const size_t na = 5 + c % 23;
    const size_t nb = 3 + (c * 7) % 31;
    RandomStream stream(9, c, StreamPurpose::kCrossover);
    const Genome child = Crossover(Tagged(na, 0), Tagged(nb, 1), 1, stream);
    const std::vector<Origin> o = Origins(child);
    size_t i = 0;
    while (i < o.size() && o[i].parent == 0) {
      EXPECT_EQ(o[i].index, i);
      ++i;
    }
    const size_t prefix = i;  // a[0, prefix)
    const size_t suffix_start = nb - (o.size() - prefix);
    for (size_t j = prefix; j < o.size(); ++j) {
      EXPECT_EQ(o[j].parent, 1);
      EXPECT_EQ(o[j].index, suffix_start + (j - prefix));  // b[.., nb)
    }
    // Both cuts come from one fraction f: |prefix/na - start/nb| is at most
    // the two roundings.
    EXPECT_LE(std::fabs(static_cast<double>(prefix) / na -
                        static_cast<double>(suffix_start) / nb),
              0.5 / na + 0.5 / nb + 1e-12)
        << na << " " << nb << " " << prefix << " " << suffix_start;
  }
}

TEST(CrossoverTest, ChildTakesTheParentsSegmentsInOrder) {
  for (int points : {1, 2, 3, 4, 9}) {
    for (uint64_t c = 0; c < 200; ++c) {
      const size_t na = c % 41;  // Including empty parents.
      const size_t nb = (c * 13) % 37;
      const Genome a = Tagged(na, 0);
      const Genome b = Tagged(nb, 1);
      RandomStream stream(2, c, StreamPurpose::kCrossover);
      const Genome expected = ExpectedCrossover(a, b, points, stream);
      const Genome child = Crossover(a, b, points, stream);
      EXPECT_EQ(child, expected) << points << " points, child " << c;
      // Black-box properties: from each parent, indices strictly increase;
      // the length is a mix of the parents' within the rounding of each cut.
      size_t next[2] = {0, 0};
      for (const Origin& o : Origins(child)) {
        EXPECT_GE(o.index, next[o.parent]);
        next[o.parent] = o.index + 1;
      }
      const double lo = static_cast<double>(std::min(na, nb)) - points;
      const double hi = static_cast<double>(std::max(na, nb)) + points;
      EXPECT_GE(static_cast<double>(child.elements.size()), lo);
      EXPECT_LE(static_cast<double>(child.elements.size()), hi);
    }
  }
}

TEST(CrossoverTest, IdenticalParentsGiveTheParent) {
  for (uint64_t c = 0; c < 100; ++c) {
    RandomStream genome_stream(4, c, StreamPurpose::kRandomGenome);
    const Genome parent = RandomGenome(genome_stream, 1 + c % 15);
    for (int points : {1, 2, 5}) {
      RandomStream stream(4, c, StreamPurpose::kCrossover);
      EXPECT_EQ(Crossover(parent, parent, points, stream), parent);
    }
  }
}

TEST(CrossoverTest, EveryInnerCutPositionOccurs) {
  // One point between parents of 10: the cut can fall between any two
  // elements.
  std::vector<int> seen(11, 0);
  for (uint64_t c = 0; c < 2000; ++c) {
    RandomStream stream(6, c, StreamPurpose::kCrossover);
    const std::vector<Origin> o =
        Origins(Crossover(Tagged(10, 0), Tagged(10, 1), 1, stream));
    size_t prefix = 0;
    while (prefix < o.size() && o[prefix].parent == 0) ++prefix;
    ++seen[prefix];
  }
  for (size_t cut = 1; cut < 10; ++cut) EXPECT_GT(seen[cut], 100) << cut;
}

// --- InitialCandidate -----------------------------------------------------

TEST(InitialCandidateTest, IsTheRandomGenomeOfItsStream) {
  EvolutionParams params;
  params.seed = 77;
  for (int units : {1, 10, 25}) {
    params.initial_units = units;
    for (uint64_t index :
         {uint64_t{0}, uint64_t{1}, uint64_t{999}, uint64_t{1} << 40}) {
      RandomStream stream(77, index, StreamPurpose::kRandomGenome);
      const Genome expected = RandomGenome(stream, units);
      const Genome candidate = InitialCandidate(index, params);
      EXPECT_EQ(candidate, expected);
      EXPECT_EQ(candidate.elements.size(),
                static_cast<size_t>(2 * units + kPaperInputChannels +
                                    kOutputChannels));
      EXPECT_TRUE(ValidateGenome(candidate).ok());
    }
  }
  EXPECT_NE(InitialCandidate(0, params), InitialCandidate(1, params));
}

}  // namespace
}  // namespace animat
