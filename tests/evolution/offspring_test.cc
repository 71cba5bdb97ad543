// MakeOffspring (master/evolution/operators.h): the composition of
// selection, crossover and mutation, each from its own stream.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "common/base/rng.h"
#include "common/genome/genome.h"
#include "common/genome/random_genome.h"
#include "master/evolution/operators.h"
#include "tests/evolution/stats.h"

namespace animat {
namespace {

// A ranked generation of `n` random genomes of `units` units with ids 100,
// 101, ...: ids are given fitness decreasing with id, except that every
// seventh failed. With units < 0 the genomes are empty: statistics of
// selection and variation then need few draws (they are slow in the
// sanitizer build).
class Generation {
 public:
  explicit Generation(int n, int units = 10) {
    std::vector<Scored> members;
    for (int i = 0; i < n; ++i) {
      const uint64_t id = 100 + static_cast<uint64_t>(i);
      RandomStream stream(12, id, StreamPurpose::kRandomGenome);
      genomes_[id] = units < 0 ? Genome{} : RandomGenome(stream, units);
      Scored s;
      s.id = id;
      if (i % 7 != 3) s.fitness = 1.0 / (1.0 + i);
      members.push_back(s);
    }
    ranked_ = Rank(members);
    for (size_t r = 0; r < ranked_.size(); ++r) rank_of_[ranked_[r].id] = r;
  }

  const std::vector<Scored>& ranked() const { return ranked_; }
  std::function<const Genome&(uint64_t)> genome_of() const {
    return [this](uint64_t id) -> const Genome& { return genomes_.at(id); };
  }
  size_t rank_of(uint64_t id) const { return rank_of_.at(id); }
  bool has(uint64_t id) const { return genomes_.count(id) != 0; }

 private:
  std::map<uint64_t, Genome> genomes_;
  std::vector<Scored> ranked_;
  std::map<uint64_t, size_t> rank_of_;
};

EvolutionParams NoMutationParams() {
  EvolutionParams p;
  p.mutation.type_rate = 0.0;
  p.mutation.sign_rate = 0.0;
  p.mutation.coordinate_rate = 0.0;
  p.mutation.duplication_rate = 0.0;
  p.mutation.deletion_rate = 0.0;
  return p;
}

bool SameOffspring(const Offspring& a, const Offspring& b) {
  return a.genome == b.genome && a.parents == b.parents &&
         a.operators == b.operators;
}

TEST(MakeOffspringTest, IsAPureFunctionOfSeedChildAndParents) {
  const Generation generation(30);
  EvolutionParams params;
  params.seed = 5;
  params.crossover_fraction = 0.5;
  // Another generation object with the same content, children made in
  // another order in between: the same offspring.
  const Generation copy(30);
  for (uint64_t child = 1000; child < 1100; ++child) {
    const Offspring first = MakeOffspring(child, generation.ranked(),
                                          generation.genome_of(), params);
    MakeOffspring(child + 7, copy.ranked(), copy.genome_of(), params);
    const Offspring again =
        MakeOffspring(child, copy.ranked(), copy.genome_of(), params);
    EXPECT_TRUE(SameOffspring(first, again)) << child;
  }
}

TEST(MakeOffspringTest, DiffersBetweenChildrenAndSeeds) {
  const Generation generation(30);
  EvolutionParams params;  // Defaults.
  std::set<std::tuple<std::vector<uint64_t>, std::vector<std::string>, size_t>>
      distinct;
  const int children = 200;
  std::vector<Offspring> made;
  for (int c = 0; c < children; ++c) {
    made.push_back(MakeOffspring(static_cast<uint64_t>(c), generation.ranked(),
                                 generation.genome_of(), params));
  }
  int differing_neighbours = 0;
  for (int c = 1; c < children; ++c) {
    differing_neighbours += !SameOffspring(made[c - 1], made[c]);
  }
  EXPECT_GE(differing_neighbours, children - 10);
  // Another seed, same child ids: other offspring.
  params.seed = 2;
  int differing_seed = 0;
  for (int c = 0; c < children; ++c) {
    differing_seed += !SameOffspring(
        made[c], MakeOffspring(static_cast<uint64_t>(c), generation.ranked(),
                               generation.genome_of(), params));
  }
  EXPECT_GE(differing_seed, children - 10);
}

TEST(MakeOffspringTest, ComposesTheOperatorsWithOneStreamPerPurpose) {
  const Generation generation(25);
  EvolutionParams params;
  params.seed = 41;
  params.crossover_fraction = 0.5;
  params.crossover_points = 3;
  const size_t n = generation.ranked().size();
  int crossovers = 0;
  for (uint64_t child = 0; child < 200; ++child) {
    const Offspring o = MakeOffspring(child, generation.ranked(),
                                      generation.genome_of(), params);
    RandomStream variation(41, child, StreamPurpose::kVariation);
    const bool crossover = variation.NextDouble() < 0.5;
    RandomStream selection(41, child, StreamPurpose::kSelection);
    const uint64_t first =
        generation.ranked()[Tournament(n, params.tournament_size, selection)]
            .id;
    Genome genome = generation.genome_of()(first);
    std::vector<uint64_t> parents = {first};
    std::vector<std::string> operators;
    if (crossover) {
      ++crossovers;
      const uint64_t second =
          generation.ranked()[Tournament(n, params.tournament_size, selection)]
              .id;
      parents.push_back(second);
      RandomStream cuts(41, child, StreamPurpose::kCrossover);
      genome = Crossover(genome, generation.genome_of()(second), 3, cuts);
      operators.push_back("crossover");
    }
    RandomStream mutation(41, child, StreamPurpose::kMutation);
    genome = Mutate(genome, params.mutation, params.max_elements, mutation,
                    &operators);
    if (operators.empty()) operators.push_back("copy");
    EXPECT_EQ(o.parents, parents) << child;
    EXPECT_EQ(o.operators, operators) << child;
    EXPECT_EQ(o.genome, genome) << child;
  }
  EXPECT_GT(crossovers, 50);
  EXPECT_LT(crossovers, 150);
}

TEST(MakeOffspringTest, CrossoverFractionOfOffspringIsCrossovers) {
  const Generation generation(40, /*units=*/-1);
  for (double fraction : {0.0, 0.2, 0.7, 1.0}) {
    EvolutionParams params;
    params.crossover_fraction = fraction;
    const int64_t children = 3000;
    int64_t crossovers = 0;
    for (int64_t c = 0; c < children; ++c) {
      const Offspring o =
          MakeOffspring(static_cast<uint64_t>(c), generation.ranked(),
                        generation.genome_of(), params);
      const bool is_crossover =
          !o.operators.empty() && o.operators[0] == "crossover";
      EXPECT_EQ(is_crossover, o.parents.size() == 2u);
      crossovers += is_crossover;
    }
    const double observed = static_cast<double>(crossovers) / children;
    if (fraction == 0.0 || fraction == 1.0) {
      EXPECT_EQ(observed, fraction);
    } else {
      EXPECT_NEAR(observed, fraction,
                  testing::ProportionTolerance(fraction, children));
    }
  }
}

TEST(MakeOffspringTest, ParentsAreRankedMembersAndBetterRanksWinMoreOften) {
  const Generation generation(20, /*units=*/-1);
  EvolutionParams params;  // Tournaments of 3.
  params.crossover_fraction = 0.3;
  const size_t n = generation.ranked().size();
  // Every parent, first or second, is a tournament winner.
  std::vector<int64_t> counts(n, 0);
  for (uint64_t c = 0; c < 6000; ++c) {
    const Offspring o =
        MakeOffspring(c, generation.ranked(), generation.genome_of(), params);
    ASSERT_FALSE(o.parents.empty());
    for (uint64_t parent : o.parents) {
      ASSERT_TRUE(generation.has(parent)) << parent;
      ++counts[generation.rank_of(parent)];
    }
  }
  // Rank i wins with ((n - i)^3 - (n - i - 1)^3) / n^3.
  std::vector<double> p(n);
  for (size_t i = 0; i < n; ++i) {
    const double hi = static_cast<double>(n - i), lo = hi - 1.0;
    p[i] = (hi * hi * hi - lo * lo * lo) / static_cast<double>(n * n * n);
  }
  // The best-ranked member is chosen more often than any other.
  for (size_t i = 1; i < n; ++i) EXPECT_GT(counts[0], counts[i]);
  int64_t top = 0, bottom = 0;
  for (size_t i = 0; i < 5; ++i) {
    top += counts[i];
    bottom += counts[n - 1 - i];
  }
  EXPECT_GT(top, 5 * bottom);
  std::vector<int64_t> pooled = counts;
  testing::PoolTail(&pooled, &p, 20.0);
  EXPECT_LT(testing::ChiSquare(pooled, p), testing::ChiSquareBound(p.size()));
}

TEST(MakeOffspringTest, WithoutVariationItIsACopyOfItsParent) {
  const Generation generation(10);
  EvolutionParams params = NoMutationParams();
  params.crossover_fraction = 0.0;
  for (uint64_t c = 0; c < 50; ++c) {
    const Offspring o =
        MakeOffspring(c, generation.ranked(), generation.genome_of(), params);
    ASSERT_EQ(o.parents.size(), 1u);
    EXPECT_EQ(o.operators, (std::vector<std::string>{"copy"}));
    EXPECT_EQ(o.genome, generation.genome_of()(o.parents[0]));
  }
  params.crossover_fraction = 1.0;
  for (uint64_t c = 0; c < 50; ++c) {
    const Offspring o =
        MakeOffspring(c, generation.ranked(), generation.genome_of(), params);
    ASSERT_EQ(o.parents.size(), 2u);
    EXPECT_EQ(o.operators, (std::vector<std::string>{"crossover"}));
  }
}

TEST(MakeOffspringTest, OffspringAreValidAndWithinMaxElements) {
  const Generation generation(15);
  EvolutionParams params;
  params.max_elements = 32;
  params.crossover_fraction = 0.5;
  params.mutation.duplication_rate = 0.8;
  for (uint64_t c = 0; c < 500; ++c) {
    const Offspring o =
        MakeOffspring(c, generation.ranked(), generation.genome_of(), params);
    EXPECT_TRUE(ValidateGenome(o.genome).ok());
    EXPECT_LE(o.genome.elements.size(), 32u);
  }
}

}  // namespace
}  // namespace animat
