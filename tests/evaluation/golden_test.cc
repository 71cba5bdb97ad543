// Golden determinism: fixed genomes give fixed fitness bits and final-state
// hashes. CI runs this in a Release build and in a Debug build with
// sanitizers; both must match these values, so optimisation never changes
// a result. A deliberate change of the model changes them: update them in
// the same commit and say why.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>

#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "tests/test_util.h"

namespace animat {
namespace {

struct Golden {
  const char* genome;
  Precision precision;
  uint64_t fitness_bits;
  uint64_t state_hash;
};

class GoldenTest : public ::testing::TestWithParam<Golden> {};

TEST_P(GoldenTest, FitnessBitsAndFinalStateAreFixed) {
  const Golden& golden = GetParam();
  v1::Genome message;
  ASSERT_TRUE(
      ReadProtoFile(testing::TestData(std::string("genomes/") + golden.genome),
                    &message)
          .ok());
  Result<Genome> genome = GenomeFromProto(message);
  ASSERT_TRUE(genome.ok());
  ModelConfig config;
  config.grn.precision = golden.precision;
  // The values below were recorded under model v1: chains allowed,
  // semi-implicit Euler with one sub-step, no contacts. `min_chambers: 0`
  // with that integrator and contact rule reproduces them bit for bit.
  config.evaluation.min_chambers = 0;
  config.physics.integrator = Integrator::kSemiImplicitEuler;
  config.physics.substeps = 1;
  config.physics.contact_rule = ContactRule::kNone;
  const EvaluationResult r = Evaluate(*genome, config);
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_TRUE(r.fitness.has_value());
  EXPECT_EQ(std::bit_cast<uint64_t>(*r.fitness), golden.fitness_bits)
      << "fitness " << *r.fitness;
  EXPECT_EQ(r.state_hash, golden.state_hash) << std::hex << r.state_hash;
  EXPECT_EQ(r.cells, 32);
}

// Model v2 with RK4 and one sub-step, the default from 2026-11-25 until
// Ralston's third order met the accuracy rule more cheaply: recorded when
// RK4 became the default, pinned here so that runs made under it stay
// reproducible.
class GoldenRk4Test : public ::testing::TestWithParam<Golden> {};

// The default configuration of model v2: the chamber rule and Ralston's
// third order with one sub-step (model §7.6's rule), no contacts. Recorded
// when it became the default.
class GoldenRalston3Test : public ::testing::TestWithParam<Golden> {};

// Model v3 as first set, the default from 2026-11-27 until full-length
// evolutions pressed cells deeper than its contacts held: contacts between
// unjoined cells at k_c 200 and velocity Verlet with two sub-steps.
// Recorded when it became the default, with the deepest unjoined overlap
// (model §8.6), pinned here so that runs made under it stay reproducible.
struct GoldenV3 {
  Golden golden;
  uint64_t max_overlap_bits;
};
class GoldenV3FirstTest : public ::testing::TestWithParam<GoldenV3> {};

// Model v3 as set on 2026-11-28, the default until a 250-generation run
// pressed cells deeper than its contacts held: k_c 1500 and velocity
// Verlet with four sub-steps. Recorded when it became the default, pinned
// here so that runs made under it (the first main runs of the third
// replication) stay reproducible.
class GoldenV3K1500Test : public ::testing::TestWithParam<GoldenV3> {};

// The default configuration of model v3: contacts between unjoined cells at
// the stiffness chosen over the accuracy set's animats that press hardest
// (model §7.10) and the integrator the accuracy rule chose with it (model
// §11.4). Recorded when it became the default.
class GoldenDefaultTest : public ::testing::TestWithParam<GoldenV3> {};

// The default configuration of model v2 (Ralston's third order with one
// sub-step, no contacts), which the RK4 test changes only in its
// integrator.
ModelConfig ModelV2() {
  ModelConfig config;
  config.physics.integrator = Integrator::kRalston3;
  config.physics.substeps = 1;
  config.physics.contact_rule = ContactRule::kNone;
  return config;
}

EvaluationResult EvaluateGolden(const Golden& golden, ModelConfig config) {
  v1::Genome message;
  const Status read = ReadProtoFile(
      testing::TestData(std::string("genomes/") + golden.genome), &message);
  EXPECT_TRUE(read.ok()) << read.message();
  Result<Genome> genome = GenomeFromProto(message);
  EXPECT_TRUE(genome.ok());
  if (!genome.ok()) return {};
  config.grn.precision = golden.precision;
  return Evaluate(*genome, config);
}

void ExpectGolden(const Golden& golden, const EvaluationResult& r) {
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_TRUE(r.fitness.has_value());
  EXPECT_EQ(std::bit_cast<uint64_t>(*r.fitness), golden.fitness_bits)
      << "fitness " << *r.fitness << " bits " << std::hex
      << std::bit_cast<uint64_t>(*r.fitness);
  EXPECT_EQ(r.state_hash, golden.state_hash) << std::hex << r.state_hash;
}

TEST_P(GoldenRk4Test, FitnessBitsAndFinalStateAreFixed) {
  ModelConfig config = ModelV2();
  config.physics.integrator = Integrator::kRk4;
  ExpectGolden(GetParam(), EvaluateGolden(GetParam(), config));
}

TEST_P(GoldenRalston3Test, FitnessBitsAndFinalStateAreFixed) {
  ModelConfig config = ModelV2();
  config.physics.integrator = Integrator::kRalston3;
  ExpectGolden(GetParam(), EvaluateGolden(GetParam(), config));
}

void ExpectGoldenV3(const GoldenV3& v3, const ModelConfig& config) {
  const EvaluationResult r = EvaluateGolden(v3.golden, config);
  ExpectGolden(v3.golden, r);
  ASSERT_TRUE(r.max_overlap.has_value());
  EXPECT_EQ(std::bit_cast<uint64_t>(*r.max_overlap), v3.max_overlap_bits)
      << "max_overlap " << *r.max_overlap << " bits " << std::hex
      << std::bit_cast<uint64_t>(*r.max_overlap);
}

TEST_P(GoldenV3FirstTest, FitnessBitsAndFinalStateAreFixed) {
  ModelConfig config;
  config.physics.contact_rule = ContactRule::kUnjoined;
  config.physics.contact_stiffness = 200;
  config.physics.contact_damping = 0.5;
  config.physics.integrator = Integrator::kVelocityVerlet;
  config.physics.substeps = 2;
  ExpectGoldenV3(GetParam(), config);
}

TEST_P(GoldenV3K1500Test, FitnessBitsAndFinalStateAreFixed) {
  ModelConfig config;
  config.physics.contact_rule = ContactRule::kUnjoined;
  config.physics.contact_stiffness = 1500;
  config.physics.contact_damping = 0.5;
  config.physics.integrator = Integrator::kVelocityVerlet;
  config.physics.substeps = 4;
  ExpectGoldenV3(GetParam(), config);
}

TEST_P(GoldenDefaultTest, FitnessBitsAndFinalStateAreFixed) {
  ExpectGoldenV3(GetParam(), ModelConfig());
}

INSTANTIATE_TEST_SUITE_P(
    Genomes, GoldenRk4Test,
    ::testing::Values(Golden{"seed-1198.json", Precision::kFloat,
                             0x3fbecf821b14a83dull, 0x2278ae92b7c1e8d8ull},
                      Golden{"seed-1198.json", Precision::kDouble,
                             0x3fbecf7f71000c0full, 0x0b4791c522ae6497ull},
                      Golden{"seed-139.json", Precision::kFloat,
                             0x3e242dad5851e621ull, 0xd88d6d84e51586f4ull},
                      Golden{"seed-139.json", Precision::kDouble,
                             0x3e243d8f0199d074ull, 0x379475141da9ba33ull}));

INSTANTIATE_TEST_SUITE_P(
    Genomes, GoldenRalston3Test,
    ::testing::Values(Golden{"seed-1198.json", Precision::kFloat,
                             0x3fbeaa47b9299a91ull, 0x9fc1c0d8d2fe788eull},
                      Golden{"seed-1198.json", Precision::kDouble,
                             0x3fbeaa450b871f38ull, 0x68b61d0499b9eedbull},
                      Golden{"seed-139.json", Precision::kFloat,
                             0x3e2431dbeefb6b64ull, 0x8fff975d5c4c46bfull},
                      Golden{"seed-139.json", Precision::kDouble,
                             0x3e2441b81b71c39cull, 0x857f9c496b95312aull}));

INSTANTIATE_TEST_SUITE_P(
    Genomes, GoldenV3FirstTest,
    ::testing::Values(GoldenV3{{"seed-1198.json", Precision::kFloat,
                                0x3fbfb32bc7e27511ull, 0x0dd7177061c4e303ull},
                               0x3f4d878161c61400ull},
                      GoldenV3{{"seed-1198.json", Precision::kDouble,
                                0x3fbfb62d8b1f43a5ull, 0xc1deab9a70a9d9b1ull},
                               0x3f4ce87ace073c00ull},
                      // No two unjoined cells ever overlap.
                      GoldenV3{{"seed-139.json", Precision::kFloat,
                                0x3e23f7b5faf65ae9ull, 0xb2e0b2d649196303ull},
                               0},
                      GoldenV3{{"seed-139.json", Precision::kDouble,
                                0x3e24077315d36f1aull, 0x95a4efb56b4dbc2dull},
                               0}));

INSTANTIATE_TEST_SUITE_P(
    Genomes, GoldenV3K1500Test,
    ::testing::Values(GoldenV3{{"seed-1198.json", Precision::kFloat,
                                0x3fbfb20b14242186ull, 0x169cd337dc7e33e7ull},
                               0x3f2bbbc081390000ull},
                      GoldenV3{{"seed-1198.json", Precision::kDouble,
                                0x3fbfa8045bed3c4dull, 0xcd8c372596327d39ull},
                               0x3f242883ab382000ull},
                      // No two unjoined cells ever overlap.
                      GoldenV3{{"seed-139.json", Precision::kFloat,
                                0x3e241f6c799ebe9aull, 0x0045668f82fd1081ull},
                               0},
                      GoldenV3{{"seed-139.json", Precision::kDouble,
                                0x3e242f7d6af27d00ull, 0x2d2deefe0010587eull},
                               0}));

INSTANTIATE_TEST_SUITE_P(
    Genomes, GoldenDefaultTest,
    ::testing::Values(GoldenV3{{"seed-1198.json", Precision::kFloat,
                                0x3fbfb5e81220591eull, 0x383e247911934224ull},
                               0x3f23b214d9e8d000ull},
                      GoldenV3{{"seed-1198.json", Precision::kDouble,
                                0x3fbfa32d497883dcull, 0x3bad6af2de5dbaf3ull},
                               0x3f22825c8b02d000ull},
                      // No two unjoined cells ever overlap.
                      GoldenV3{{"seed-139.json", Precision::kFloat,
                                0x3e241f6c799ebe9aull, 0x0045668f82fd1081ull},
                               0},
                      GoldenV3{{"seed-139.json", Precision::kDouble,
                                0x3e242f7d6af27d00ull, 0x2d2deefe0010587eull},
                               0}));

// Under model v2 the chamber rule changes nothing for a body with chambers:
// the same bits as with min_chambers 0.
TEST(GoldenTest, ChamberRuleLeavesChamberedBodiesBitIdentical) {
  v1::Genome message;
  ASSERT_TRUE(
      ReadProtoFile(testing::TestData("genomes/seed-1198.json"), &message)
          .ok());
  Result<Genome> genome = GenomeFromProto(message);
  ASSERT_TRUE(genome.ok());
  ModelConfig with_rule = ModelV2();
  ModelConfig without_rule = ModelV2();
  without_rule.evaluation.min_chambers = 0;
  const EvaluationResult a = Evaluate(*genome, with_rule);
  const EvaluationResult b = Evaluate(*genome, without_rule);
  ASSERT_EQ(a.status, EvalStatus::kOk) << a.reason;
  ASSERT_EQ(b.status, EvalStatus::kOk) << b.reason;
  EXPECT_EQ(std::bit_cast<uint64_t>(*a.fitness),
            std::bit_cast<uint64_t>(*b.fitness));
  EXPECT_EQ(a.state_hash, b.state_hash);
}

INSTANTIATE_TEST_SUITE_P(
    Genomes, GoldenTest,
    ::testing::Values(
        // A 32-cell body with 40 chambers (the benchmark genome).
        Golden{"seed-1198.json", Precision::kDouble, 0x3fbba73be0ef9f5eull,
               0xc9385f269eba3b50ull},
        // A chain of 32 cells (no chambers), the best random mover.
        Golden{"seed-1203.json", Precision::kDouble, 0x40008b7cce86237eull,
               0x3c32a0c09749ca88ull},
        // A compact body that barely moves (fitness ~1.6e-9).
        Golden{"seed-139.json", Precision::kDouble, 0x3e1b71602ce579ccull,
               0x7f3c6cee70ea41a1ull},
        // Single-precision network arithmetic.
        Golden{"seed-1198.json", Precision::kFloat, 0x3fbba73efa17ef20ull,
               0xafef83c87623ea05ull},
        Golden{"seed-1203.json", Precision::kFloat, 0x40008b6e86b32e98ull,
               0x238bf96f27d95dcfull}));

}  // namespace
}  // namespace animat
