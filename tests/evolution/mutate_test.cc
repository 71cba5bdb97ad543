// Mutation (master/evolution/operators.h): each kind does what it says, at
// its rate, reports itself, and the result is always a valid genome.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/base/rng.h"
#include "common/genome/genome.h"
#include "common/genome/random_genome.h"
#include "master/evolution/operators.h"
#include "tests/evolution/stats.h"
#include "tests/genome_builder.h"

namespace animat {
namespace {

constexpr int kNoLimit = static_cast<int>(kMaxGenomeElements);

MutationParams NoMutation() {
  MutationParams p;
  p.type_rate = 0.0;
  p.sign_rate = 0.0;
  p.coordinate_rate = 0.0;
  p.duplication_rate = 0.0;
  p.deletion_rate = 0.0;
  return p;
}

Genome RandomParent(uint64_t i, int units = 10) {
  RandomStream stream(31, i, StreamPurpose::kRandomGenome);
  return RandomGenome(stream, units);
}

// n P elements with distinct coordinates (x = index), so a run can be
// located in a mutated genome.
Genome Tagged(size_t n) {
  Genome g;
  for (size_t i = 0; i < n; ++i) {
    g.elements.push_back(testing::P(static_cast<double>(i), 0.0));
  }
  return g;
}

Genome Slice(const Genome& g, size_t begin, size_t end) {
  Genome s;
  s.elements.assign(g.elements.begin() + static_cast<ptrdiff_t>(begin),
                    g.elements.begin() + static_cast<ptrdiff_t>(end));
  return s;
}

Genome Concat(std::initializer_list<Genome> parts) {
  Genome out;
  for (const Genome& p : parts) {
    out.elements.insert(out.elements.end(), p.elements.begin(),
                        p.elements.end());
  }
  return out;
}

struct Mutated {
  Genome genome;
  std::vector<std::string> applied;
};

Mutated MutateWith(const Genome& g, const MutationParams& p, uint64_t child,
                   int max_elements = kNoLimit, uint64_t seed = 8) {
  RandomStream stream(seed, child, StreamPurpose::kMutation);
  Mutated m;
  m.genome = Mutate(g, p, max_elements, stream, &m.applied);
  return m;
}

bool Has(const std::vector<std::string>& applied, const std::string& kind) {
  return std::find(applied.begin(), applied.end(), kind) != applied.end();
}

// Kinds appear at most once, in the documented order.
::testing::AssertionResult ReportedInOrder(
    const std::vector<std::string>& applied) {
  static const std::vector<std::string> kOrder = {"type", "sign", "coordinates",
                                                  "duplication", "deletion"};
  size_t next = 0;
  for (const std::string& kind : applied) {
    const auto it = std::find(kOrder.begin() + static_cast<ptrdiff_t>(next),
                              kOrder.end(), kind);
    if (it == kOrder.end()) {
      return ::testing::AssertionFailure()
             << "'" << kind << "' unknown, repeated or out of order";
    }
    next = static_cast<size_t>(it - kOrder.begin()) + 1;
  }
  return ::testing::AssertionSuccess();
}

// Nothing changed that was not reported.
::testing::AssertionResult OnlyReportedChanges(const Genome& before,
                                               const Mutated& m,
                                               int max_elements) {
  const std::vector<std::string>& a = m.applied;
  const Genome& after = m.genome;
  const bool type = Has(a, "type"), sign = Has(a, "sign"),
             coordinates = Has(a, "coordinates"),
             duplication = Has(a, "duplication"), deletion = Has(a, "deletion");
  const size_t cap =
      std::min(before.elements.size(), static_cast<size_t>(max_elements));
  if (!duplication && !deletion) {
    if (after.elements.size() != cap) {
      return ::testing::AssertionFailure()
             << "size " << after.elements.size() << " without a run change";
    }
    for (size_t i = 0; i < cap; ++i) {
      const Element& x = before.elements[i];
      const Element& y = after.elements[i];
      if (!type && (x.type != y.type || x.channel != y.channel)) {
        return ::testing::AssertionFailure() << "type changed at " << i;
      }
      if (!sign && x.sign != y.sign) {
        return ::testing::AssertionFailure() << "sign changed at " << i;
      }
      if (!coordinates && (x.x != y.x || x.y != y.y)) {
        return ::testing::AssertionFailure() << "coordinates changed at " << i;
      }
    }
    return ::testing::AssertionSuccess();
  }
  if (!duplication && after.elements.size() > before.elements.size()) {
    return ::testing::AssertionFailure() << "grew without duplication";
  }
  if (!deletion && after.elements.size() < cap) {
    return ::testing::AssertionFailure() << "shrank without deletion";
  }
  if (!type && !sign && !coordinates) {
    for (const Element& e : after.elements) {
      if (std::find(before.elements.begin(), before.elements.end(), e) ==
          before.elements.end()) {
        return ::testing::AssertionFailure()
               << "an element not in the parent, without element changes";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(MutateTest, ZeroRatesChangeNothingAndReportNothing) {
  for (uint64_t i = 0; i < 200; ++i) {
    const Genome parent = RandomParent(i, static_cast<int>(i % 20));
    const Mutated m = MutateWith(parent, NoMutation(), i);
    EXPECT_EQ(m.genome, parent);
    EXPECT_TRUE(m.applied.empty());
  }
}

TEST(MutateTest, EmptyGenomeStaysEmpty) {
  MutationParams p;
  p.type_rate = p.sign_rate = p.coordinate_rate = 1.0;
  p.duplication_rate = p.deletion_rate = 1.0;
  for (uint64_t i = 0; i < 20; ++i) {
    const Mutated m = MutateWith(Genome{}, p, i);
    EXPECT_TRUE(m.genome.elements.empty());
    EXPECT_TRUE(m.applied.empty());
  }
}

TEST(MutateTest, TypeRateOneRedrawsEveryTypeAmongTheOtherFour) {
  MutationParams p = NoMutation();
  p.type_rate = 1.0;
  // new_type[old][new], and channels drawn for new S elements.
  std::vector<std::vector<int64_t>> transitions(5, std::vector<int64_t>(5, 0));
  std::vector<int64_t> inputs(kPaperInputChannels, 0),
      outputs(kOutputChannels, 0);
  for (uint64_t i = 0; i < 250; ++i) {
    const Genome parent = RandomParent(i);
    const Mutated m = MutateWith(parent, p, i);
    ASSERT_TRUE(ValidateGenome(m.genome).ok());
    EXPECT_EQ(m.applied, (std::vector<std::string>{"type"}));
    ASSERT_EQ(m.genome.elements.size(), parent.elements.size());
    for (size_t k = 0; k < parent.elements.size(); ++k) {
      const Element& x = parent.elements[k];
      const Element& y = m.genome.elements[k];
      EXPECT_NE(x.type, y.type);
      EXPECT_EQ(x.sign, y.sign);
      EXPECT_EQ(x.x, y.x);
      EXPECT_EQ(x.y, y.y);
      ++transitions[static_cast<int>(x.type)][static_cast<int>(y.type)];
      if (y.type == ElementType::kSIn) ++inputs[y.channel];
      if (y.type == ElementType::kSOut) ++outputs[y.channel];
    }
  }
  for (int from = 0; from < 5; ++from) {
    std::vector<int64_t> others;
    for (int to = 0; to < 5; ++to) {
      if (to == from) {
        EXPECT_EQ(transitions[from][to], 0);
      } else {
        others.push_back(transitions[from][to]);
      }
    }
    EXPECT_LT(testing::ChiSquare(others, std::vector<double>(4, 0.25)),
              testing::ChiSquareBound(4))
        << "from type " << from;
  }
  EXPECT_LT(testing::ChiSquare(inputs,
                               std::vector<double>(kPaperInputChannels,
                                                   1.0 / kPaperInputChannels)),
            testing::ChiSquareBound(kPaperInputChannels));
  EXPECT_LT(
      testing::ChiSquare(
          outputs, std::vector<double>(kOutputChannels, 1.0 / kOutputChannels)),
      testing::ChiSquareBound(kOutputChannels));
}

// A guidance run's mutations draw among all five input channels; the
// paper's (above) never draw CHEMICAL.
TEST(MutateTest, GuidanceRedrawsAmongFiveInputChannels) {
  MutationParams p = NoMutation();
  p.type_rate = 1.0;
  p.input_channels = kInputChannels;
  std::vector<int64_t> inputs(kInputChannels, 0);
  for (uint64_t i = 0; i < 250; ++i) {
    const Mutated m = MutateWith(RandomParent(i), p, i);
    ASSERT_TRUE(ValidateGenome(m.genome).ok());
    for (const Element& e : m.genome.elements) {
      if (e.type == ElementType::kSIn) ++inputs[e.channel];
    }
  }
  EXPECT_GT(inputs[static_cast<int>(InputChannel::kChemical)], 0);
  EXPECT_LT(
      testing::ChiSquare(
          inputs, std::vector<double>(kInputChannels, 1.0 / kInputChannels)),
      testing::ChiSquareBound(kInputChannels));
}

TEST(MutateTest, SignRateOneFlipsEverySignAndNothingElse) {
  MutationParams p = NoMutation();
  p.sign_rate = 1.0;
  for (uint64_t i = 0; i < 100; ++i) {
    const Genome parent = RandomParent(i);
    const Mutated m = MutateWith(parent, p, i);
    EXPECT_EQ(m.applied, (std::vector<std::string>{"sign"}));
    Genome flipped = parent;
    for (Element& e : flipped.elements) e.sign = -e.sign;
    EXPECT_EQ(m.genome, flipped);
  }
}

TEST(MutateTest, CoordinateStepsAreNormalWithTheGivenDeviation) {
  MutationParams p = NoMutation();
  p.coordinate_rate = 1.0;
  p.coordinate_sigma = 0.5;
  std::vector<double> dx, dy;
  for (uint64_t i = 0; i < 300; ++i) {
    const Genome parent = RandomParent(i);
    const Mutated m = MutateWith(parent, p, i);
    EXPECT_EQ(m.applied, (std::vector<std::string>{"coordinates"}));
    ASSERT_EQ(m.genome.elements.size(), parent.elements.size());
    for (size_t k = 0; k < parent.elements.size(); ++k) {
      const Element& x = parent.elements[k];
      const Element& y = m.genome.elements[k];
      EXPECT_EQ(x.type, y.type);
      EXPECT_EQ(x.sign, y.sign);
      EXPECT_EQ(x.channel, y.channel);
      dx.push_back(y.x - x.x);
      dy.push_back(y.y - x.y);
    }
  }
  const double n = static_cast<double>(dx.size());  // 9000 per axis.
  for (const std::vector<double>* d : {&dx, &dy}) {
    double sum = 0, sum2 = 0;
    int64_t within_one_sigma = 0;
    for (double v : *d) {
      sum += v;
      sum2 += v * v;
      within_one_sigma += std::fabs(v) < 0.5;
    }
    const double mean = sum / n;
    const double sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_LT(std::fabs(mean), 5.0 * 0.5 / std::sqrt(n));  // 0.026
    // The sample deviation's own deviation is about sigma / sqrt(2n).
    EXPECT_LT(std::fabs(sd - 0.5), 5.0 * 0.5 / std::sqrt(2.0 * n));
    // P(|Z| < 1) = 0.6827 for a normal.
    EXPECT_NEAR(static_cast<double>(within_one_sigma) / n, 0.6827,
                testing::ProportionTolerance(0.6827, static_cast<int64_t>(n)));
  }
  // The two axes move independently.
  double cross = 0;
  for (size_t k = 0; k < dx.size(); ++k) cross += dx[k] * dy[k];
  EXPECT_LT(std::fabs(cross / n / 0.25), 5.0 / std::sqrt(n));
}

TEST(MutateTest, PerElementRatesHold) {
  MutationParams p = NoMutation();
  p.type_rate = 0.1;
  p.sign_rate = 0.2;
  p.coordinate_rate = 0.3;
  int64_t elements = 0, types = 0, signs = 0, moves = 0;
  for (uint64_t i = 0; i < 400; ++i) {
    const Genome parent = RandomParent(i);
    const Mutated m = MutateWith(parent, p, i);
    ASSERT_EQ(m.genome.elements.size(), parent.elements.size());
    for (size_t k = 0; k < parent.elements.size(); ++k) {
      const Element& x = parent.elements[k];
      const Element& y = m.genome.elements[k];
      ++elements;
      types += x.type != y.type;
      signs += x.sign != y.sign;
      moves += x.x != y.x;
    }
  }
  const double n = static_cast<double>(elements);  // 12000.
  EXPECT_NEAR(types / n, 0.1, testing::ProportionTolerance(0.1, elements));
  EXPECT_NEAR(signs / n, 0.2, testing::ProportionTolerance(0.2, elements));
  EXPECT_NEAR(moves / n, 0.3, testing::ProportionTolerance(0.3, elements));
}

TEST(MutateTest, PerGenomeRatesHold) {
  MutationParams p = NoMutation();
  p.duplication_rate = 0.3;
  p.deletion_rate = 0.1;
  const int64_t genomes = 4000;
  int64_t duplications = 0, deletions = 0;
  for (uint64_t i = 0; i < static_cast<uint64_t>(genomes); ++i) {
    const Mutated m = MutateWith(Tagged(5), p, i);
    duplications += Has(m.applied, "duplication");
    deletions += Has(m.applied, "deletion");
  }
  EXPECT_NEAR(static_cast<double>(duplications) / genomes, 0.3,
              testing::ProportionTolerance(0.3, genomes));
  EXPECT_NEAR(static_cast<double>(deletions) / genomes, 0.1,
              testing::ProportionTolerance(0.1, genomes));
}

TEST(MutateTest, DuplicationInsertsAnExactCopyOfARunRightAfterIt) {
  MutationParams p = NoMutation();
  p.duplication_rate = 1.0;
  p.max_run_length = 4;
  const size_t n = 12;
  const Genome parent = Tagged(n);
  std::vector<int64_t> lengths(4, 0);
  std::vector<int64_t> starts(n, 0);
  for (uint64_t i = 0; i < 3000; ++i) {
    const Mutated m = MutateWith(parent, p, i);
    ASSERT_EQ(m.applied, (std::vector<std::string>{"duplication"}));
    const size_t grown = m.genome.elements.size() - n;
    ASSERT_GE(grown, 1u);
    ASSERT_LE(grown, 4u);
    ++lengths[grown - 1];
    // The first element where the child departs from the parent is the
    // start of the copy, so the run is the `grown` elements before it.
    size_t split = 0;
    while (split < n && m.genome.elements[split] == parent.elements[split]) {
      ++split;
    }
    // When the run is at the end, the copy follows the whole parent.
    ASSERT_GE(split, grown);
    const size_t start = split - grown;
    ++starts[start];
    EXPECT_EQ(m.genome, Concat({Slice(parent, 0, start + grown),
                                Slice(parent, start, start + grown),
                                Slice(parent, start + grown, n)}));
  }
  // Run lengths are uniform in [1, 4]; every valid start occurs.
  EXPECT_LT(testing::ChiSquare(lengths, std::vector<double>(4, 0.25)),
            testing::ChiSquareBound(4));
  for (size_t s = 0; s < n; ++s) EXPECT_GT(starts[s], 0) << s;
}

TEST(MutateTest, DuplicationRunIsCappedAtTheGenomeSize) {
  MutationParams p = NoMutation();
  p.duplication_rate = 1.0;
  p.max_run_length = 10;
  const Genome parent = Tagged(2);
  for (uint64_t i = 0; i < 200; ++i) {
    const Mutated m = MutateWith(parent, p, i);
    ASSERT_GE(m.genome.elements.size(), 3u);
    ASSERT_LE(m.genome.elements.size(), 4u);
  }
  const Mutated whole = MutateWith(Tagged(1), p, 0);
  EXPECT_EQ(whole.genome, Concat({Tagged(1), Tagged(1)}));
}

TEST(MutateTest, DeletionRemovesARun) {
  MutationParams p = NoMutation();
  p.deletion_rate = 1.0;
  p.max_run_length = 4;
  const size_t n = 12;
  const Genome parent = Tagged(n);
  std::vector<int64_t> lengths(4, 0);
  std::vector<int64_t> starts(n, 0);
  for (uint64_t i = 0; i < 3000; ++i) {
    const Mutated m = MutateWith(parent, p, i);
    ASSERT_EQ(m.applied, (std::vector<std::string>{"deletion"}));
    const size_t removed = n - m.genome.elements.size();
    ASSERT_GE(removed, 1u);
    ASSERT_LE(removed, 4u);
    ++lengths[removed - 1];
    size_t start = 0;
    while (start < m.genome.elements.size() &&
           m.genome.elements[start] == parent.elements[start]) {
      ++start;
    }
    ASSERT_LE(start + removed, n);
    ++starts[start];
    EXPECT_EQ(m.genome, Concat({Slice(parent, 0, start),
                                Slice(parent, start + removed, n)}));
  }
  EXPECT_LT(testing::ChiSquare(lengths, std::vector<double>(4, 0.25)),
            testing::ChiSquareBound(4));
  for (size_t s = 0; s < n; ++s) EXPECT_GT(starts[s], 0) << s;
}

TEST(MutateTest, DeletionNeverRemovesTheWholeGenome) {
  MutationParams p = NoMutation();
  p.deletion_rate = 1.0;
  p.max_run_length = 10;
  for (size_t n : {2u, 3u, 5u}) {
    for (uint64_t i = 0; i < 200; ++i) {
      const Mutated m = MutateWith(Tagged(n), p, i);
      EXPECT_GE(m.genome.elements.size(), 1u);
      EXPECT_LT(m.genome.elements.size(), n);
    }
  }
  // A genome of one element is left alone, and nothing is reported.
  for (uint64_t i = 0; i < 20; ++i) {
    const Mutated m = MutateWith(Tagged(1), p, i);
    EXPECT_EQ(m.genome, Tagged(1));
    EXPECT_TRUE(m.applied.empty());
  }
}

TEST(MutateTest, MaxElementsCutsTheEnd) {
  MutationParams p = NoMutation();
  p.duplication_rate = 1.0;
  p.sign_rate = 0.3;
  for (uint64_t i = 0; i < 80; ++i) {
    const Genome parent = RandomParent(i);  // 30 elements.
    const Mutated full = MutateWith(parent, p, i);
    for (int max_elements : {1, 20, 30, 31}) {
      const Mutated cut = MutateWith(parent, p, i, max_elements);
      EXPECT_LE(cut.genome.elements.size(), static_cast<size_t>(max_elements));
      // The same mutations, then the elements beyond the limit dropped.
      EXPECT_EQ(cut.genome, Slice(full.genome, 0,
                                  std::min(full.genome.elements.size(),
                                           static_cast<size_t>(max_elements))));
      EXPECT_EQ(cut.applied, full.applied);
    }
  }
  // Also without any mutation.
  EXPECT_EQ(MutateWith(Tagged(30), NoMutation(), 0, 12).genome, Tagged(12));
}

TEST(MutateTest, IsDeterministicPerStream) {
  const MutationParams p;  // Defaults.
  const Genome parent = RandomParent(3);
  const Mutated first = MutateWith(parent, p, 5);
  const Mutated again = MutateWith(parent, p, 5);
  EXPECT_EQ(first.genome, again.genome);
  EXPECT_EQ(first.applied, again.applied);
  int differing = 0;
  for (uint64_t c = 0; c < 50; ++c)
    differing += MutateWith(parent, p, c).genome != first.genome;
  EXPECT_GT(differing, 30);
}

// Property: over many random genomes, rates and limits, the result is
// valid, bounded, reported in order, and changed only as reported.
TEST(MutateTest, ResultIsAlwaysValidAndChangedOnlyAsReported) {
  const double kRates[] = {0.0, 0.02, 0.3, 1.0};
  RandomStream pick(99, 0, StreamPurpose::kVariation);
  int checked = 0;
  for (uint64_t i = 0; i < 500; ++i) {
    MutationParams p;
    p.type_rate = kRates[pick.Below(4)];
    p.sign_rate = kRates[pick.Below(4)];
    p.coordinate_rate = kRates[pick.Below(4)];
    p.coordinate_sigma = pick.Uniform(0.0, 5.0);
    p.duplication_rate = kRates[pick.Below(4)];
    p.deletion_rate = kRates[pick.Below(4)];
    p.max_run_length = 1 + static_cast<int>(pick.Below(8));
    const int max_elements = 1 + static_cast<int>(pick.Below(60));
    Genome genome = RandomParent(i, static_cast<int>(pick.Below(25)));
    // A few generations in a row, so genomes drift far from random ones.
    for (int generation = 0; generation < 3; ++generation) {
      const Mutated m = MutateWith(genome, p, i, max_elements,
                                   /*seed=*/static_cast<uint64_t>(generation));
      const Status valid = ValidateGenome(m.genome);
      ASSERT_TRUE(valid.ok()) << valid.ToString();
      ASSERT_LE(m.genome.elements.size(), static_cast<size_t>(max_elements));
      ASSERT_TRUE(ReportedInOrder(m.applied));
      ASSERT_TRUE(OnlyReportedChanges(genome, m, max_elements))
          << "case " << i << " generation " << generation;
      if (m.applied.empty()) {
        EXPECT_EQ(m.genome, Slice(genome, 0,
                                  std::min(genome.elements.size(),
                                           static_cast<size_t>(max_elements))));
      }
      genome = m.genome;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 1500);
}

}  // namespace
}  // namespace animat
