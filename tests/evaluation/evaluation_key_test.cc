// EvaluationKey: genomes whose keys are equal evaluate to the same result
// bit for bit (the master records one's evaluation for the other), and a
// change that an evaluation reads changes the key.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "common/base/rng.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/genome/random_genome.h"
#include "common/grn/network.h"
#include "tests/test_genome.h"

namespace animat {
namespace {

using testing::LoadGenome;

using testing::ShortConfig;

// Every field of the result, as the wire carries it.
std::string Bits(const EvaluationResult& result) {
  return EvaluationResultToProto(result).SerializeAsString();
}

std::string Bytes(const Genome& genome) {
  return GenomeToProto(genome).SerializeAsString();
}

TEST(EvaluationKeyTest, AnElementThatBindsNothingChangesNeitherKeyNorResult) {
  const ModelConfig config = ShortConfig();
  const Genome genome = LoadGenome("seed-1198.json");
  ASSERT_FALSE(genome.elements.empty());
  // A P element far from every factor, put first: it binds nothing, and
  // every element after it moves one place in the genome.
  Genome far = genome;
  Element p;
  p.type = ElementType::kP;
  p.x = 1e6;
  p.y = -1e6;
  far.elements.insert(far.elements.begin(), p);
  ASSERT_NE(Bytes(far), Bytes(genome));
  const std::optional<std::string> key = EvaluationKey(genome, config);
  ASSERT_TRUE(key.has_value());
  EXPECT_EQ(EvaluationKey(far, config), key);
  const EvaluationResult before = Evaluate(genome, config);
  ASSERT_EQ(before.status, EvalStatus::kOk) << before.reason;
  EXPECT_EQ(Bits(Evaluate(far, config)), Bits(before));
}

TEST(EvaluationKeyTest, EveryElementMovedKeepsItsResultWhenItKeepsItsKey) {
  // Each element moved far away in turn: where the key stays (it bound
  // nothing), the result is the same bits; where it changes, the element
  // was read. Both happen in this genome.
  const ModelConfig config = ShortConfig();
  const Genome genome = LoadGenome("seed-1198.json");
  const std::optional<std::string> key = EvaluationKey(genome, config);
  ASSERT_TRUE(key.has_value());
  const std::string bits = Bits(Evaluate(genome, config));
  int same = 0;
  int changed = 0;
  for (size_t i = 0; i < genome.elements.size(); ++i) {
    Genome moved = genome;
    moved.elements[i].x += 1000.0;
    if (EvaluationKey(moved, config) == key) {
      ++same;
      EXPECT_EQ(Bits(Evaluate(moved, config)), bits) << "element " << i;
    } else {
      ++changed;
    }
  }
  EXPECT_GT(same, 0);
  EXPECT_GT(changed, 0);
}

TEST(EvaluationKeyTest, GenomesOfOneKeyEvaluateAlike) {
  // Evolved and random genomes, each element in turn moved far, doubled
  // or removed: a variant that keeps the genome's key (nothing read
  // changed: the element bound nothing, or only fed nodes that reach no
  // output) gives the same result bits, whatever the status.
  ModelConfig config;
  config.evaluation.motion_steps = 60;
  config.evaluation.equilibration_steps = 20;
  std::vector<Genome> genomes;
  for (const char* name :
       {"seed-1198.json", "seed-1203.json", "seed-139.json",
        "folding-dn1-seed3.json", "evolved-stops-actuating.json"}) {
    genomes.push_back(LoadGenome(name));
  }
  for (uint64_t individual = 0; individual < 8; ++individual) {
    RandomStream stream(7, individual, StreamPurpose::kRandomGenome);
    genomes.push_back(RandomGenome(stream));
  }
  int same = 0;
  int same_ok = 0;  // Of them, ok evaluations.
  int pruned = 0;   // Kept the key although a weight or binding changed.
  for (size_t g = 0; g < genomes.size(); ++g) {
    const Genome& genome = genomes[g];
    const std::optional<std::string> key = EvaluationKey(genome, config);
    ASSERT_TRUE(key.has_value());
    const EvaluationResult result = Evaluate(genome, config);
    const std::string bits = Bits(result);
    const Network network = Network::Build(genome, config.grn);
    for (size_t i = 0; i < genome.elements.size(); ++i) {
      for (int change = 0; change < 3; ++change) {
        Genome variant = genome;
        if (change == 0) variant.elements[i].x += 1000.0;
        if (change == 1) {
          variant.elements.insert(variant.elements.begin() + i,
                                  genome.elements[i]);
        }
        if (change == 2) variant.elements.erase(variant.elements.begin() + i);
        if (EvaluationKey(variant, config) != key) continue;
        ++same;
        same_ok += result.status == EvalStatus::kOk;
        const Network other = Network::Build(variant, config.grn);
        pruned += other.weight_value() != network.weight_value() ||
                  other.successors() != network.successors();
        EXPECT_EQ(Bits(Evaluate(variant, config)), bits)
            << "genome " << g << ", element " << i << ", change " << change;
      }
    }
  }
  EXPECT_GT(same_ok, 20);
  EXPECT_GT(same - same_ok, 20);
  EXPECT_GT(pruned, 0) << "no variant kept its key through the pruning";
}

TEST(EvaluationKeyTest, AWeightChangedOrAnInvalidGenome) {
  const ModelConfig config = ShortConfig();
  const Genome genome = LoadGenome("seed-1198.json");
  const std::optional<std::string> key = EvaluationKey(genome, config);
  // A binding pair's distance changed by a little changes its weight's
  // bits: some element's small move must change the key.
  bool some = false;
  for (size_t i = 0; i < genome.elements.size() && !some; ++i) {
    Genome nudged = genome;
    nudged.elements[i].x += 1e-3;
    some = EvaluationKey(nudged, config) != key;
  }
  EXPECT_TRUE(some);
  // Another GRN parameter reads the same genome differently.
  ModelConfig other = config;
  other.grn.weight_max *= 2;
  EXPECT_NE(EvaluationKey(genome, other), key);
  // An invalid genome has no key (its evaluation names its fault).
  Genome invalid = genome;
  invalid.elements[0].sign = 0;
  EXPECT_EQ(EvaluationKey(invalid, config), std::nullopt);
}

}  // namespace
}  // namespace animat
