// Hard cases: no NaN, no crash, energy bounded where physics says it must
// be, and a clear failure status where the model cannot hold.
//
// Also covered elsewhere: a chamber pushed inside out turns back
// (SoftBodyTest.ChamberPushedInsideOutTurnsBack), invalid constants are
// rejected naming the field (ModelConfigTest.RejectsInvalidConstants...),
// hundredfold drag under the stable update (StableDragTest), coincident
// cells separate during development (DevelopmentTest).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/base/rng.h"
#include "common/body/body.h"
#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "common/genome/random_genome.h"
#include "common/io/proto_file.h"
#include "common/physics/soft_body.h"
#include "tests/physics/body_source.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using testing::AtRest;
using testing::MustBuild;

// Two nodes on a spring, stretched by 10% and let go, no damping, no drag:
// a harmonic oscillator of angular frequency w = sqrt(2 k / m). Returns the
// largest |l - L0| over `steps` steps.
double OscillatorAmplitude(Integrator integrator, double h_omega, int steps) {
  const Body body_def = MustBuild({{0.0, 0.0}, {1.0, 0.0}});
  PhysicsParams params;
  params.integrator = integrator;
  params.damping = 0.0;
  params.drag_normal = 0.0;
  params.drag_tangential = 0.0;
  const double omega = h_omega / params.dt;
  params.stiffness = omega * omega * params.mass / 2.0;
  SoftBody body(body_def, params);
  MotionState state = AtRest(body_def);
  state.position[1].x = 1.1;
  double amplitude = 0.0;
  for (int s = 0; s < steps; ++s) {
    body.Step(&state);
    const double l = Length(state.position[1] - state.position[0]);
    if (!std::isfinite(l)) return l;
    amplitude = std::max(amplitude, std::fabs(l - 1.0));
  }
  return amplitude;
}

TEST(HardCaseTest, StiffSpringsJustInsideTheStabilityLimitStayBounded) {
  // Semi-implicit Euler and velocity Verlet are stable for h w < 2, RK4 for
  // h w < 2.78.
  EXPECT_LT(OscillatorAmplitude(Integrator::kSemiImplicitEuler, 1.95, 100000),
            1.0);
  EXPECT_LT(OscillatorAmplitude(Integrator::kVelocityVerlet, 1.95, 100000),
            1.0);
  EXPECT_LT(OscillatorAmplitude(Integrator::kRk4, 2.7, 100000), 0.2);
}

TEST(HardCaseTest, StiffSpringsBeyondTheLimitBlowUpAndAreCaught) {
  testing::FpTrapsOff traps_off;
  const Body body_def = MustBuild({{0.0, 0.0}, {1.0, 0.0}});
  PhysicsParams params;
  params.integrator = Integrator::kSemiImplicitEuler;  // Stable to h w = 2.
  params.substeps = 1;
  params.damping = 0.0;
  const double omega = 2.05 / params.dt;
  params.stiffness = omega * omega * params.mass / 2.0;
  SoftBody body(body_def, params);
  MotionState state = AtRest(body_def);
  state.position[1].x = 1.1;
  std::string problem;
  for (int s = 1; s <= 100000 && problem.empty(); ++s) {
    body.Step(&state);
    if (s % 100 == 0) problem = CheckState(state, 1e6);
  }
  EXPECT_FALSE(problem.empty()) << "the unstable oscillator was not caught";
}

// Full expansion and full contraction on alternate steps with the largest
// valid amplitude: rest lengths jump between 1.9 L0 and 0.1 L0.
std::string ShakeBody(const Body& body_def, DragUpdate drag, int steps) {
  PhysicsParams params;
  params.actuation_max = 0.45;
  params.drag_update = drag;
  SoftBody body(body_def, params);
  MotionState state = AtRest(body_def);
  const std::vector<double> full(body_def.nodes(), 1.0);
  const std::vector<double> none(body_def.nodes(), 0.0);
  for (int s = 0; s < steps; ++s) {
    if (s % 2 == 0) {
      body.SetActuation(full, none);
    } else {
      body.SetActuation(none, full);
    }
    body.Step(&state);
    const std::string problem = CheckState(state, 1e6);
    if (!problem.empty()) return problem + " at step " + std::to_string(s);
  }
  return "";
}

TEST(HardCaseTest, ThirtyTwoCellsInALineSurviveMaximumActuation) {
  std::vector<Vec2> line;
  for (int i = 0; i < 32; ++i) line.push_back({1.7 * i, 0.0});
  const Body body = MustBuild(line);
  ASSERT_EQ(body.springs.size(), 31u);
  EXPECT_TRUE(body.chambers.empty());
  EXPECT_EQ(body.skin.size(), 31u);
  EXPECT_EQ(ShakeBody(body, DragUpdate::kExplicit, 5000), "");
  EXPECT_EQ(ShakeBody(body, DragUpdate::kStable, 5000), "");
}

TEST(HardCaseTest, CocircularCellsMakeFourSidedChambersAndSurvive) {
  // A 4 x 8 grid: every unit square is cocircular, its diagonals cross and
  // are removed.
  std::vector<Vec2> grid;
  for (int x = 0; x < 8; ++x) {
    for (int y = 0; y < 4; ++y) grid.push_back({1.8 * x, 1.8 * y});
  }
  const Body body = MustBuild(grid);
  EXPECT_EQ(body.springs.size(), 52u);   // 4 x 7 + 8 x 3 grid edges.
  EXPECT_EQ(body.chambers.size(), 21u);  // 3 x 7 squares.
  for (const Chamber& c : body.chambers) EXPECT_EQ(c.walk.size(), 4u);
  EXPECT_EQ(ShakeBody(body, DragUpdate::kExplicit, 5000), "");
}

TEST(HardCaseTest, RandomCompactBodiesSurviveMaximumActuation) {
  testing::Source source(17);
  for (int trial = 0; trial < 5; ++trial) {
    const Body body = testing::RandomBody(source, 32, 9.0);
    EXPECT_EQ(ShakeBody(body, DragUpdate::kExplicit, 3000), "") << trial;
  }
}

TEST(HardCaseTest, CoincidentCellsFailAsADegenerateBody) {
  Result<Body> body = BuildBody(
      std::vector<Vec2>{{0.0, 0.0}, {2.0, 0.0}, {1.0, 1.5}, {2.0, 0.0}});
  ASSERT_FALSE(body.ok());
  EXPECT_NE(body.status().message().find("coincident"), std::string::npos);
}

Genome LoadGenome(const std::string& name) {
  v1::Genome message;
  EXPECT_TRUE(
      ReadProtoFile(testing::TestData("genomes/" + name), &message).ok());
  Result<Genome> genome = GenomeFromProto(message);
  EXPECT_TRUE(genome.ok());
  return genome.ok() ? *genome : Genome{};
}

TEST(HardCaseTest, HundredfoldDragBlowsUpExplicitlyButNotStably) {
  testing::FpTrapsOff traps_off;  // The explicit run makes NaN on purpose.
  ModelConfig config;
  config.evaluation.motion_steps = 500;
  config.physics.drag_normal = 100.0;
  config.physics.drag_tangential = 0.5;
  // Model v2's default integrator, Ralston's third order with one step.
  config.physics.integrator = Integrator::kRalston3;
  config.physics.substeps = 1;
  const Genome genome = LoadGenome("seed-1198.json");
  // Explicit quadratic drag overshoots, oscillates and diverges: a
  // recorded failure, not a crash and not a number.
  const EvaluationResult explicit_drag = Evaluate(genome, config);
  EXPECT_EQ(explicit_drag.status, EvalStatus::kNumericalFailure);
  EXPECT_FALSE(explicit_drag.fitness.has_value());
  EXPECT_NE(explicit_drag.reason.find("non-finite"), std::string::npos)
      << explicit_drag.reason;
  config.physics.drag_update = DragUpdate::kStable;
  const EvaluationResult stable = Evaluate(genome, config);
  ASSERT_EQ(stable.status, EvalStatus::kOk) << stable.reason;
  EXPECT_TRUE(std::isfinite(*stable.fitness));
}

TEST(HardCaseTest, GenomeOfAThousandElementsEvaluates) {
  ModelConfig config;
  config.evaluation.equilibration_steps = 20;
  config.evaluation.motion_steps = 50;
  // Seed 2's body is a chain: without the chamber rule it runs through
  // every phase, which is what this test is about.
  config.evaluation.min_chambers = 0;
  int developed = 0;
  for (uint64_t seed : {1, 2}) {
    RandomStream stream(seed, 0, StreamPurpose::kRandomGenome);
    const Genome genome = RandomGenome(stream, 495);
    ASSERT_EQ(genome.elements.size(), 1000u);
    const EvaluationResult r = Evaluate(genome, config);
    EXPECT_EQ(r.fitness.has_value(), r.status == EvalStatus::kOk);
    if (r.status == EvalStatus::kOk) {
      ++developed;
      EXPECT_TRUE(std::isfinite(*r.fitness));
      EXPECT_EQ(r.cells, 32);
    }
  }
  EXPECT_EQ(developed, 1);  // Seed 2 develops; seed 1 stays one cell.
}

}  // namespace
}  // namespace animat
