// The genetic algorithm's configuration (master/evolution/evolution_params.h)
// and configs/paper.txtpb.
#include "master/evolution/evolution_params.h"

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "common/io/proto_file.h"
#include "tests/test_util.h"

namespace animat {
namespace {

std::string ConfigsDir() { return std::string(ANIMAT_SOURCE_DIR) + "/configs"; }

std::string Text(const EvolutionParams& p) {
  return SerializeProto(EvolutionParamsToProto(p), ProtoFormat::kText);
}

std::string Text(const RunSettings& s) {
  return SerializeProto(RunSettingsToProto(s), ProtoFormat::kText);
}

TEST(EvolutionParamsTest, DefaultsAreTheDocumentedValues) {
  const EvolutionParams p;
  EXPECT_EQ(p.seed, 1u);
  EXPECT_EQ(p.population, 300);
  EXPECT_EQ(p.generations, 100);
  EXPECT_EQ(p.elite, 3);
  EXPECT_EQ(p.tournament_size, 3);
  EXPECT_EQ(p.crossover_fraction, 0.2);
  EXPECT_EQ(p.crossover_points, 2);
  EXPECT_EQ(p.mutation.type_rate, 0.01);
  EXPECT_EQ(p.mutation.sign_rate, 0.01);
  EXPECT_EQ(p.mutation.coordinate_rate, 0.05);
  EXPECT_EQ(p.mutation.coordinate_sigma, 0.5);
  EXPECT_EQ(p.mutation.duplication_rate, 0.05);
  EXPECT_EQ(p.mutation.deletion_rate, 0.05);
  EXPECT_EQ(p.mutation.max_run_length, 4);
  EXPECT_EQ(p.initial_units, 10);
  EXPECT_EQ(p.initial_min_fitness, 1e-6);
  EXPECT_EQ(p.max_elements, 1000);
}

TEST(EvolutionParamsTest, EmptyMessageKeepsDefaults) {
  EvolutionParams p;
  ASSERT_TRUE(EvolutionParamsFromProto(v1::EvolutionConfig(), &p).ok());
  EXPECT_EQ(Text(p), Text(EvolutionParams{}));
}

TEST(EvolutionParamsTest, PresentFieldsOverrideAbsentOnesKeep) {
  v1::EvolutionConfig m;
  m.set_population(50);
  m.mutable_mutation()->set_sign_rate(0.25);
  EvolutionParams p;
  ASSERT_TRUE(EvolutionParamsFromProto(m, &p).ok());
  EXPECT_EQ(p.population, 50);
  EXPECT_EQ(p.mutation.sign_rate, 0.25);
  EXPECT_EQ(p.elite, 3);
  EXPECT_EQ(p.mutation.type_rate, 0.01);
}

TEST(EvolutionParamsTest, ToProtoSetsEveryField) {
  const v1::EvolutionConfig m = EvolutionParamsToProto(EvolutionParams{});
  EXPECT_TRUE(m.has_seed() && m.has_population() && m.has_generations() &&
              m.has_elite() && m.has_tournament_size() &&
              m.has_crossover_fraction() && m.has_crossover_points() &&
              m.has_mutation() && m.has_initial_units() &&
              m.has_initial_min_fitness() && m.has_max_elements());
  const v1::MutationConfig& u = m.mutation();
  EXPECT_TRUE(u.has_type_rate() && u.has_sign_rate() &&
              u.has_coordinate_rate() && u.has_coordinate_sigma() &&
              u.has_duplication_rate() && u.has_deletion_rate() &&
              u.has_max_run_length());
}

TEST(EvolutionParamsTest, RoundTripsThroughProto) {
  EvolutionParams p;
  p.seed = 0xFEEDFACECAFEBEEFull;
  p.population = 40;
  p.generations = 7;
  p.elite = 39;
  p.tournament_size = 9;
  p.crossover_fraction = 1.0;
  p.crossover_points = 5;
  p.mutation.type_rate = 0.125;
  p.mutation.sign_rate = 0.0;
  p.mutation.coordinate_rate = 1.0;
  p.mutation.coordinate_sigma = 0.0;
  p.mutation.duplication_rate = 0.3;
  p.mutation.deletion_rate = 0.7;
  p.mutation.max_run_length = 12;
  p.initial_units = 4;
  p.initial_min_fitness = 0.0;
  p.max_elements = 10000;
  EvolutionParams back;
  ASSERT_TRUE(EvolutionParamsFromProto(EvolutionParamsToProto(p), &back).ok());
  EXPECT_EQ(Text(back), Text(p));
  EXPECT_EQ(back.seed, p.seed);
}

// The invalid value is rejected with a message starting with its field,
// and the params are left unchanged.
void ExpectRejected(const std::function<void(v1::EvolutionConfig*)>& set,
                    const std::string& field) {
  testing::FpTrapsOff traps_off;
  v1::EvolutionConfig m;
  set(&m);
  EvolutionParams p;
  p.population = 77;  // Not a default, to see that nothing is overwritten.
  const std::string before = Text(p);
  const Status status = EvolutionParamsFromProto(m, &p);
  ASSERT_FALSE(status.ok()) << field;
  EXPECT_EQ(status.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(status.message().rfind(field + ": ", 0), 0u)
      << status.message() << " should start with " << field;
  EXPECT_EQ(Text(p), before) << field;
}

TEST(EvolutionParamsTest, RejectsInvalidValuesNamingTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using M = v1::EvolutionConfig*;
  ExpectRejected([](M m) { m->set_population(1); }, "evolution.population");
  ExpectRejected([](M m) { m->set_population(-300); }, "evolution.population");
  ExpectRejected([](M m) { m->set_generations(0); }, "evolution.generations");
  ExpectRejected([](M m) { m->set_elite(-1); }, "evolution.elite");
  ExpectRejected([](M m) { m->set_elite(77); }, "evolution.elite");
  ExpectRejected(
      [](M m) {
        m->set_population(10);
        m->set_elite(10);
      },
      "evolution.elite");
  ExpectRejected([](M m) { m->set_tournament_size(0); },
                 "evolution.tournament_size");
  ExpectRejected([](M m) { m->set_crossover_fraction(-0.1); },
                 "evolution.crossover_fraction");
  ExpectRejected([](M m) { m->set_crossover_fraction(1.5); },
                 "evolution.crossover_fraction");
  ExpectRejected([&](M m) { m->set_crossover_fraction(nan); },
                 "evolution.crossover_fraction");
  ExpectRejected([](M m) { m->set_crossover_points(0); },
                 "evolution.crossover_points");
  ExpectRejected([](M m) { m->set_crossover_points(10001); },
                 "evolution.crossover_points");
  ExpectRejected([](M m) { m->set_tournament_size(10001); },
                 "evolution.tournament_size");
  // Each rate must be in [0, 1].
  const std::vector<
      std::pair<std::string, void (v1::MutationConfig::*)(double)>>
      rates = {
          {"type_rate", &v1::MutationConfig::set_type_rate},
          {"sign_rate", &v1::MutationConfig::set_sign_rate},
          {"coordinate_rate", &v1::MutationConfig::set_coordinate_rate},
          {"duplication_rate", &v1::MutationConfig::set_duplication_rate},
          {"deletion_rate", &v1::MutationConfig::set_deletion_rate},
      };
  for (const auto& [name, setter] : rates) {
    for (double bad : {-0.01, 1.01, nan, inf}) {
      ExpectRejected([&](M m) { (m->mutable_mutation()->*setter)(bad); },
                     "evolution.mutation." + name);
    }
  }
  for (double bad : {-0.5, nan, inf, 2e6}) {
    ExpectRejected(
        [&](M m) { m->mutable_mutation()->set_coordinate_sigma(bad); },
        "evolution.mutation.coordinate_sigma");
  }
  ExpectRejected([](M m) { m->mutable_mutation()->set_max_run_length(0); },
                 "evolution.mutation.max_run_length");
  ExpectRejected([](M m) { m->set_initial_units(0); },
                 "evolution.initial_units");
  ExpectRejected([](M m) { m->set_initial_units(5000); },
                 "evolution.initial_units");
  for (double bad : {-1e-9, nan, inf}) {
    ExpectRejected([&](M m) { m->set_initial_min_fitness(bad); },
                   "evolution.initial_min_fitness");
  }
  ExpectRejected([](M m) { m->set_max_elements(0); }, "evolution.max_elements");
  ExpectRejected([](M m) { m->set_max_elements(10001); },
                 "evolution.max_elements");
}

TEST(EvolutionParamsTest, ErrorsSayTheRangeAndTheValue) {
  v1::EvolutionConfig m;
  m.set_elite(400);
  EvolutionParams p;
  const Status status = EvolutionParamsFromProto(m, &p);
  EXPECT_EQ(status.message(), "evolution.elite: must be in [0, 299], got 400");
}

TEST(EvolutionParamsTest, AcceptsTheEdgesOfEachRange) {
  v1::EvolutionConfig m;
  m.set_population(2);
  m.set_generations(1);
  m.set_elite(1);
  m.set_tournament_size(1);
  m.set_crossover_fraction(0.0);
  m.set_crossover_points(1);
  m.mutable_mutation()->set_type_rate(1.0);
  m.mutable_mutation()->set_coordinate_sigma(0.0);
  m.mutable_mutation()->set_max_run_length(1);
  m.set_initial_units(1);
  m.set_initial_min_fitness(0.0);
  m.set_max_elements(1);
  EvolutionParams p;
  const Status status = EvolutionParamsFromProto(m, &p);
  EXPECT_TRUE(status.ok()) << status.ToString();
  m.set_max_elements(10000);
  m.set_initial_units(4995);  // 2 * 4995 + 10 = 10000 elements.
  m.set_tournament_size(10000);
  m.set_crossover_points(10000);
  EXPECT_TRUE(EvolutionParamsFromProto(m, &p).ok());
}

TEST(RunSettingsTest, ModelErrorsNameTheModelField) {
  v1::RunConfig m;
  m.mutable_model()->mutable_physics()->set_mass(-1.0);
  m.mutable_evolution()->set_population(10);
  RunSettings s;
  const std::string before = Text(s);
  const Status status = RunSettingsFromProto(m, &s);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind("physics.mass: ", 0), 0u)
      << status.message();
  EXPECT_EQ(Text(s), before);

  m.Clear();
  m.mutable_evolution()->set_tournament_size(0);
  m.mutable_model()->mutable_physics()->set_mass(2.0);
  const Status evolution_status = RunSettingsFromProto(m, &s);
  ASSERT_FALSE(evolution_status.ok());
  EXPECT_EQ(evolution_status.message().rfind("evolution.tournament_size: ", 0),
            0u);
  EXPECT_EQ(Text(s), before);
}

TEST(RunSettingsTest, RoundTripsThroughProto) {
  RunSettings s;
  s.model.physics.stiffness = 12.5;
  s.model.evaluation.motion_steps = 300;
  s.evolution.population = 20;
  s.evolution.mutation.deletion_rate = 0.5;
  RunSettings back;
  ASSERT_TRUE(RunSettingsFromProto(RunSettingsToProto(s), &back).ok());
  EXPECT_EQ(Text(back), Text(s));
}

TEST(RunSettingsTest, ReadRunConfigFileNamesTheFileAndField) {
  const std::string path = ::testing::TempDir() + "/bad-run.txtpb";
  ASSERT_TRUE(WriteFile(path, "evolution { elite: 400 }\n").ok());
  Result<RunSettings> settings = ReadRunConfigFile(path);
  ASSERT_FALSE(settings.ok());
  EXPECT_EQ(settings.status().message().rfind(path + ": evolution.elite", 0),
            0u)
      << settings.status().message();

  const std::string json = ::testing::TempDir() + "/run.json";
  ASSERT_TRUE(
      WriteFile(json, R"({"evolution": {"population": 12, "elite": 2}})").ok());
  Result<RunSettings> read = ReadRunConfigFile(json);
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->evolution.population, 12);
  EXPECT_EQ(read->evolution.elite, 2);

  EXPECT_FALSE(ReadRunConfigFile(::testing::TempDir() + "/missing.txtpb").ok());
}

// Guidance (docs/model.md §10.2) lets the run's genomes carry the CHEMICAL
// channel; without it every draw is the paper's.
TEST(RunSettingsTest, GuidanceEnablesTheChemicalChannel) {
  RunSettings paper;
  ASSERT_TRUE(RunSettingsFromProto(v1::RunConfig(), &paper).ok());
  EXPECT_FALSE(paper.evolution.chemical_input);
  EXPECT_EQ(paper.evolution.mutation.input_channels, kPaperInputChannels);
  v1::RunConfig m;
  m.mutable_model()->mutable_guidance()->set_enabled(true);
  RunSettings guided;
  ASSERT_TRUE(RunSettingsFromProto(m, &guided).ok());
  EXPECT_TRUE(guided.evolution.chemical_input);
  EXPECT_EQ(guided.evolution.mutation.input_channels, kInputChannels);
  // One more element: 2 * 4995 + 11 is beyond the genome limit.
  m.mutable_evolution()->set_initial_units(4995);
  const Status status = RunSettingsFromProto(m, &guided);
  EXPECT_EQ(status.message().rfind("evolution.initial_units:", 0), 0u)
      << status.message();
  m.mutable_evolution()->set_initial_units(4994);
  EXPECT_TRUE(RunSettingsFromProto(m, &guided).ok());
}

TEST(GuidanceConfigTest, ReadsAsAGuidanceRun) {
  Result<RunSettings> settings =
      ReadRunConfigFile(ConfigsDir() + "/guidance.txtpb");
  ASSERT_TRUE(settings.ok()) << settings.status().ToString();
  EXPECT_TRUE(settings->model.guidance.enabled);
  EXPECT_EQ(settings->model.guidance.trials, 4);
  EXPECT_TRUE(settings->evolution.chemical_input);
  EXPECT_EQ(settings->evolution.mutation.input_channels, kInputChannels);
}

// The guidance arm of the third replication differs from the guidance runs
// by the lead only.
TEST(GuidanceConfigTest, TheLeadArmIsTheGuidanceRunsWithALead) {
  Result<RunSettings> settings =
      ReadRunConfigFile(ConfigsDir() + "/guidance-lead.txtpb");
  ASSERT_TRUE(settings.ok()) << settings.status().ToString();
  Result<RunSettings> expected =
      ReadRunConfigFile(ConfigsDir() + "/guidance.txtpb");
  ASSERT_TRUE(expected.ok());
  expected->model.guidance.lead_steps = 200;
  EXPECT_EQ(Text(*settings), Text(*expected));
}

TEST(EnergyConfigTest, IsTheReplicationsDn1RunWithTheEnergyBudget) {
  Result<RunSettings> settings =
      ReadRunConfigFile(ConfigsDir() + "/energy.txtpb");
  ASSERT_TRUE(settings.ok()) << settings.status().ToString();
  // The replication's d_N = 1 runs (configs/paper.txtpb with RK4, the
  // integrator they used) for 150 generations, but for the fitness.
  Result<RunSettings> expected =
      ReadRunConfigFile(ConfigsDir() + "/paper.txtpb");
  ASSERT_TRUE(expected.ok());
  expected->model.physics.drag_normal = 1.0;
  expected->model.physics.drag_tangential = 0.005;
  expected->model.physics.integrator = Integrator::kRk4;
  expected->model.physics.substeps = 1;
  expected->model.physics.contact_rule = ContactRule::kNone;  // Model v2.
  expected->evolution.generations = 150;
  expected->model.evaluation.fitness = FitnessKind::kDistanceWithinEnergyBudget;
  expected->model.evaluation.energy_budget = 10000.0;
  EXPECT_EQ(Text(*settings), Text(*expected));
  // The model its second-edition runs ran, as their kept best records it.
  Result<ModelConfig> ran = ReadConfigFile(
      ConfigsDir() +
      "/../docs/results/bests/energy-dn1-seed1-132270.config.txtpb");
  ASSERT_TRUE(ran.ok()) << ran.status().ToString();
  EXPECT_EQ(SerializeProto(ConfigToProto(settings->model), ProtoFormat::kText),
            SerializeProto(ConfigToProto(*ran), ProtoFormat::kText));
}

// The holding arm differs from the energy runs by the holding cost only.
TEST(EnergyConfigTest, TheHoldingArmIsTheEnergyRunsWithAHoldingCost) {
  Result<RunSettings> settings =
      ReadRunConfigFile(ConfigsDir() + "/energy-holding.txtpb");
  ASSERT_TRUE(settings.ok()) << settings.status().ToString();
  Result<RunSettings> expected =
      ReadRunConfigFile(ConfigsDir() + "/energy.txtpb");
  ASSERT_TRUE(expected.ok());
  expected->model.evaluation.holding_cost = 0.05;
  EXPECT_EQ(Text(*settings), Text(*expected));
}

TEST(PaperConfigTest, ReadsAsThePapersSetup) {
  Result<RunSettings> settings =
      ReadRunConfigFile(ConfigsDir() + "/paper.txtpb");
  ASSERT_TRUE(settings.ok()) << settings.status().ToString();
  EXPECT_EQ(settings->evolution.population, 300);
  EXPECT_EQ(settings->evolution.crossover_fraction, 0.2);
  EXPECT_EQ(settings->evolution.initial_units, 10);
  EXPECT_EQ(settings->evolution.initial_min_fitness, 1e-6);
  // The model at its defaults; the genetic algorithm at the built-in
  // defaults, every field of it written out.
  EXPECT_EQ(Text(*settings), Text(RunSettings{}));
  v1::RunConfig message;
  ASSERT_TRUE(ReadProtoFile(ConfigsDir() + "/paper.txtpb", &message).ok());
  EXPECT_EQ(message.evolution().ByteSizeLong(),
            EvolutionParamsToProto(EvolutionParams{}).ByteSizeLong());
}

}  // namespace
}  // namespace animat
