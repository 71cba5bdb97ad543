// Knock-outs (docs/analysis.md, "Knock-outs"): an input silenced during
// motion only, and the report of `animat analyze --knockouts`.
#include <gtest/gtest.h>

#include <bit>
#include <string>
#include <vector>

#include "common/base/hash.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/knockout.h"
#include "common/genome/genome_proto.h"
#include "common/grn/network.h"
#include "common/io/proto_file.h"
#include "tests/genome_builder.h"
#include "tests/test_genome.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using testing::GInt;
using testing::GMor;
using testing::In;
using testing::P;

using testing::LoadGenome;

// seed-1203, the best random mover: a chain of 32 cells with three
// morphogens of its own. Its EXPAND output is element 7.
Genome Swimmer() { return LoadGenome("seed-1203.json"); }

const Element& ExpandOutput(const Genome& genome) {
  const Element& expand = genome.elements[7];
  EXPECT_EQ(expand.type, ElementType::kSOut);
  EXPECT_EQ(expand.channel, static_cast<int>(OutputChannel::kExpand));
  return expand;
}

// The swimmer with a relay from the skin inward: CHEMICAL -> unit A, which
// makes only a morphogen; A's morphogen -> unit B -> EXPAND. Both stay at
// 0 through development, where the chemical is 0.
Genome RelaySwimmer() {
  Genome genome = Swimmer();
  const Element expand = ExpandOutput(genome);
  genome.elements.push_back(In(InputChannel::kChemical, 50.0, 50.0));
  genome.elements.push_back(P(50.0, 50.0));  // A
  genome.elements.push_back(GMor(60.0, 60.0));
  genome.elements.push_back(P(60.0, 60.0));  // B
  genome.elements.push_back(GInt(expand.x, expand.y, expand.sign));
  return genome;
}

// The node of the unit whose first element is genome element `element`.
int NodeOf(const Network& network, int element) {
  for (int node = 0; node < network.node_count(); ++node) {
    if (network.nodes()[node].first_element == element) return node;
  }
  ADD_FAILURE() << "no node starts at element " << element;
  return -1;
}

ModelConfig ChainConfig() {
  ModelConfig config;
  config.evaluation.min_chambers = 0;  // seed-1203 grows a chain.
  config.evaluation.motion_steps = 1000;
  return config;
}

ModelConfig GuidanceConfig(int trials = 4) {
  ModelConfig config = ChainConfig();
  config.guidance.enabled = true;
  config.guidance.trials = trials;
  return config;
}

EvaluationResult EvaluateWith(const Genome& genome, const ModelConfig& config,
                              Knockout knockout,
                              EvaluationObserver* observer = nullptr) {
  EvaluateOptions options;
  options.knockout = knockout;
  return Evaluate(genome, config, observer, options);
}

Knockout Chemical() { return {Knockout::Kind::kChemical, -1}; }
Knockout Morphogen(int node) { return {Knockout::Kind::kMorphogen, node}; }

uint64_t Bits(const std::optional<double>& value) {
  return value ? std::bit_cast<uint64_t>(*value) : 0;
}

// Every bit but the final-state hash, which also hashes levels that need
// not act (a CHEMICAL input's).
void ExpectSameOutcome(const EvaluationResult& a, const EvaluationResult& b) {
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.reason, b.reason);
  EXPECT_EQ(Bits(a.fitness), Bits(b.fitness));
  EXPECT_EQ(Bits(a.distance), Bits(b.distance));
  EXPECT_EQ(Bits(a.energy), Bits(b.energy));
  ASSERT_EQ(a.source_distances.size(), b.source_distances.size());
  for (size_t k = 0; k < a.source_distances.size(); ++k) {
    EXPECT_EQ(std::bit_cast<uint64_t>(a.source_distances[k]),
              std::bit_cast<uint64_t>(b.source_distances[k]));
  }
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_EQ(a.steps, b.steps);
}

void ExpectSameBits(const EvaluationResult& a, const EvaluationResult& b) {
  ExpectSameOutcome(a, b);
  EXPECT_EQ(a.state_hash, b.state_hash);
}

void ExpectSameBody(const EvaluationResult& a, const EvaluationResult& b) {
  ASSERT_TRUE(a.body && b.body);
  EXPECT_EQ(a.body->cells, b.body->cells);
  EXPECT_EQ(a.body->springs, b.body->springs);
  EXPECT_EQ(a.body->chambers, b.body->chambers);
  EXPECT_EQ(a.body->skin_edges, b.body->skin_edges);
  EXPECT_EQ(std::bit_cast<uint64_t>(a.body->spread_major),
            std::bit_cast<uint64_t>(b.body->spread_major));
  EXPECT_EQ(std::bit_cast<uint64_t>(a.body->spread_minor),
            std::bit_cast<uint64_t>(b.body->spread_minor));
}

// Hashes what happens before motion (development, body, equilibration),
// and keeps each trial's final positions.
class Recorder : public EvaluationObserver {
 public:
  void OnDevelopmentStep(int step, const Embryo& embryo) override {
    before.AddU64(static_cast<uint64_t>(step));
    for (Vec2 p : embryo.position) {
      before.AddDouble(p.x);
      before.AddDouble(p.y);
    }
    before.AddDoubles(embryo.radius);
  }
  void OnBody(const Body&, std::span<const double> expand,
              std::span<const double> contract) override {
    before.AddDoubles(expand);
    before.AddDoubles(contract);
  }
  void OnGuidanceTrial(int, std::span<const Vec2>) override {
    final_positions.emplace_back();
  }
  void OnMotionStep(MotionPhase phase, int, const MotionState& state,
                    std::span<const double> expand,
                    std::span<const double> contract) override {
    if (phase == MotionPhase::kEquilibration) {
      HashMotionState(state, &before);
      before.AddDoubles(expand);
      before.AddDoubles(contract);
      return;
    }
    if (final_positions.empty()) final_positions.emplace_back();
    final_positions.back() = state.position;
  }
  StateHash before;
  std::vector<std::vector<Vec2>> final_positions;  // One per trial seen.
};

void ExpectSamePositions(const std::vector<Vec2>& a,
                         const std::vector<Vec2>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::bit_cast<uint64_t>(a[i].x), std::bit_cast<uint64_t>(b[i].x))
        << i;
    EXPECT_EQ(std::bit_cast<uint64_t>(a[i].y), std::bit_cast<uint64_t>(b[i].y))
        << i;
  }
}

TEST(KnockoutTest, NoKnockoutIsTheModelsEvaluation) {
  const Genome genome = RelaySwimmer();
  const ModelConfig config = GuidanceConfig();
  EvaluateOptions options;
  EXPECT_EQ(options.knockout.kind, Knockout::Kind::kNone);
  ExpectSameBits(Evaluate(genome, config),
                 EvaluateWith(genome, config, Knockout{}));
}

TEST(KnockoutTest, AGenomeWithoutMorphogensIsUnchangedByAnyKnockout) {
  Genome genome = Swimmer();
  for (Element& e : genome.elements) {
    if (e.type == ElementType::kGMorphogen) e.type = ElementType::kGInternal;
  }
  const ModelConfig config = ChainConfig();
  const Network network = Network::Build(genome, config.grn);
  ASSERT_EQ(network.morphogen_count(), 0);
  EXPECT_TRUE(MotionMorphogenUnits(network).empty());
  const EvaluationResult intact = Evaluate(genome, config);
  ASSERT_EQ(intact.status, EvalStatus::kOk) << intact.reason;
  for (int node = -1; node <= network.node_count(); ++node) {
    SCOPED_TRACE(node);
    ExpectSameBits(EvaluateWith(genome, config, Morphogen(node)), intact);
  }
}

TEST(KnockoutTest, SilencingAMorphogenNoCellMakesChangesNothing) {
  // A unit whose region nothing binds stays at 0 in every cell, while its
  // morphogen would excite EXPAND: motion computes it, and it is 0.
  Genome genome = Swimmer();
  const Element expand = ExpandOutput(genome);
  const int first = static_cast<int>(genome.elements.size());
  genome.elements.push_back(P(200.0, 200.0));
  genome.elements.push_back(GMor(expand.x, expand.y, expand.sign));
  for (Precision precision : {Precision::kFloat, Precision::kDouble}) {
    ModelConfig config = ChainConfig();
    config.grn.precision = precision;
    const Network network = Network::Build(genome, config.grn);
    const int silent = NodeOf(network, first);
    const std::vector<int> units = MotionMorphogenUnits(network);
    ASSERT_NE(std::find(units.begin(), units.end(), silent), units.end());
    EXPECT_TRUE(MorphogenReachesActuators(genome, network, config.grn, silent));
    const EvaluationResult intact = Evaluate(genome, config);
    ASSERT_EQ(intact.status, EvalStatus::kOk) << intact.reason;
    ExpectSameBits(EvaluateWith(genome, config, Morphogen(silent)), intact);
    // Nor does silencing a node that makes no morphogen (the EXPAND
    // output), or the chemical without guidance: it reads 0 anyway.
    ExpectSameBits(EvaluateWith(genome, config, Morphogen(NodeOf(network, 7))),
                   intact);
    ExpectSameBits(EvaluateWith(genome, config, Chemical()), intact);
  }
}

TEST(KnockoutTest, AKnockoutChangesNothingBeforeMotion) {
  const Genome genome = RelaySwimmer();
  const ModelConfig config = GuidanceConfig();
  const Network network = Network::Build(genome, config.grn);
  Recorder intact_recorder;
  const EvaluationResult intact =
      EvaluateWith(genome, config, Knockout{}, &intact_recorder);
  ASSERT_EQ(intact.status, EvalStatus::kOk) << intact.reason;
  std::vector<Knockout> knockouts = {Chemical()};
  for (int node : MotionMorphogenUnits(network)) {
    knockouts.push_back(Morphogen(node));
  }
  ASSERT_EQ(knockouts.size(), 5u);  // The swimmer's three, and A.
  int changed = 0;
  for (const Knockout& knockout : knockouts) {
    SCOPED_TRACE(knockout.node);
    Recorder recorder;
    const EvaluationResult r =
        EvaluateWith(genome, config, knockout, &recorder);
    ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
    EXPECT_EQ(recorder.before.value(), intact_recorder.before.value());
    EXPECT_EQ(r.cells, intact.cells);
    ExpectSameBody(r, intact);
    if (*r.fitness != *intact.fitness) ++changed;
  }
  EXPECT_EQ(changed, 5) << "every one of these inputs moves the swimmer";
}

TEST(KnockoutTest, SilencingTheChemicalSwimsAsAGenomeWithoutIt) {
  const ModelConfig config = GuidanceConfig();
  // Every trial the same path, that of the swimmer without a CHEMICAL
  // element (whose trials all follow one path too).
  EvaluateOptions all;
  all.observed_trial = EvaluateOptions::kAllTrials;
  Recorder deaf;
  const EvaluationResult without = Evaluate(Swimmer(), config, &deaf, all);
  ASSERT_EQ(without.status, EvalStatus::kOk) << without.reason;
  all.knockout = Chemical();
  Recorder silenced;
  const EvaluationResult r = Evaluate(RelaySwimmer(), config, &silenced, all);
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_EQ(silenced.final_positions.size(), 4u);
  ASSERT_EQ(deaf.final_positions.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    ExpectSamePositions(silenced.final_positions[k], deaf.final_positions[0]);
    ExpectSamePositions(deaf.final_positions[k], deaf.final_positions[0]);
  }
  EXPECT_EQ(Bits(r.distance), Bits(without.distance));
  EXPECT_EQ(Bits(r.energy), Bits(without.energy));
  EXPECT_EQ(Bits(r.fitness), Bits(without.fitness));
  // The chemical does move the intact relay swimmer.
  const EvaluationResult intact = Evaluate(RelaySwimmer(), config);
  ASSERT_EQ(intact.status, EvalStatus::kOk);
  EXPECT_NE(*intact.distance, *r.distance);
}

TEST(KnockoutTest, SilencingTheRelayMorphogenCutsTheChemicalOff) {
  const Genome genome = RelaySwimmer();
  const ModelConfig config = GuidanceConfig();
  const Network network = Network::Build(genome, config.grn);
  const int relay =
      NodeOf(network, static_cast<int>(Swimmer().elements.size()) + 1);
  EXPECT_TRUE(ChemicalReaches(network, relay));
  EXPECT_TRUE(MorphogenReachesActuators(genome, network, config.grn, relay));
  EvaluateOptions all;
  all.observed_trial = EvaluateOptions::kAllTrials;
  all.knockout = Morphogen(relay);
  Recorder relay_off;
  const EvaluationResult r = Evaluate(genome, config, &relay_off, all);
  all.knockout = Chemical();
  Recorder chemical_off;
  const EvaluationResult c = Evaluate(genome, config, &chemical_off, all);
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_EQ(c.status, EvalStatus::kOk) << c.reason;
  ASSERT_EQ(relay_off.final_positions.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    ExpectSamePositions(relay_off.final_positions[k],
                        chemical_off.final_positions[k]);
  }
  EXPECT_EQ(Bits(r.fitness), Bits(c.fitness));
  // A's own level differs (it still senses), so the final states do.
  EXPECT_NE(r.state_hash, c.state_hash);
}

TEST(KnockoutTest, TheReportNamesEachKnockoutAndItsPaths) {
  const Genome genome = RelaySwimmer();
  const ModelConfig config = GuidanceConfig(2);
  const Network network = Network::Build(genome, config.grn);
  const int relay =
      NodeOf(network, static_cast<int>(Swimmer().elements.size()) + 1);
  const KnockoutReport report = RunKnockouts(genome, config, 1);
  EXPECT_TRUE(report.guidance);
  ASSERT_EQ(report.intact.status, EvalStatus::kOk);
  ASSERT_EQ(report.runs.size(), 5u);
  EXPECT_EQ(report.runs[0].knockout.kind, Knockout::Kind::kChemical);
  EXPECT_TRUE(report.runs[0].actuator_path);
  std::vector<int> nodes;
  for (size_t i = 1; i < report.runs.size(); ++i) {
    const KnockoutRun& run = report.runs[i];
    EXPECT_EQ(run.knockout.kind, Knockout::Kind::kMorphogen);
    nodes.push_back(run.knockout.node);
    // The relay hears the chemical (and passes it on through B to units
    // near EXPAND, which may be the swimmer's morphogens); all reach the
    // actuators.
    EXPECT_EQ(run.chemical_path, ChemicalReaches(network, run.knockout.node));
    if (run.knockout.node == relay) {
      EXPECT_TRUE(run.chemical_path);
    }
    EXPECT_TRUE(run.actuator_path);
  }
  EXPECT_EQ(nodes, MotionMorphogenUnits(network));
  for (const KnockoutRun& run : report.runs) {
    ASSERT_EQ(run.result.status, EvalStatus::kOk);
    EXPECT_EQ(Bits(run.fitness_change),
              Bits(*run.result.fitness - *report.intact.fitness));
    ExpectSameBits(run.result, EvaluateWith(genome, config, run.knockout));
  }
  const v1::KnockoutAnalysis m = KnockoutReportToProto(report);
  EXPECT_TRUE(m.guidance());
  EXPECT_EQ(m.intact().kind(), v1::Knockout::NONE);
  EXPECT_FALSE(m.intact().has_fitness_change());
  EXPECT_FALSE(m.intact().has_chemical_path());
  ASSERT_EQ(m.knockout_size(), 5);
  EXPECT_EQ(m.knockout(0).kind(), v1::Knockout::CHEMICAL);
  EXPECT_FALSE(m.knockout(0).has_chemical_path());
  EXPECT_TRUE(m.knockout(0).actuator_path());
  EXPECT_EQ(m.knockout(1).kind(), v1::Knockout::MORPHOGEN);
  EXPECT_FALSE(m.knockout(0).has_node());
  EXPECT_EQ(m.knockout(1).node(), nodes[0]);
  EXPECT_EQ(m.knockout(1).unit_element(),
            network.nodes()[nodes[0]].first_element);
  EXPECT_EQ(report.runs[1].unit_element, m.knockout(1).unit_element());
  EXPECT_EQ(m.knockout(1).result().source_distances_size(), 2);
  EXPECT_EQ(m.knockout(1).fitness_change(), *report.runs[1].fitness_change);
}

TEST(KnockoutTest, AChemicalThatBindsNothingReachesNothing) {
  Genome genome = Swimmer();
  genome.elements.push_back(In(InputChannel::kChemical, 90.0, 90.0));
  const ModelConfig config = GuidanceConfig(2);
  const KnockoutReport report = RunKnockouts(genome, config, 2);
  ASSERT_EQ(report.intact.status, EvalStatus::kOk) << report.intact.reason;
  ASSERT_EQ(report.runs.size(), 4u);
  EXPECT_FALSE(report.runs[0].actuator_path);
  // The CHEMICAL node's level is all that differs.
  ExpectSameOutcome(report.runs[0].result, report.intact);
  EXPECT_NE(report.runs[0].result.state_hash, report.intact.state_hash);
  EXPECT_EQ(Bits(report.runs[0].fitness_change), Bits(0.0));
  for (const KnockoutRun& run : report.runs) {
    EXPECT_FALSE(run.chemical_path &&
                 run.knockout.kind == Knockout::Kind::kMorphogen)
        << run.knockout.node;
  }
}

TEST(KnockoutTest, TheReportDoesNotDependOnThreads) {
  const Genome genome = RelaySwimmer();
  const ModelConfig config = GuidanceConfig(3);
  const KnockoutReport one = RunKnockouts(genome, config, 1);
  for (int threads : {2, 7}) {
    const KnockoutReport many = RunKnockouts(genome, config, threads);
    ExpectSameBits(many.intact, one.intact);
    ASSERT_EQ(many.runs.size(), one.runs.size());
    for (size_t i = 0; i < one.runs.size(); ++i) {
      ExpectSameBits(many.runs[i].result, one.runs[i].result);
    }
  }
  // Nor an evaluation on the trial threads.
  EvaluateOptions options;
  options.knockout = one.runs[1].knockout;
  options.threads = 3;
  ExpectSameBits(Evaluate(genome, config, nullptr, options),
                 one.runs[1].result);
}

TEST(KnockoutTest, AnInvalidGenomeIsReportedWithoutKnockouts) {
  Genome genome = Swimmer();
  genome.elements[0].sign = 0;
  const KnockoutReport report = RunKnockouts(genome, GuidanceConfig(), 2);
  EXPECT_EQ(report.intact.status, EvalStatus::kInvalidGenome);
  EXPECT_TRUE(report.runs.empty());
}

}  // namespace
}  // namespace animat
