// protocol::ValidateResult: what the master refuses in a worker's result
// before it can reach the lineage store, the body summary included.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "animat/v1/trace.pb.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/protocol/protocol.h"
#include "tests/test_util.h"

namespace animat {
namespace {

// An OK result with a plausible body.
v1::EvaluationResult OkWithBody() {
  v1::EvaluationResult r;
  r.set_status(v1::EvaluationResult::OK);
  r.set_fitness(0.5);
  r.set_cells(32);
  v1::BodySummary* b = r.mutable_body();
  b->set_cells(32);
  b->set_springs(75);
  b->set_chambers(12);
  b->set_skin_edges(18);
  b->set_spread_major(2.5);
  b->set_spread_minor(1.25);
  return r;
}

std::string Refusal(const v1::EvaluationResult& r) {
  const Status status = protocol::ValidateResult(r);
  EXPECT_FALSE(status.ok());
  return status.message();
}

TEST(ValidateResultTest, AcceptsAResultWithOrWithoutABody) {
  v1::EvaluationResult r = OkWithBody();
  EXPECT_TRUE(protocol::ValidateResult(r).ok());
  r.clear_body();
  EXPECT_TRUE(protocol::ValidateResult(r).ok());
  // A straight chain: no chamber, no minor spread.
  v1::EvaluationResult chain;
  chain.set_status(v1::EvaluationResult::DEGENERATE_BODY);
  chain.set_reason("no chamber: the body encloses no area");
  chain.mutable_body()->set_cells(4);
  chain.mutable_body()->set_springs(3);
  chain.mutable_body()->set_spread_major(1.118);
  EXPECT_TRUE(protocol::ValidateResult(chain).ok());
}

TEST(ValidateResultTest, AcceptsWhatAnEvaluationReports) {
  v1::Genome message;
  ASSERT_TRUE(
      ReadProtoFile(testing::TestData("genomes/seed-1198.json"), &message)
          .ok());
  Result<Genome> genome = GenomeFromProto(message);
  ASSERT_TRUE(genome.ok());
  ModelConfig config;
  config.evaluation.motion_steps = 50;
  const v1::EvaluationResult r =
      EvaluationResultToProto(Evaluate(*genome, config));
  ASSERT_TRUE(r.has_body());
  EXPECT_GT(r.body().chambers(), 0);
  const Status status = protocol::ValidateResult(r);
  EXPECT_TRUE(status.ok()) << status.ToString();
}

// A guidance result (docs/model.md §10.2): its fitness may be negative,
// and its per-trial distances are bounded, finite and >= 0.
TEST(ValidateResultTest, GuidanceResultsMayScoreBelowZero) {
  static_assert(protocol::kMaxSourceDistances >= kMaxGuidanceTrials);
  v1::EvaluationResult r = OkWithBody();
  r.set_fitness(-2.5);
  EXPECT_EQ(Refusal(r), "fitness -2.5");  // Not a guidance result.
  r.add_source_distances(31.0);
  r.add_source_distances(34.0);
  EXPECT_TRUE(protocol::ValidateResult(r).ok());
  r.set_source_distances(1, -1.0);
  EXPECT_EQ(Refusal(r), "source distance -1");
  {
    testing::FpTrapsOff traps_off;
    r.set_source_distances(1, std::numeric_limits<double>::quiet_NaN());
    EXPECT_EQ(Refusal(r).rfind("source distance ", 0), 0u);
    r.set_fitness(std::numeric_limits<double>::infinity());
    r.set_source_distances(1, 34.0);
    EXPECT_EQ(Refusal(r).rfind("fitness ", 0), 0u);
  }
  r.set_fitness(1.0);
  r.clear_source_distances();
  for (int k = 0; k <= protocol::kMaxSourceDistances; ++k) {
    r.add_source_distances(30.0);
  }
  EXPECT_NE(Refusal(r).find("more than 64"), std::string::npos);
  v1::EvaluationResult failed;
  failed.set_status(v1::EvaluationResult::NUMERICAL_FAILURE);
  failed.add_source_distances(30.0);
  EXPECT_EQ(Refusal(failed), "source distances without status OK");
}

TEST(ValidateResultTest, RefusesNegativeCountsNamingThem) {
  v1::EvaluationResult r = OkWithBody();
  r.mutable_body()->set_cells(-1);
  EXPECT_EQ(Refusal(r), "body cells -1");
  r = OkWithBody();
  r.mutable_body()->set_springs(-2);
  EXPECT_EQ(Refusal(r), "body springs -2");
  r = OkWithBody();
  r.mutable_body()->set_chambers(std::numeric_limits<int32_t>::min());
  EXPECT_EQ(Refusal(r), "body chambers -2147483648");
  r = OkWithBody();
  r.mutable_body()->set_skin_edges(-4);
  EXPECT_EQ(Refusal(r), "body skin_edges -4");
}

TEST(ValidateResultTest, RefusesSpreadsThatAreNotFiniteNonNegativeAndOrdered) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  v1::EvaluationResult r = OkWithBody();
  r.mutable_body()->set_spread_major(nan);
  EXPECT_EQ(Refusal(r), "body spread_major nan");
  r = OkWithBody();
  r.mutable_body()->set_spread_major(inf);
  EXPECT_EQ(Refusal(r), "body spread_major inf");
  r = OkWithBody();
  r.mutable_body()->set_spread_minor(-inf);
  EXPECT_EQ(Refusal(r), "body spread_minor -inf");
  r = OkWithBody();
  r.mutable_body()->set_spread_minor(-0.5);
  EXPECT_EQ(Refusal(r), "body spread_minor -0.5");
  r = OkWithBody();
  r.mutable_body()->set_spread_minor(3.0);
  EXPECT_EQ(Refusal(r), "body spread_minor 3 above spread_major 2.5");
}

TEST(ValidateResultTest, RefusesADistanceOrEnergyNotFiniteNonNegativeOrNotOk) {
  v1::EvaluationResult r = OkWithBody();
  r.set_distance(0.5);
  r.set_energy(0.0);
  EXPECT_TRUE(protocol::ValidateResult(r).ok());
  r.set_energy(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(Refusal(r), "energy nan");
  r.set_energy(12.5);
  r.set_distance(-1.0);
  EXPECT_EQ(Refusal(r), "distance -1");
  r.set_distance(std::numeric_limits<double>::infinity());
  EXPECT_EQ(Refusal(r), "distance inf");
  r = OkWithBody();
  r.set_status(v1::EvaluationResult::NUMERICAL_FAILURE);
  r.clear_fitness();
  r.set_energy(1.0);
  EXPECT_EQ(Refusal(r), "energy present without status OK");
}

TEST(ValidateResultTest, RefusesAnOverlapOutsideTheUnitIntervalOrNotOk) {
  v1::EvaluationResult r = OkWithBody();
  for (const double fine : {0.0, 0.25, 1.0}) {
    r.set_max_overlap(fine);
    EXPECT_TRUE(protocol::ValidateResult(r).ok()) << fine;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  r.set_max_overlap(nan);
  EXPECT_EQ(Refusal(r), "max_overlap nan outside [0, 1]");
  r.set_max_overlap(inf);
  EXPECT_EQ(Refusal(r), "max_overlap inf outside [0, 1]");
  r.set_max_overlap(-0.01);
  EXPECT_EQ(Refusal(r), "max_overlap -0.01 outside [0, 1]");
  r.set_max_overlap(1.5);
  EXPECT_EQ(Refusal(r), "max_overlap 1.5 outside [0, 1]");
  r = OkWithBody();
  r.set_status(v1::EvaluationResult::NUMERICAL_FAILURE);
  r.clear_fitness();
  r.set_max_overlap(0.5);
  EXPECT_EQ(Refusal(r), "max_overlap present without status OK");
}

TEST(ValidateResultTest, ABadBodyIsRefusedWhateverTheStatus) {
  v1::EvaluationResult r = OkWithBody();
  r.set_status(v1::EvaluationResult::NUMERICAL_FAILURE);
  r.clear_fitness();
  r.mutable_body()->set_spread_major(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(Refusal(r), "body spread_major nan");
}

}  // namespace
}  // namespace animat
