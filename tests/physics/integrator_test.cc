// Tests of the integrators, sub-steps and the stable drag update
// (SoftBody::Step with PhysicsParams::integrator, substeps, drag_update).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"
#include "tests/physics/body_source.h"

namespace animat {
namespace {

using testing::AtRest;
using testing::MaxDistance;
using testing::MustBuild;
using testing::Problem;
using testing::RandomBody;
using testing::Simulate;
using testing::Source;

const Integrator kIntegrators[] = {
    Integrator::kSemiImplicitEuler, Integrator::kVelocityVerlet,
    Integrator::kRk4, Integrator::kSsprk3, Integrator::kRalston3};

// A deformed, moving random body with constant actuation: a smooth problem
// (no drag, whose |v| v is only once differentiable at v = 0).
Problem SmoothProblem(uint64_t seed) {
  Source source(seed);
  Problem p;
  p.body = RandomBody(source, 12, 5.0);
  p.start = AtRest(p.body);
  for (Vec2& v : p.start.velocity) {
    v = {source.Uniform(-0.2, 0.2), source.Uniform(-0.2, 0.2)};
  }
  for (int i = 0; i < p.body.nodes(); ++i) {
    p.expand.push_back(source.Uniform(0, 1));
    p.contract.push_back(source.Uniform(0, 1));
  }
  return p;
}

// Without drag and contacts (whose forces have kinks where a pair starts
// to overlap): a smooth problem.
PhysicsParams NoDrag(Integrator integrator, int substeps) {
  PhysicsParams params;
  params.contact_rule = ContactRule::kNone;
  params.drag_normal = 0.0;
  params.drag_tangential = 0.0;
  params.integrator = integrator;
  params.substeps = substeps;
  return params;
}

// Error against RK4 with 64 sub-steps, at sub-step counts s and 2s: the
// ratio shows the order (2^order).
double ConvergenceRatio(Integrator integrator, int s) {
  const Problem p = SmoothProblem(11);
  const int steps = 40;  // Two time units.
  const MotionState reference =
      Simulate(p, NoDrag(Integrator::kRk4, 64), steps);
  const double coarse =
      MaxDistance(Simulate(p, NoDrag(integrator, s), steps), reference);
  const double fine =
      MaxDistance(Simulate(p, NoDrag(integrator, 2 * s), steps), reference);
  EXPECT_GT(fine, 0.0);
  return coarse / fine;
}

TEST(IntegratorTest, SemiImplicitEulerIsFirstOrder) {
  const double ratio = ConvergenceRatio(Integrator::kSemiImplicitEuler, 2);
  EXPECT_GT(ratio, 1.7);
  EXPECT_LT(ratio, 2.4);
}

TEST(IntegratorTest, VelocityVerletIsSecondOrder) {
  const double ratio = ConvergenceRatio(Integrator::kVelocityVerlet, 2);
  EXPECT_GT(ratio, 3.4);
  EXPECT_LT(ratio, 4.8);
}

TEST(IntegratorTest, Rk4IsFourthOrder) {
  const double ratio = ConvergenceRatio(Integrator::kRk4, 1);
  EXPECT_GT(ratio, 12.0);
  EXPECT_LT(ratio, 20.0);
}

TEST(IntegratorTest, Ssprk3IsThirdOrder) {
  const double ratio = ConvergenceRatio(Integrator::kSsprk3, 1);
  EXPECT_GT(ratio, 6.5);
  EXPECT_LT(ratio, 9.5);
}

TEST(IntegratorTest, Ralston3IsThirdOrder) {
  const double ratio = ConvergenceRatio(Integrator::kRalston3, 1);
  EXPECT_GT(ratio, 6.5);
  EXPECT_LT(ratio, 9.5);
}

// One step of a three-stage scheme written out from its Butcher tableau
// with ComputeForces: y' = f(y), y = (x, v), f = (v, F(x, v) / m).
MotionState Rk3ByHand(SoftBody* body, const MotionState& y, double h,
                      const double a21, const double a31, const double a32,
                      const double b1, const double b2, const double b3) {
  const int n = static_cast<int>(y.position.size());
  const double m = body->params().mass;
  std::vector<Vec2> f1, f2, f3;
  body->ComputeForces(y, &f1);
  MotionState y2 = y;
  for (int i = 0; i < n; ++i) {
    y2.position[i] = y.position[i] + y.velocity[i] * (h * a21);
    y2.velocity[i] = y.velocity[i] + f1[i] / m * (h * a21);
  }
  body->ComputeForces(y2, &f2);
  MotionState y3 = y;
  for (int i = 0; i < n; ++i) {
    y3.position[i] =
        y.position[i] + (y.velocity[i] * a31 + y2.velocity[i] * a32) * h;
    y3.velocity[i] = y.velocity[i] + (f1[i] / m * a31 + f2[i] / m * a32) * h;
  }
  body->ComputeForces(y3, &f3);
  MotionState out = y;
  for (int i = 0; i < n; ++i) {
    out.position[i] +=
        (y.velocity[i] * b1 + y2.velocity[i] * b2 + y3.velocity[i] * b3) * h;
    out.velocity[i] += (f1[i] / m * b1 + f2[i] / m * b2 + f3[i] / m * b3) * h;
  }
  return out;
}

TEST(IntegratorTest, ThirdOrderSchemesFollowTheirTableauxBitForBit) {
  // SSPRK3 (Shu-Osher) and Ralston's third order, as published, against
  // SoftBody's steps, with a non-unit mass and drag on.
  struct Case {
    Integrator integrator;
    double a21, a31, a32, b1, b2, b3;
  };
  const Case cases[] = {
      {Integrator::kSsprk3, 1.0, 0.25, 0.25, 1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0},
      {Integrator::kRalston3, 0.5, 0.0, 0.75, 2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0},
  };
  for (const Case& c : cases) {
    const Problem p = SmoothProblem(23);
    PhysicsParams params;
    params.integrator = c.integrator;
    params.substeps = 1;
    params.mass = 1.5;
    SoftBody body(p.body, params);
    body.SetActuation(p.expand, p.contract);
    MotionState stepped = p.start;
    MotionState by_hand = p.start;
    for (int step = 0; step < 20; ++step) {
      body.Step(&stepped);
      by_hand = Rk3ByHand(&body, by_hand, params.dt, c.a21, c.a31, c.a32, c.b1,
                          c.b2, c.b3);
    }
    for (int i = 0; i < p.body.nodes(); ++i) {
      EXPECT_EQ(stepped.position[i], by_hand.position[i])
          << IntegratorName(c.integrator) << " node " << i;
      EXPECT_EQ(stepped.velocity[i], by_hand.velocity[i])
          << IntegratorName(c.integrator) << " node " << i;
    }
  }
}

TEST(IntegratorTest, HigherOrderIsMoreAccurateAtTheSameStep) {
  const Problem p = SmoothProblem(5);
  const MotionState reference = Simulate(p, NoDrag(Integrator::kRk4, 64), 40);
  const double euler = MaxDistance(
      Simulate(p, NoDrag(Integrator::kSemiImplicitEuler, 1), 40), reference);
  const double verlet = MaxDistance(
      Simulate(p, NoDrag(Integrator::kVelocityVerlet, 1), 40), reference);
  const double rk4 =
      MaxDistance(Simulate(p, NoDrag(Integrator::kRk4, 1), 40), reference);
  const double ssprk3 =
      MaxDistance(Simulate(p, NoDrag(Integrator::kSsprk3, 1), 40), reference);
  const double ralston3 =
      MaxDistance(Simulate(p, NoDrag(Integrator::kRalston3, 1), 40), reference);
  EXPECT_LT(verlet, euler);
  EXPECT_LT(ssprk3, verlet);
  EXPECT_LT(ralston3, verlet);
  EXPECT_LT(rk4, ssprk3);
  EXPECT_LT(rk4, ralston3);
}

TEST(VelocityVerletTest, EqualsTwoFullForceEvaluationsPerStepToRounding) {
  // The scheme written out with ComputeForces at both ends of every step;
  // SoftBody measures each position's geometry once. Actuation changes
  // every step and the velocities are damped between steps, as in
  // equilibration.
  const Problem p = SmoothProblem(17);
  PhysicsParams params;
  params.integrator = Integrator::kVelocityVerlet;
  params.substeps = 1;
  // One step of dt holds contacts at k_c 200, not at the default 1500 (a
  // contact between two cells rings in 2.3 steps): model §7.10, §11.4.
  params.contact_stiffness = 200.0;
  SoftBody body(p.body, params);
  SoftBody forces(p.body, params);
  MotionState state = p.start;
  MotionState by_hand = p.start;
  const int n = p.body.nodes();
  const double h = params.dt;
  std::vector<Vec2> a0, a1;
  for (int step = 0; step < 200; ++step) {
    std::vector<double> expand(n), contract(n);
    for (int i = 0; i < n; ++i) {
      expand[i] = p.expand[i] * (0.5 + 0.5 * std::sin(0.1 * step + i));
      contract[i] = p.contract[i] * (0.5 + 0.5 * std::cos(0.13 * step));
    }
    body.SetActuation(expand, contract);
    body.Step(&state);
    forces.SetActuation(expand, contract);
    forces.ComputeForces(by_hand, &a0);
    MotionState end = by_hand;
    for (int i = 0; i < n; ++i) {
      a0[i] = a0[i] / params.mass;
      end.position[i] += by_hand.velocity[i] * h + a0[i] * (0.5 * h * h);
      end.velocity[i] += a0[i] * h;
    }
    forces.ComputeForces(end, &a1);
    for (int i = 0; i < n; ++i) {
      by_hand.position[i] = end.position[i];
      by_hand.velocity[i] += (a0[i] + a1[i] / params.mass) * (0.5 * h);
    }
    if (step % 3 == 0) {
      for (Vec2& v : state.velocity) v = v * 0.9;
      for (Vec2& v : by_hand.velocity) v = v * 0.9;
    }
  }
  EXPECT_LT(MaxDistance(state, by_hand), 1e-12);
  for (int i = 0; i < n; ++i) {
    EXPECT_LT(Length(state.velocity[i] - by_hand.velocity[i]), 1e-12);
  }
}

TEST(VelocityVerletTest, AFreshBodyContinuesWithTheSameBits) {
  // What one sub-step keeps for the next (the geometry of its end) is
  // exactly what a fresh SoftBody measures; positions moved between steps
  // are measured again.
  const Problem p = SmoothProblem(19);
  PhysicsParams params;
  params.integrator = Integrator::kVelocityVerlet;
  params.substeps = 2;
  SoftBody body(p.body, params);
  body.SetActuation(p.expand, p.contract);
  MotionState state = p.start;
  for (int step = 0; step < 5; ++step) body.Step(&state);
  for (bool move : {false, true}) {
    if (move) state.position[0].x += 0.01;
    MotionState fresh_state = state;
    body.Step(&state);
    SoftBody fresh(p.body, params);
    fresh.SetActuation(p.expand, p.contract);
    fresh.Step(&fresh_state);
    for (int i = 0; i < p.body.nodes(); ++i) {
      EXPECT_EQ(state.position[i], fresh_state.position[i]) << move;
      EXPECT_EQ(state.velocity[i], fresh_state.velocity[i]) << move;
    }
  }
}

TEST(IntegratorTest, OneSubStepOfEulerIsTheModelStep) {
  // substeps = 1 divides dt by 1: exactly v += F/m dt; x += v dt.
  const Problem p = SmoothProblem(3);
  PhysicsParams params;
  params.integrator = Integrator::kSemiImplicitEuler;
  params.substeps = 1;
  SoftBody body(p.body, params);
  body.SetActuation(p.expand, p.contract);
  MotionState stepped = p.start;
  body.Step(&stepped);
  MotionState by_hand = p.start;
  std::vector<Vec2> force;
  body.ComputeForces(by_hand, &force);
  for (int i = 0; i < p.body.nodes(); ++i) {
    by_hand.velocity[i] += force[i] / params.mass * params.dt;
    by_hand.position[i] += by_hand.velocity[i] * params.dt;
    EXPECT_EQ(stepped.position[i], by_hand.position[i]);
    EXPECT_EQ(stepped.velocity[i], by_hand.velocity[i]);
  }
}

TEST(IntegratorTest, EveryIntegratorKeepsTheCentreOfMassWithoutDrag) {
  for (Integrator integrator : kIntegrators) {
    for (DragUpdate drag : {DragUpdate::kExplicit, DragUpdate::kStable}) {
      Problem p = SmoothProblem(21);
      // Zero total momentum.
      Vec2 mean;
      for (const Vec2& v : p.start.velocity) mean += v;
      mean = mean / static_cast<double>(p.start.velocity.size());
      for (Vec2& v : p.start.velocity) v -= mean;
      PhysicsParams params = NoDrag(integrator, 3);
      params.drag_update = drag;
      const Vec2 before = CentreOfMass(p.start);
      const Vec2 after = CentreOfMass(Simulate(p, params, 500));
      EXPECT_LT(Length(after - before), 1e-10)
          << IntegratorName(integrator) << " " << DragUpdateName(drag);
    }
  }
}

TEST(IntegratorTest, EveryIntegratorLeavesARestingBodyAtRest) {
  Source source(8);
  const Body body_def = RandomBody(source, 10, 4.0);
  const std::vector<double> zero(body_def.nodes(), 0.0);
  for (Integrator integrator : kIntegrators) {
    for (DragUpdate drag : {DragUpdate::kExplicit, DragUpdate::kStable}) {
      PhysicsParams params;
      params.integrator = integrator;
      params.drag_update = drag;
      params.substeps = 2;
      // Random centres: unjoined cells may overlap at rest.
      params.contact_rule = ContactRule::kNone;
      SoftBody body(body_def, params);
      body.SetActuation(zero, zero);
      MotionState state = AtRest(body_def);
      for (int s = 0; s < 50; ++s) body.Step(&state);
      for (int i = 0; i < body_def.nodes(); ++i) {
        EXPECT_EQ(state.position[i], body_def.position[i]);
        EXPECT_EQ(state.velocity[i], Vec2{});
      }
    }
  }
}

// Two nodes joined by a spring at rest length, both moving with v0 across
// the edge: only normal drag acts, d_N l |v| v on the edge of mass 2m, so
// v(t) = v0 / (1 + c v0 t) with c = d_N l / (2 m).
struct TranslatingEdge {
  Body body;
  MotionState state;
};

TranslatingEdge MakeTranslatingEdge(double v0) {
  TranslatingEdge edge;
  edge.body = MustBuild({{0.0, 0.0}, {2.0, 0.0}});
  edge.state = AtRest(edge.body);
  for (Vec2& v : edge.state.velocity) v = {0.0, v0};
  return edge;
}

TEST(StableDragTest, IsExactForATranslatingEdge) {
  const double v0 = 3.0;
  TranslatingEdge edge = MakeTranslatingEdge(v0);
  PhysicsParams params;
  params.drag_update = DragUpdate::kStable;
  params.drag_normal = 5.0;
  SoftBody body(edge.body, params);
  const double c = params.drag_normal * 2.0 / (2.0 * params.mass);
  for (int step = 1; step <= 400; ++step) {
    body.Step(&edge.state);
    const double t = step * params.dt;
    const double exact = v0 / (1.0 + c * v0 * t);
    ASSERT_NEAR(edge.state.velocity[0].y, exact, 1e-13 * v0) << step;
    ASSERT_EQ(edge.state.velocity[0], edge.state.velocity[1]);
  }
}

TEST(StableDragTest, HundredfoldDragNeverReversesTheVelocity) {
  // Drag 100 times the default: the explicit update overshoots (the
  // velocity changes sign in one step); the stable one only slows down.
  const double v0 = 2.0;
  PhysicsParams params;
  params.integrator = Integrator::kSemiImplicitEuler;
  params.substeps = 1;
  params.drag_normal = 100.0;
  params.drag_tangential = 0.5;

  TranslatingEdge explicit_edge = MakeTranslatingEdge(v0);
  SoftBody explicit_body(explicit_edge.body, params);
  explicit_body.Step(&explicit_edge.state);
  EXPECT_LT(explicit_edge.state.velocity[0].y, 0.0) << "explicit overshoot";

  params.drag_update = DragUpdate::kStable;
  TranslatingEdge stable_edge = MakeTranslatingEdge(v0);
  SoftBody stable_body(stable_edge.body, params);
  double previous = v0;
  for (int step = 0; step < 1000; ++step) {
    stable_body.Step(&stable_edge.state);
    const double v = stable_edge.state.velocity[0].y;
    ASSERT_GT(v, 0.0) << step;
    ASSERT_LE(v, previous) << step;
    previous = v;
  }
}

TEST(StableDragTest, ConvergesToExplicitDragAsTheStepShrinks) {
  // A deforming body (not a translation): both updates approximate the model's
  // drag; their difference shrinks with the step.
  Problem p = SmoothProblem(31);
  auto difference = [&](int substeps) {
    PhysicsParams params;
    params.substeps = substeps;
    params.contact_stiffness = 200.0;  // One sub-step holds it (above).
    const MotionState a = Simulate(p, params, 20);
    params.drag_update = DragUpdate::kStable;
    const MotionState b = Simulate(p, params, 20);
    return MaxDistance(a, b);
  };
  const double coarse = difference(1);
  const double fine = difference(8);
  EXPECT_GT(coarse, 0.0);
  EXPECT_LT(fine, coarse / 4.0);
}

// Spring, pressure and kinetic energy of a body with constant actuation:
// springs and pressure are conservative (pressure is -dU/dx with
// U = -c_p (S - S^2 / (2 S0))), damping and drag only remove energy.
double Energy(const Body& body, const SoftBody& soft, const MotionState& s,
              const PhysicsParams& params) {
  double energy = 0.0;
  for (const Vec2& v : s.velocity) energy += 0.5 * params.mass * Dot(v, v);
  for (size_t k = 0; k < body.springs.size(); ++k) {
    const Spring& spring = body.springs[k];
    const double l = Length(s.position[spring.b] - s.position[spring.a]);
    const double stretch = l - soft.rest_lengths()[k];
    energy += 0.5 * params.stiffness * stretch * stretch;
  }
  for (int c = 0; c < soft.chambers(); ++c) {
    const double area = soft.ChamberArea(s, c);
    const double rest = body.chambers[c].rest_area;
    energy += -params.pressure * (area - area * area / (2.0 * rest)) +
              params.pressure * rest / 2.0;
  }
  return energy;
}

TEST(IntegratorTest, EnergyNeverGrowsWithDampingAndDrag) {
  for (Integrator integrator :
       {Integrator::kVelocityVerlet, Integrator::kRk4}) {
    Problem p = SmoothProblem(41);
    PhysicsParams params;
    params.integrator = integrator;
    params.contact_rule = ContactRule::kNone;  // Energy below has none.
    SoftBody body(p.body, params);
    body.SetActuation(p.expand, p.contract);
    MotionState state = p.start;
    const double start = Energy(p.body, body, state, params);
    double previous = start;
    for (int step = 0; step < 2000; ++step) {
      body.Step(&state);
      const double now = Energy(p.body, body, state, params);
      // A dissipative system: energy falls, up to the integrator's error.
      ASSERT_LE(now, previous + 1e-6 * start)
          << IntegratorName(integrator) << " step " << step;
      previous = now;
    }
    EXPECT_LT(previous, start);
  }
}

}  // namespace
}  // namespace animat
