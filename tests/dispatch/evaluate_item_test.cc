// A worker's evaluation of one item (worker/evaluation_pool.h): the result
// names the instruction-set path that ran it, and every path gives the
// same result.
#include <gtest/gtest.h>

#include <string>

#include "common/base/text.h"
#include "common/genome/genome_proto.h"
#include "common/kernels/isa.h"
#include "tests/test_genome.h"
#include "worker/evaluation_pool.h"

namespace animat {
namespace {

// The result's path by name: "avx512" for AVX512.
std::string Named(v1::WorkResult::Isa isa) {
  return AsciiLowerCase(v1::WorkResult::Isa_Name(isa));
}

TEST(EvaluateItemTest, EachResultNamesItsPathAndEveryPathGivesTheSameBits) {
  ModelConfig config;
  config.evaluation.motion_steps = 300;  // The path shows within a few.
  v1::WorkItem item;
  item.set_individual(42);
  *item.mutable_genome() = GenomeToProto(testing::LoadGenome("seed-1198.json"));
  item.set_genome_hash(7);
  const Isa before = ActiveIsa();
  std::string first;
  for (Isa isa : SupportedIsas()) {
    ASSERT_TRUE(SelectIsa(isa).ok());
    const v1::WorkResult r = EvaluateItem(item, config);
    EXPECT_EQ(Named(r.isa()), IsaName(isa));
    EXPECT_EQ(r.individual(), 42u);
    EXPECT_EQ(r.result().status(), v1::EvaluationResult::OK);
    const std::string bits = r.result().SerializeAsString();
    if (first.empty()) first = bits;
    EXPECT_EQ(bits, first) << IsaName(isa);
  }
  ASSERT_TRUE(SelectIsa(before).ok());
}

// An invalid genome is still said where it was refused: the path is the
// worker's, whatever the item.
TEST(EvaluateItemTest, AnInvalidGenomeStillNamesThePath) {
  v1::WorkItem item;
  item.set_individual(1);
  item.mutable_genome()->add_elements();  // Not a valid genome.
  const v1::WorkResult r = EvaluateItem(item, ModelConfig{});
  EXPECT_EQ(r.result().status(), v1::EvaluationResult::INVALID_GENOME);
  EXPECT_EQ(Named(r.isa()), IsaName(ActiveIsa()));
}

}  // namespace
}  // namespace animat
