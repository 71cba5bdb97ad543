#include "common/evaluation/model_config.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/io/proto_file.h"
#include "tests/test_util.h"

namespace animat {
namespace {

std::string ConfigsDir() { return std::string(ANIMAT_SOURCE_DIR) + "/configs"; }

TEST(ModelConfigTest, DefaultFileEqualsBuiltInDefaults) {
  Result<ModelConfig> config = ReadConfigFile(ConfigsDir() + "/default.txtpb");
  ASSERT_TRUE(config.ok()) << config.status().ToString();
  const std::string from_file =
      SerializeProto(ConfigToProto(*config), ProtoFormat::kText);
  const std::string built_in =
      SerializeProto(ConfigToProto(ModelConfig{}), ProtoFormat::kText);
  EXPECT_EQ(from_file, built_in);
}

TEST(ModelConfigTest, DefaultFileSetsEveryField) {
  v1::Config message;
  ASSERT_TRUE(ReadProtoFile(ConfigsDir() + "/default.txtpb", &message).ok());
  // ConfigToProto sets every field; the file must too, so that it documents
  // all of them.
  const v1::Config full = ConfigToProto(ModelConfig{});
  EXPECT_EQ(message.ByteSizeLong(), full.ByteSizeLong());
}

TEST(ModelConfigTest, DefaultsAreModelValues) {
  const ModelConfig c;
  EXPECT_EQ(c.grn.weight_max, 10.0);
  EXPECT_EQ(c.grn.decay_length, 1.0);
  EXPECT_EQ(c.grn.cutoff, 3.0);
  EXPECT_EQ(c.grn.dt, 0.05);
  EXPECT_EQ(c.physics.mass, 1.0);
  EXPECT_EQ(c.physics.stiffness, 10.0);
  EXPECT_EQ(c.physics.damping, 0.5);
  EXPECT_EQ(c.physics.pressure, 10.0);
  EXPECT_EQ(c.physics.drag_normal, 1.0);
  EXPECT_EQ(c.physics.drag_tangential, 1.0 / 200.0);
  EXPECT_EQ(c.physics.dt, 0.05);
  EXPECT_EQ(c.physics.actuation_max, 0.2);
  EXPECT_EQ(c.physics.min_rest_fraction, 0.1);
  EXPECT_EQ(c.evaluation.equilibration_steps, 200);
  EXPECT_EQ(c.evaluation.equilibration_damping, 0.9);
  EXPECT_EQ(c.evaluation.motion_steps, 6000);
  EXPECT_EQ(c.evaluation.max_coordinate, 1e6);
  EXPECT_EQ(c.evaluation.check_interval, 100);
  EXPECT_EQ(c.evaluation.fitness, FitnessKind::kDistance);
  EXPECT_EQ(c.evaluation.energy_budget, 10000.0);
  EXPECT_FALSE(c.guidance.enabled);
  EXPECT_EQ(c.guidance.trials, 4);
  EXPECT_EQ(c.guidance.source_distance, 30.0);
  EXPECT_EQ(c.guidance.decay_length, 10.0);
}

TEST(ModelConfigTest, AbsentFieldsKeepDefaultsAndPresentOnesOverride) {
  v1::Config message;
  message.mutable_physics()->set_stiffness(20.0);
  message.mutable_evaluation()->set_motion_steps(100);
  ModelConfig config;
  ASSERT_TRUE(ConfigFromProto(message, &config).ok());
  EXPECT_EQ(config.physics.stiffness, 20.0);
  EXPECT_EQ(config.evaluation.motion_steps, 100);
  EXPECT_EQ(config.physics.mass, 1.0);
  EXPECT_EQ(config.development.steps, 400);
}

TEST(ModelConfigTest, RoundTripsThroughProto) {
  ModelConfig config;
  config.physics.pressure = 3.5;
  config.signals.max_delay = 17;
  config.development.size_gain = 0.25;
  config.evaluation.fitness = FitnessKind::kDistanceWithinEnergyBudget;
  config.evaluation.energy_budget = 123.5;
  ModelConfig back;
  ASSERT_TRUE(ConfigFromProto(ConfigToProto(config), &back).ok());
  EXPECT_EQ(SerializeProto(ConfigToProto(back), ProtoFormat::kText),
            SerializeProto(ConfigToProto(config), ProtoFormat::kText));
  config = ModelConfig{};
  config.guidance.enabled = true;
  config.guidance.trials = 7;
  config.guidance.source_distance = 12.5;
  config.guidance.decay_length = 3.25;
  ASSERT_TRUE(ConfigFromProto(ConfigToProto(config), &back).ok());
  EXPECT_EQ(SerializeProto(ConfigToProto(back), ProtoFormat::kText),
            SerializeProto(ConfigToProto(config), ProtoFormat::kText));
}

// Each invalid value is rejected, the message naming its field, and the
// config is left unchanged.
void ExpectRejected(const v1::Config& message, const std::string& field) {
  ModelConfig config;
  const std::string before =
      SerializeProto(ConfigToProto(config), ProtoFormat::kText);
  Status status = ConfigFromProto(message, &config);
  ASSERT_FALSE(status.ok()) << field;
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(status.message().rfind(field + ":", 0), 0u)
      << status.message() << " should start with " << field;
  EXPECT_EQ(SerializeProto(ConfigToProto(config), ProtoFormat::kText), before);
}

TEST(ModelConfigTest, RejectsInvalidConstantsNamingTheField) {
  testing::FpTrapsOff traps_off;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  v1::Config m;
  m.mutable_physics()->set_mass(-1.0);
  ExpectRejected(m, "physics.mass");
  m.Clear();
  m.mutable_physics()->set_mass(0.0);
  ExpectRejected(m, "physics.mass");
  m.Clear();
  m.mutable_physics()->set_actuation_max(0.5);
  ExpectRejected(m, "physics.actuation_max");
  m.Clear();
  m.mutable_physics()->set_actuation_max(-0.1);
  ExpectRejected(m, "physics.actuation_max");
  m.Clear();
  m.mutable_physics()->set_dt(0.0);
  ExpectRejected(m, "physics.dt");
  m.Clear();
  m.mutable_physics()->set_dt(-0.05);
  ExpectRejected(m, "physics.dt");
  m.Clear();
  m.mutable_grn()->set_dt(0.0);
  ExpectRejected(m, "grn.dt");
  m.Clear();
  m.mutable_physics()->set_stiffness(nan);
  ExpectRejected(m, "physics.stiffness");
  m.Clear();
  m.mutable_grn()->set_cutoff(std::numeric_limits<double>::infinity());
  ExpectRejected(m, "grn.cutoff");
  m.Clear();
  m.mutable_signals()->set_kernel_length(nan);
  ExpectRejected(m, "signals.kernel_length");
  m.Clear();
  m.mutable_development()->set_mechanics_dt(nan);
  ExpectRejected(m, "development.mechanics_dt");
  m.Clear();
  m.mutable_evaluation()->set_equilibration_damping(1.5);
  ExpectRejected(m, "evaluation.equilibration_damping");
  m.Clear();
  m.mutable_evaluation()->set_check_interval(0);
  ExpectRejected(m, "evaluation.check_interval");
  m.Clear();
  m.mutable_evaluation()->set_max_coordinate(nan);
  ExpectRejected(m, "evaluation.max_coordinate");
  m.Clear();
  m.mutable_evaluation()->set_energy_budget(0.0);
  ExpectRejected(m, "evaluation.energy_budget");
  m.Clear();
  m.mutable_evaluation()->set_fitness(
      static_cast<v1::EvaluationConfig::Fitness>(99));
  ExpectRejected(m, "evaluation.fitness");
  m.Clear();
  m.mutable_guidance()->set_trials(0);
  ExpectRejected(m, "guidance.trials");
  m.Clear();
  m.mutable_guidance()->set_trials(kMaxGuidanceTrials + 1);
  ExpectRejected(m, "guidance.trials");
  m.Clear();
  m.mutable_guidance()->set_source_distance(0.0);
  ExpectRejected(m, "guidance.source_distance");
  m.Clear();
  m.mutable_guidance()->set_source_distance(nan);
  ExpectRejected(m, "guidance.source_distance");
  m.Clear();
  m.mutable_guidance()->set_decay_length(-1.0);
  ExpectRejected(m, "guidance.decay_length");
  m.Clear();
  m.mutable_guidance()->set_decay_length(
      std::numeric_limits<double>::infinity());
  ExpectRejected(m, "guidance.decay_length");
}

TEST(ModelConfigTest, GuidanceNeedsTheDistanceFitness) {
  v1::Config m;
  m.mutable_guidance()->set_enabled(true);
  m.mutable_evaluation()->set_fitness(
      v1::EvaluationConfig::DISTANCE_WITHIN_ENERGY_BUDGET);
  ExpectRejected(m, "guidance.enabled");
  m.mutable_evaluation()->set_fitness(v1::EvaluationConfig::DISTANCE);
  ModelConfig config;
  ASSERT_TRUE(ConfigFromProto(m, &config).ok());
  EXPECT_TRUE(config.guidance.enabled);
  EXPECT_EQ(config.guidance.trials, 4);
}

TEST(ModelConfigTest, ReadConfigFileNamesTheFileAndField) {
  const std::string path = ::testing::TempDir() + "/bad-config.txtpb";
  ASSERT_TRUE(WriteFile(path, "physics { mass: -2 }\n").ok());
  Result<ModelConfig> config = ReadConfigFile(path);
  ASSERT_FALSE(config.ok());
  EXPECT_NE(config.status().message().find(path), std::string::npos);
  EXPECT_NE(config.status().message().find("physics.mass"), std::string::npos);
}

}  // namespace
}  // namespace animat
