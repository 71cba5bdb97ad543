#include "common/evaluation/evaluator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/base/rng.h"
#include "common/genome/genome_proto.h"
#include "common/genome/random_genome.h"
#include "common/io/proto_file.h"
#include "tests/test_genome.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using testing::LoadGenome;

using testing::ShortConfig;

TEST(EvaluatorTest, NonViableNetworkHasNoFitnessAndSaysWhy) {
  const EvaluationResult r =
      Evaluate(LoadGenome("seed-1-nonviable.json"), ShortConfig());
  EXPECT_EQ(r.status, EvalStatus::kNonViable);
  EXPECT_FALSE(r.fitness.has_value());
  EXPECT_NE(r.reason.find("DIVIDE"), std::string::npos) << r.reason;
  EXPECT_EQ(r.steps, 0);
}

TEST(EvaluatorTest, TooFewCellsHasNoFitness) {
  const EvaluationResult r =
      Evaluate(LoadGenome("seed-2-too-few-cells.json"), ShortConfig());
  EXPECT_EQ(r.status, EvalStatus::kTooFewCells);
  EXPECT_FALSE(r.fitness.has_value());
  EXPECT_EQ(r.cells, 1);
  EXPECT_EQ(r.steps, 400);
  EXPECT_NE(r.reason.find("at least 3"), std::string::npos) << r.reason;
}

TEST(EvaluatorTest, InvalidGenomeIsAStatusNotACrash) {
  Genome genome = LoadGenome("seed-1198.json");
  genome.elements[0].sign = 0;
  const EvaluationResult r = Evaluate(genome, ShortConfig());
  EXPECT_EQ(r.status, EvalStatus::kInvalidGenome);
  EXPECT_FALSE(r.fitness.has_value());
  EXPECT_NE(r.reason.find("elements[0].sign"), std::string::npos);
}

TEST(EvaluatorTest, LateDivisionWhenDivisionsMustEndEarly) {
  ModelConfig config = ShortConfig();
  config.development.last_division_step = 10;
  const EvaluationResult r = Evaluate(LoadGenome("seed-1198.json"), config);
  EXPECT_EQ(r.status, EvalStatus::kLateDivision);
  EXPECT_FALSE(r.fitness.has_value());
  EXPECT_NE(r.reason.find("divisions must end before step 10"),
            std::string::npos)
      << r.reason;
}

TEST(EvaluatorTest, ViableAnimatRunsEveryPhase) {
  const ModelConfig config = ShortConfig();
  const EvaluationResult r = Evaluate(LoadGenome("seed-1198.json"), config);
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_TRUE(r.fitness.has_value());
  EXPECT_TRUE(std::isfinite(*r.fitness));
  EXPECT_GE(*r.fitness, 0.0);
  EXPECT_EQ(r.cells, 32);
  EXPECT_EQ(r.steps, 400 + 200 + 300);
  EXPECT_NE(r.state_hash, 0u);
  EXPECT_TRUE(r.reason.empty());
  // The actuators' work, recorded with the result (model §10.1).
  ASSERT_TRUE(r.energy.has_value());
  EXPECT_TRUE(std::isfinite(*r.energy));
  EXPECT_GT(*r.energy, 0.0);
  const v1::EvaluationResult m = EvaluationResultToProto(r);
  ASSERT_TRUE(m.has_energy());
  EXPECT_EQ(m.energy(), *r.energy);
}

TEST(EvaluatorTest, EnergyIsTheMotionPhasesActuationWork) {
  // Replays the work from what an observer sees: at motion step t, the
  // state the step started from (the previous call's) and the actuation
  // the step set, against the one before it (for t = 1, equilibration's).
  struct Replay : EvaluationObserver {
    const ModelConfig* config = nullptr;
    std::unique_ptr<SoftBody> soft;
    Body body;
    MotionState start;
    double work = 0.0;
    void OnBody(const Body& b, std::span<const double> e,
                std::span<const double> c) override {
      body = b;
      soft = std::make_unique<SoftBody>(b, config->physics);
      soft->SetActuation(e, c);
    }
    void OnMotionStep(MotionPhase phase, int step, const MotionState& state,
                      std::span<const double> e,
                      std::span<const double> c) override {
      if (phase == MotionPhase::kMotion && step > 0) {
        const std::vector<double> before = soft->rest_lengths();
        soft->SetActuation(e, c);
        const std::vector<double>& after = soft->rest_lengths();
        double step_work = 0.0;
        for (size_t s = 0; s < body.springs.size(); ++s) {
          const Spring& spring = body.springs[s];
          const double l =
              Length(start.position[spring.b] - start.position[spring.a]);
          step_work += std::fabs(config->physics.stiffness * (l - after[s]) *
                                 (after[s] - before[s]));
        }
        work += step_work;
      }
      start = state;
    }
  };
  const ModelConfig config = ShortConfig();
  Replay replay;
  replay.config = &config;
  const EvaluationResult r =
      Evaluate(LoadGenome("seed-1198.json"), config, &replay);
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_TRUE(r.energy.has_value());
  EXPECT_GT(replay.work, 0.0);
  EXPECT_EQ(*r.energy, replay.work);
  // A failure has no energy.
  const EvaluationResult failed =
      Evaluate(LoadGenome("seed-2-too-few-cells.json"), config);
  EXPECT_NE(failed.status, EvalStatus::kOk);
  EXPECT_FALSE(failed.energy.has_value());
  EXPECT_FALSE(EvaluationResultToProto(failed).has_energy());
}

TEST(EvaluatorTest, TheEnergyBudgetScalesDistanceDownBeyondIt) {
  ModelConfig config = ShortConfig();
  const Genome genome = LoadGenome("seed-1198.json");
  const EvaluationResult plain = Evaluate(genome, config);
  ASSERT_EQ(plain.status, EvalStatus::kOk);
  ASSERT_TRUE(plain.distance && plain.energy);
  // The paper's fitness is the distance, bit for bit.
  EXPECT_EQ(*plain.fitness, *plain.distance);
  config.evaluation.fitness = FitnessKind::kDistanceWithinEnergyBudget;
  // Within the budget: the distance.
  config.evaluation.energy_budget = *plain.energy * 2;
  const EvaluationResult within = Evaluate(genome, config);
  EXPECT_EQ(*within.fitness, *plain.distance);
  // Beyond it: d * (B / E), and the distance and energy unchanged.
  config.evaluation.energy_budget = *plain.energy / 4;
  const EvaluationResult beyond = Evaluate(genome, config);
  EXPECT_EQ(
      *beyond.fitness,
      *plain.distance * (config.evaluation.energy_budget / *plain.energy));
  EXPECT_LT(*beyond.fitness, *plain.distance);
  EXPECT_EQ(*beyond.distance, *plain.distance);
  EXPECT_EQ(*beyond.energy, *plain.energy);
  EXPECT_EQ(beyond.state_hash, plain.state_hash);
  const v1::EvaluationResult m = EvaluationResultToProto(beyond);
  EXPECT_EQ(m.fitness(), *beyond.fitness);
  EXPECT_EQ(m.distance(), *plain.distance);
}

// The holding cost (docs/model.md §10.1): E = W + c_h * sum over motion
// steps of sum over springs |L - L0|, replayed from the rest lengths an
// observer sees; the motion itself is untouched.
TEST(EvaluatorTest, HoldingCostAddsTheHeldActuationToTheWork) {
  struct Held : EvaluationObserver {
    const ModelConfig* config = nullptr;
    std::unique_ptr<SoftBody> soft;
    std::vector<double> rest0;
    double held = 0.0;
    void OnBody(const Body& b, std::span<const double> e,
                std::span<const double> c) override {
      soft = std::make_unique<SoftBody>(b, config->physics);
      soft->SetActuation(e, c);
      for (const Spring& spring : b.springs)
        rest0.push_back(spring.rest_length);
    }
    void OnMotionStep(MotionPhase phase, int step, const MotionState&,
                      std::span<const double> e,
                      std::span<const double> c) override {
      if (phase != MotionPhase::kMotion || step == 0) return;
      soft->SetActuation(e, c);
      double step_held = 0.0;
      for (size_t s = 0; s < rest0.size(); ++s) {
        step_held += std::fabs(soft->rest_lengths()[s] - rest0[s]);
      }
      held += step_held;
    }
  };
  ModelConfig config = ShortConfig();
  const Genome genome = LoadGenome("seed-1198.json");
  const EvaluationResult plain = Evaluate(genome, config);
  ASSERT_EQ(plain.status, EvalStatus::kOk);
  config.evaluation.holding_cost = 0.25;
  Held held;
  held.config = &config;
  const EvaluationResult holding = Evaluate(genome, config, &held);
  ASSERT_EQ(holding.status, EvalStatus::kOk);
  EXPECT_GT(held.held, 0.0);
  EXPECT_EQ(*holding.energy, *plain.energy + 0.25 * held.held);
  EXPECT_EQ(*holding.distance, *plain.distance);
  EXPECT_EQ(*holding.fitness, *plain.fitness);  // DISTANCE ignores E.
  EXPECT_EQ(holding.state_hash, plain.state_hash);
  // And the budget's fitness reads the new E.
  config.evaluation.fitness = FitnessKind::kDistanceWithinEnergyBudget;
  config.evaluation.energy_budget = *plain.energy;
  const EvaluationResult budget = Evaluate(genome, config);
  EXPECT_EQ(*budget.fitness,
            *plain.distance * (*plain.energy / *holding.energy));
}

TEST(EvaluatorTest, RunawayMotionIsANumericalFailure) {
  // Springs far beyond the explicit stability limit blow up; the evaluation
  // must say so instead of returning a number.
  ModelConfig config = ShortConfig();
  config.physics.stiffness = 1e7;
  config.physics.actuation_max = 0.45;
  testing::FpTrapsOff traps_off;
  const EvaluationResult r = Evaluate(LoadGenome("seed-1198.json"), config);
  EXPECT_EQ(r.status, EvalStatus::kNumericalFailure);
  EXPECT_FALSE(r.fitness.has_value());
  EXPECT_FALSE(r.reason.empty());
}

TEST(EvaluatorTest, ChainWithoutChamberFailsAsADegenerateBody) {
  // seed-1203 develops into a straight chain of 32 cells
  // (docs/model.md §6.5, v2).
  const Genome chain = LoadGenome("seed-1203.json");
  const EvaluationResult r = Evaluate(chain, ShortConfig());
  EXPECT_EQ(r.status, EvalStatus::kDegenerateBody);
  EXPECT_EQ(r.reason, "no chamber: the body encloses no area");
  EXPECT_FALSE(r.fitness.has_value());
  EXPECT_EQ(r.steps, 400);  // Only development was paid for.
  ASSERT_TRUE(r.body.has_value());
  EXPECT_EQ(r.body->cells, 32);
  EXPECT_EQ(r.body->springs, 31);
  EXPECT_EQ(r.body->chambers, 0);
  EXPECT_LT(r.body->spread_minor, 1e-6);
  const v1::EvaluationResult m = EvaluationResultToProto(r);
  ASSERT_TRUE(m.has_body());
  EXPECT_EQ(m.body().springs(), 31);

  ModelConfig old_rule = ShortConfig();
  old_rule.evaluation.min_chambers = 0;
  const EvaluationResult old = Evaluate(chain, old_rule);
  EXPECT_EQ(old.status, EvalStatus::kOk) << old.reason;
  EXPECT_EQ(old.steps, 400 + 200 + 300);
}

TEST(EvaluatorTest, SuccessCarriesItsBodySummary) {
  const EvaluationResult r =
      Evaluate(LoadGenome("seed-1198.json"), ShortConfig());
  ASSERT_EQ(r.status, EvalStatus::kOk) << r.reason;
  ASSERT_TRUE(r.body.has_value());
  EXPECT_EQ(r.body->cells, 32);
  EXPECT_GE(r.body->chambers, 1);
  EXPECT_GT(r.body->springs, r.body->cells);
  EXPECT_GE(r.body->spread_major, r.body->spread_minor);
  EXPECT_GT(r.body->spread_minor, 1.0);
  // Failures before the body have none.
  EXPECT_FALSE(Evaluate(LoadGenome("seed-2-too-few-cells.json"), ShortConfig())
                   .body.has_value());
}

TEST(EvaluatorTest, DevelopmentBlowUpIsANumericalFailureWhateverTheCells) {
  // Overdamped mechanics far beyond their stability limit: the first
  // daughter, placed one radius from its mother, is thrown some 1e8 radii
  // away in the first sub-step after its birth.
  ModelConfig config = ShortConfig();
  config.development.stiffness = 1e9;
  // Without the blow-up this genome could not pass either: too few cells.
  config.development.min_cells = 33;
  testing::FpTrapsOff traps_off;
  const EvaluationResult r = Evaluate(LoadGenome("seed-1198.json"), config);
  EXPECT_EQ(r.status, EvalStatus::kNumericalFailure) << r.reason;
  EXPECT_NE(r.reason.find("at development step"), std::string::npos)
      << r.reason;
  EXPECT_LT(r.steps, 400);  // Development ended at once.
  EXPECT_FALSE(r.fitness.has_value());
  EXPECT_FALSE(r.body.has_value());

  // Numerical failure also outranks a late division.
  config.development.last_division_step = 1;
  EXPECT_EQ(Evaluate(LoadGenome("seed-1198.json"), config).status,
            EvalStatus::kNumericalFailure);
}

class PhaseRecorder : public EvaluationObserver {
 public:
  void OnDevelopmentStep(int step, const Embryo&) override {
    development_steps.push_back(step);
  }
  void OnBody(const Body& body, std::span<const double> expand,
              std::span<const double> contract) override {
    body_nodes = body.nodes();
    actuation = static_cast<int>(expand.size() + contract.size());
  }
  void OnMotionStep(MotionPhase phase, int step, const MotionState&,
                    std::span<const double>, std::span<const double>) override {
    (phase == MotionPhase::kEquilibration ? equilibration : motion)
        .push_back(step);
  }
  std::vector<int> development_steps, equilibration, motion;
  int body_nodes = 0;
  int actuation = 0;
};

TEST(EvaluatorTest, ObserverSeesEveryStepOfEveryPhase) {
  PhaseRecorder recorder;
  const ModelConfig config = ShortConfig();
  const EvaluationResult r =
      Evaluate(LoadGenome("seed-1198.json"), config, &recorder);
  ASSERT_EQ(r.status, EvalStatus::kOk);
  ASSERT_EQ(recorder.development_steps.size(), 400u);
  EXPECT_EQ(recorder.development_steps.front(), 0);
  EXPECT_EQ(recorder.development_steps.back(), 399);
  EXPECT_EQ(recorder.body_nodes, 32);
  EXPECT_EQ(recorder.actuation, 64);
  ASSERT_EQ(recorder.equilibration.size(), 201u);  // Steps 0..200.
  EXPECT_EQ(recorder.equilibration.back(), 200);
  ASSERT_EQ(recorder.motion.size(), 301u);  // Steps 0..300.
  EXPECT_EQ(recorder.motion.back(), 300);
}

TEST(EvaluatorTest, ObservingDoesNotChangeTheResult) {
  PhaseRecorder recorder;
  const ModelConfig config = ShortConfig();
  const Genome genome = LoadGenome("seed-1198.json");
  const EvaluationResult plain = Evaluate(genome, config);
  const EvaluationResult observed = Evaluate(genome, config, &recorder);
  EXPECT_EQ(plain.state_hash, observed.state_hash);
  EXPECT_EQ(plain.fitness, observed.fitness);
}

// The best of a model v2 run (docs/results.md, dn1-seed3) that folds
// through itself: without contacts cell 8 comes to lie on cell 11; with the
// default contacts no two unjoined cells overlap by more than 10% of r_i +
// r_j (model §7.10, §8.6).
TEST(EvaluatorTest, ContactsKeepAFoldingBodyFromPassingThroughItself) {
  const Genome genome = LoadGenome("folding-dn1-seed3.json");
  ModelConfig config;
  const EvaluationResult contacts = Evaluate(genome, config);
  config.physics.contact_rule = ContactRule::kNone;
  const EvaluationResult none = Evaluate(genome, config);
  ASSERT_EQ(contacts.status, EvalStatus::kOk) << contacts.reason;
  ASSERT_EQ(none.status, EvalStatus::kOk) << none.reason;
  ASSERT_TRUE(contacts.max_overlap && none.max_overlap);
  EXPECT_GT(*none.max_overlap, 0.9);
  EXPECT_LE(*contacts.max_overlap, 0.10);
  EXPECT_GT(*contacts.max_overlap, 0.0);  // They do touch.
  // Folding was worth distance: contacts cost this swimmer some.
  EXPECT_LT(*contacts.fitness, *none.fitness);
}

TEST(EvaluatorTest, RandomGenomesNeverCrashAndAlwaysGiveAStatus) {
  // Development only needs a few steps to hit every early status.
  ModelConfig config;
  config.evaluation.motion_steps = 20;
  config.evaluation.equilibration_steps = 20;
  for (uint64_t individual = 0; individual < 60; ++individual) {
    RandomStream stream(99, individual, StreamPurpose::kRandomGenome);
    const EvaluationResult r = Evaluate(RandomGenome(stream), config);
    EXPECT_EQ(r.fitness.has_value(), r.status == EvalStatus::kOk);
    EXPECT_EQ(r.max_overlap.has_value(), r.status == EvalStatus::kOk);
    if (r.max_overlap) {
      EXPECT_GE(*r.max_overlap, 0.0);
      EXPECT_LE(*r.max_overlap, 1.0);
    }
    EXPECT_EQ(r.reason.empty(), r.status == EvalStatus::kOk);
    if (r.fitness) {
      EXPECT_TRUE(std::isfinite(*r.fitness));
    }
  }
}

TEST(EvaluatorTest, ResultConvertsToProto) {
  EvaluationResult r;
  r.status = EvalStatus::kTooFewCells;
  r.reason = "2 cells";
  r.cells = 2;
  r.steps = 400;
  v1::EvaluationResult m = EvaluationResultToProto(r);
  EXPECT_EQ(m.status(), v1::EvaluationResult::TOO_FEW_CELLS);
  EXPECT_FALSE(m.has_fitness());
  r.status = EvalStatus::kOk;
  r.fitness = 0.0;
  m = EvaluationResultToProto(r);
  EXPECT_EQ(m.status(), v1::EvaluationResult::OK);
  ASSERT_TRUE(m.has_fitness());  // A fitness of 0 is still present.
  EXPECT_EQ(m.fitness(), 0.0);
  EXPECT_FALSE(m.has_max_overlap());
  r.max_overlap = 0.0;  // No overlap is still reported.
  ASSERT_TRUE(EvaluationResultToProto(r).has_max_overlap());
  EXPECT_EQ(EvaluationResultToProto(r).max_overlap(), 0.0);
  EXPECT_EQ(
      EvaluationResultToProto(
          {EvalStatus::kInvalidGenome, "", {}, 0, 0, 0, {}, {}, {}, {}, {}})
          .status(),
      v1::EvaluationResult::INVALID_GENOME);
}

}  // namespace
}  // namespace animat
