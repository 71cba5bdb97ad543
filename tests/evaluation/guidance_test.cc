// Active guidance (docs/model.md §10.2): the CHEMICAL input, the trials and
// their sources, and the guidance fitness.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/body/body.h"
#include "common/evaluation/chemical.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "tests/genome_builder.h"
#include "tests/test_genome.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using testing::GInt;
using testing::In;
using testing::P;

constexpr double kPi = 3.14159265358979323846;
// Long enough for the swimmer to get going.
constexpr int kMotionSteps = 2000;

using testing::LoadGenome;

// The swimmers below grow from seed-1203, the best random mover: a chain
// of 32 cells (every cell on the skin), so the configurations accept
// bodies without chambers.
//
// A swimmer with a CHEMICAL input that binds nothing: no path from the
// chemical to any output.
Genome DeafSwimmer() {
  Genome genome = LoadGenome("seed-1203.json");
  genome.elements.push_back(In(InputChannel::kChemical, 90.0, 90.0));
  return genome;
}

// The same swimmer with CHEMICAL -> unit U -> EXPAND: U's region binds only
// the chemical, and its factor excites the swimmer's EXPAND output (the
// S_OUT at (2.888, 5.019), sign +1). U stays at 0 through development,
// where the chemical is 0.
Genome SensingSwimmer() {
  Genome genome = LoadGenome("seed-1203.json");
  const Element expand = genome.elements[7];  // A copy: elements grows.
  EXPECT_EQ(expand.type, ElementType::kSOut);
  EXPECT_EQ(expand.channel, static_cast<int>(OutputChannel::kExpand));
  const double x = expand.x, y = expand.y;
  genome.elements.push_back(In(InputChannel::kChemical, 50.0, 50.0));
  genome.elements.push_back(P(50.0, 50.0));
  genome.elements.push_back(GInt(x, y, expand.sign));
  return genome;
}

ModelConfig GuidanceConfig(int trials = 4) {
  ModelConfig config;
  config.evaluation.min_chambers = 0;
  config.evaluation.motion_steps = kMotionSteps;
  config.guidance.enabled = true;
  config.guidance.trials = trials;
  return config;
}

// Records the centre of mass where motion starts and ends, and the source
// of the observed trial.
class Watcher : public EvaluationObserver {
 public:
  void OnGuidanceTrial(int trial, std::span<const Vec2> sources) override {
    this->trial = trial;
    this->trials = static_cast<int>(sources.size());
    this->source = sources[trial];
    ++trials_seen;
  }
  void OnMotionStep(MotionPhase phase, int step, const MotionState& state,
                    std::span<const double>, std::span<const double>) override {
    if (phase != MotionPhase::kMotion) return;
    if (step == 0) start = CentreOfMass(state);
    end = CentreOfMass(state);
    final_state = state;
  }
  int trial = -1, trials = 0, trials_seen = 0;
  Vec2 source, start, end;
  MotionState final_state;
};

TEST(ChemicalTest, SourcesLieAtTheSpecifiedAngles) {
  const Vec2 start{3.0, -2.0};
  for (int trials : {1, 4, 7}) {
    for (int k = 0; k < trials; ++k) {
      const Vec2 s = GuidanceSource(start, k, trials, 30.0);
      const double angle = 2.0 * kPi * (k + 0.5) / trials;
      EXPECT_NEAR(s.x, 3.0 + 30.0 * std::cos(angle), 1e-12);
      EXPECT_NEAR(s.y, -2.0 + 30.0 * std::sin(angle), 1e-12);
    }
  }
  // K = 4: the diagonals, (±1, ±1) / sqrt 2.
  const Vec2 s0 = GuidanceSource({}, 0, 4, 1.0);
  EXPECT_NEAR(s0.x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(s0.y, std::sqrt(0.5), 1e-15);
  const Vec2 s2 = GuidanceSource({}, 2, 4, 1.0);
  EXPECT_NEAR(s2.x, -std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(s2.y, -std::sqrt(0.5), 1e-15);
}

TEST(ChemicalTest, OnlySkinCellsSenseAndInternalCellsReadZero) {
  // A hexagon around a centre cell: the centre is on no skin edge.
  std::vector<Vec2> centres = {{0.0, 0.0}};
  for (int k = 0; k < 6; ++k) {
    centres.push_back({2.0 * std::cos(kPi / 3.0 * k + 0.1),
                       2.0 * std::sin(kPi / 3.0 * k + 0.1)});
  }
  Result<Body> body = BuildBody(centres);
  ASSERT_TRUE(body.ok()) << body.status().ToString();
  const std::vector<int> skin = SkinCells(*body);
  EXPECT_EQ(skin, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  const Vec2 source{25.0, 5.0};
  std::vector<double> values;
  SenseChemical(source, 10.0, skin, centres, &values);
  ASSERT_EQ(values.size(), centres.size());
  EXPECT_EQ(values[0], 0.0);
  for (int c = 1; c < 7; ++c) {
    const double d = Length(centres[c] - source);
    EXPECT_NEAR(values[c], std::exp(-d / 10.0), 1e-15) << c;
    EXPECT_GT(values[c], 0.0);
  }
}

TEST(GuidanceTest, OffByDefaultWithNoSourceDistances) {
  ModelConfig config;
  config.evaluation.min_chambers = 0;
  config.evaluation.motion_steps = 200;
  const EvaluationResult r = Evaluate(DeafSwimmer(), config);
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  EXPECT_TRUE(r.source_distances.empty());
  EXPECT_EQ(*r.fitness, *r.distance);
}

TEST(GuidanceTest, NoChemicalPathSwimsTheSameInEveryTrial) {
  const Genome genome = DeafSwimmer();
  // Without guidance: one motion, from which every trial should follow.
  ModelConfig plain = GuidanceConfig();
  plain.guidance.enabled = false;
  Watcher alone;
  const EvaluationResult base = Evaluate(genome, plain, &alone);
  ASSERT_EQ(base.status, EvalStatus::kOk) << base.reason;
  ASSERT_GT(*base.distance, 0.1) << "it should swim";

  const ModelConfig config = GuidanceConfig();
  const EvaluationResult r = Evaluate(genome, config);
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_EQ(r.source_distances.size(), 4u);
  // Same body, same actuation: each trial is the plain motion, and only
  // the source turns around the start.
  double score = 0.0;
  for (int k = 0; k < 4; ++k) {
    EvaluateOptions options;
    options.observed_trial = k;
    Watcher watcher;
    const EvaluationResult again = Evaluate(genome, config, &watcher, options);
    ASSERT_EQ(again.status, EvalStatus::kOk);
    EXPECT_EQ(watcher.trial, k);
    EXPECT_EQ(watcher.trials, 4);
    EXPECT_EQ(watcher.start.x, alone.start.x);
    EXPECT_EQ(watcher.start.y, alone.start.y);
    EXPECT_EQ(watcher.end.x, alone.end.x) << k;
    EXPECT_EQ(watcher.end.y, alone.end.y) << k;
    ASSERT_EQ(watcher.final_state.position.size(),
              alone.final_state.position.size());
    for (size_t i = 0; i < watcher.final_state.position.size(); ++i) {
      EXPECT_EQ(watcher.final_state.position[i].x,
                alone.final_state.position[i].x);
      EXPECT_EQ(watcher.final_state.position[i].y,
                alone.final_state.position[i].y);
    }
    const Vec2 source = GuidanceSource(alone.start, k, 4, 30.0);
    EXPECT_EQ(watcher.source.x, source.x);
    EXPECT_EQ(watcher.source.y, source.y);
    EXPECT_NEAR(Length(source - alone.start), 30.0, 1e-12);
    EXPECT_NEAR(r.source_distances[k], Length(alone.end - source), 1e-12);
    score += 30.0 - r.source_distances[k];
  }
  EXPECT_NEAR(*r.fitness, score / 4.0, 1e-12);
  EXPECT_NEAR(*r.distance, *base.distance, 1e-12);
  EXPECT_NEAR(*r.energy, *base.energy, 1e-9 * *base.energy);
  EXPECT_EQ(r.steps, base.steps + 3 * config.evaluation.motion_steps);
}

// The lead (guidance.lead_steps): the network runs with the chemical on
// before motion, the body held. A swimmer that cannot sense still swims the
// same in every trial, now from a network `lead` steps on; the steps count
// the lead of every trial; a sensing swimmer's lead depends on its source.
TEST(GuidanceTest, TheLeadRunsTheNetworkBeforeMotionWithTheBodyHeld) {
  ModelConfig config = GuidanceConfig();
  const EvaluationResult base = Evaluate(DeafSwimmer(), config);
  ASSERT_EQ(base.status, EvalStatus::kOk) << base.reason;
  config.guidance.lead_steps = 50;
  const EvaluationResult led = Evaluate(DeafSwimmer(), config);
  ASSERT_EQ(led.status, EvalStatus::kOk) << led.reason;
  EXPECT_EQ(led.steps, base.steps + 4 * 50);
  EXPECT_NE(led.state_hash, base.state_hash);
  ASSERT_EQ(led.source_distances.size(), 4u);
  // Deaf: each trial is one motion seen from a source turned around the
  // start, so the distance swum is the same in every trial.
  Watcher first;
  EvaluateOptions options;
  options.observed_trial = 0;
  ASSERT_EQ(Evaluate(DeafSwimmer(), config, &first, options).status,
            EvalStatus::kOk);
  // The body was held: motion starts from the equilibrated start, which
  // the lead leaves where it was without one.
  Watcher unled;
  config.guidance.lead_steps = 0;
  ASSERT_EQ(Evaluate(DeafSwimmer(), config, &unled, options).status,
            EvalStatus::kOk);
  EXPECT_EQ(first.start.x, unled.start.x);
  EXPECT_EQ(first.start.y, unled.start.y);
  EXPECT_NEAR(*led.distance, Length(first.end - first.start), 1e-12);
  // A sensing swimmer: with the chemical knocked out its lead hears
  // nothing, and the result changes.
  config.guidance.lead_steps = 50;
  const EvaluationResult sensing = Evaluate(SensingSwimmer(), config);
  ASSERT_EQ(sensing.status, EvalStatus::kOk) << sensing.reason;
  EvaluateOptions deaf;
  deaf.knockout.kind = Knockout::Kind::kChemical;
  const EvaluationResult unheard =
      Evaluate(SensingSwimmer(), config, nullptr, deaf);
  ASSERT_EQ(unheard.status, EvalStatus::kOk) << unheard.reason;
  EXPECT_EQ(unheard.steps, sensing.steps);
  EXPECT_NE(unheard.state_hash, sensing.state_hash);
}

TEST(GuidanceTest, AnObserverMaySeeEveryTrialInTurn) {
  EvaluateOptions options;
  options.observed_trial = EvaluateOptions::kAllTrials;
  options.threads = 4;  // Ignored: the observer's thread runs them all.
  Watcher watcher;
  const EvaluationResult all =
      Evaluate(SensingSwimmer(), GuidanceConfig(3), &watcher, options);
  ASSERT_EQ(all.status, EvalStatus::kOk);
  EXPECT_EQ(watcher.trials_seen, 3);
  EXPECT_EQ(watcher.trial, 2);  // The last one, seen last.
  EXPECT_NEAR(Length(watcher.end - watcher.source), all.source_distances[2],
              1e-12);
  const EvaluationResult unwatched =
      Evaluate(SensingSwimmer(), GuidanceConfig(3));
  EXPECT_EQ(all.state_hash, unwatched.state_hash);
}

TEST(GuidanceTest, TheChemicalStaysLiveDuringMotion) {
  const Genome genome = SensingSwimmer();
  const EvaluationResult r = Evaluate(genome, GuidanceConfig());
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_EQ(r.source_distances.size(), 4u);
  // The sources pull the expansion differently in each trial. The chain
  // lies along the x axis, so trials 0 and 3 (sources at 45 and 315
  // degrees) are mirror images, as are 1 and 2: those may agree.
  for (int k = 1; k < 3; ++k) {
    EXPECT_NE(r.source_distances[k], r.source_distances[0]) << k;
    EXPECT_NE(r.source_distances[k], r.source_distances[3]) << k;
  }
  // Without a source the unit stays silent: the swimmer is the plain one.
  ModelConfig plain = GuidanceConfig();
  plain.guidance.enabled = false;
  const EvaluationResult sensing_plain = Evaluate(genome, plain);
  const EvaluationResult deaf_plain = Evaluate(DeafSwimmer(), plain);
  ASSERT_EQ(sensing_plain.status, EvalStatus::kOk);
  EXPECT_EQ(*sensing_plain.distance, *deaf_plain.distance);
}

TEST(GuidanceTest, ThreadCountDoesNotChangeTheBits) {
  const Genome genome = SensingSwimmer();
  const ModelConfig config = GuidanceConfig(5);
  const EvaluationResult one = Evaluate(genome, config);
  ASSERT_EQ(one.status, EvalStatus::kOk) << one.reason;
  for (int threads : {2, 4, 8}) {
    EvaluateOptions options;
    options.threads = threads;
    const EvaluationResult many = Evaluate(genome, config, nullptr, options);
    ASSERT_EQ(many.status, EvalStatus::kOk);
    EXPECT_EQ(std::bit_cast<uint64_t>(*many.fitness),
              std::bit_cast<uint64_t>(*one.fitness))
        << threads;
    EXPECT_EQ(std::bit_cast<uint64_t>(*many.distance),
              std::bit_cast<uint64_t>(*one.distance));
    EXPECT_EQ(std::bit_cast<uint64_t>(*many.energy),
              std::bit_cast<uint64_t>(*one.energy));
    EXPECT_EQ(many.source_distances, one.source_distances);
    EXPECT_EQ(many.max_overlap, one.max_overlap);
    EXPECT_EQ(many.state_hash, one.state_hash);
    EXPECT_EQ(many.steps, one.steps);
  }
}

// The largest |x| or |y| of any node: before motion, and in each trial.
class Extent : public EvaluationObserver {
 public:
  void OnGuidanceTrial(int trial, std::span<const Vec2>) override {
    current = trial;
  }
  void OnMotionStep(MotionPhase phase, int, const MotionState& state,
                    std::span<const double>, std::span<const double>) override {
    double& m = phase == MotionPhase::kMotion ? trial[current] : before;
    for (const Vec2& p : state.position) {
      m = std::max({m, std::fabs(p.x), std::fabs(p.y)});
    }
  }
  int current = -1;
  double before = 0.0;
  std::map<int, double> trial;
};

// Some trials cross the evaluation's bound (evaluation.max_coordinate,
// checked at every step here) and the others do not: the evaluation is a
// numerical failure named after the first of them in trial order, with its
// body and no fitness or source distances, the same on one thread as on
// several.
TEST(GuidanceTest, FailingTrialsFailTheEvaluationNamingTheFirst) {
  const Genome genome = SensingSwimmer();
  ModelConfig config = GuidanceConfig(4);
  config.evaluation.check_interval = 1;
  Extent extent;
  EvaluateOptions every_trial;
  every_trial.observed_trial = EvaluateOptions::kAllTrials;
  const EvaluationResult intact =
      Evaluate(genome, config, &extent, every_trial);
  ASSERT_EQ(intact.status, EvalStatus::kOk) << intact.reason;
  ASSERT_EQ(extent.trial.size(), 4u);
  // A bound between the farthest reach and the next one below it (mirror
  // trials reach equally far): the first trial in trial order that crosses
  // it decides, whichever thread finishes first.
  double farthest_reach = 0.0;
  for (const auto& [k, m] : extent.trial) {
    farthest_reach = std::max(farthest_reach, m);
  }
  double below = extent.before;
  for (const auto& [k, m] : extent.trial) {
    if (m < farthest_reach) below = std::max(below, m);
  }
  ASSERT_LT(below, farthest_reach) << "no trial reaches beyond the others";
  config.evaluation.max_coordinate = (below + farthest_reach) / 2;
  int farthest = 0;
  while (extent.trial[farthest] < farthest_reach) ++farthest;

  const int motion_steps = config.evaluation.motion_steps;
  for (int threads : {1, 4}) {
    SCOPED_TRACE(threads);
    EvaluateOptions options;
    options.threads = threads;
    const EvaluationResult r = Evaluate(genome, config, nullptr, options);
    EXPECT_EQ(r.status, EvalStatus::kNumericalFailure);
    EXPECT_EQ(
        r.reason.rfind("trial " + std::to_string(farthest) + ": node ", 0), 0u)
        << r.reason;
    EXPECT_NE(r.reason.find("left the region"), std::string::npos) << r.reason;
    EXPECT_FALSE(r.fitness.has_value());
    EXPECT_TRUE(r.source_distances.empty());
    EXPECT_TRUE(r.body.has_value());
    // The steps: those before motion, the trials before it in full, and
    // its own up to the failure.
    const int64_t before_motion = intact.steps - 4 * motion_steps;
    EXPECT_GT(r.steps, before_motion + farthest * motion_steps);
    EXPECT_LE(r.steps, before_motion + (farthest + 1) * motion_steps);
  }
  EvaluateOptions one, four;
  four.threads = 4;
  EXPECT_EQ(Evaluate(genome, config, nullptr, one).steps,
            Evaluate(genome, config, nullptr, four).steps);
}

TEST(GuidanceTest, ResultProtoCarriesTheSourceDistances) {
  const EvaluationResult r = Evaluate(SensingSwimmer(), GuidanceConfig(3));
  ASSERT_EQ(r.status, EvalStatus::kOk);
  const v1::EvaluationResult m = EvaluationResultToProto(r);
  ASSERT_EQ(m.source_distances_size(), 3);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(m.source_distances(k), r.source_distances[k]);
  }
}

}  // namespace
}  // namespace animat
