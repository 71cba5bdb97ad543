// Tests of contacts in inner sub-steps (physics.contact_inner_substeps,
// docs/model.md §7.6): velocity Verlet for the forces other than contacts
// once per sub-step, the contacts in n velocity Verlet sub-steps within.
// Its exact relation to plain velocity Verlet when only contacts act, its
// order, what it conserves, its accuracy on a stiff collision, and its
// configuration.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"
#include "tests/physics/body_source.h"

namespace animat {
namespace {

using testing::AtRest;
using testing::ExpectRefused;
using testing::MaxDistance;
using testing::MustBuild;
using testing::Problem;
using testing::RandomBody;
using testing::Simulate;
using testing::Source;

// A ring of `cells` touching cells (radius 1, neighbours 2 apart: one
// chamber, unjoined cells apart at rest) falling inward at `speed`, each
// velocity perturbed by up to half of it, with random constant actuation:
// it folds, and unjoined cells collide.
Problem Colliding(uint64_t seed, int cells, double speed) {
  Source source(seed);
  std::vector<Vec2> centres;
  const double pi = std::acos(-1.0);
  const double ring = 1.0 / std::sin(pi / cells);
  for (int i = 0; i < cells; ++i) {
    const double angle = 2.0 * pi * i / cells;
    centres.push_back({ring * std::cos(angle), ring * std::sin(angle)});
  }
  Problem p;
  p.body = MustBuild(centres);
  p.start = AtRest(p.body);
  for (int i = 0; i < cells; ++i) {
    p.start.velocity[i] =
        centres[i] * (-speed / ring) +
        Vec2{source.Uniform(-speed, speed), source.Uniform(-speed, speed)} *
            0.5;
  }
  for (int i = 0; i < p.body.nodes(); ++i) {
    p.expand.push_back(source.Uniform(0, 1));
    p.contract.push_back(source.Uniform(0, 1));
  }
  return p;
}

PhysicsParams Inner(int substeps, int inner) {
  PhysicsParams p;
  p.integrator = Integrator::kVelocityVerlet;
  p.substeps = substeps;
  p.contact_inner_substeps = inner;
  return p;
}

// With every force but the contacts at zero, the outer half kicks add
// zeros, and s sub-steps of n inner ones are velocity Verlet with s n
// sub-steps (h / n is dt / (s n) exactly when s n is a power of two):
// the same operations, so the same bits.
TEST(ContactInnerSubstepsTest, ContactsAloneAreVelocityVerletBitForBit) {
  for (const uint64_t seed : {1u, 2u, 3u}) {
    const Problem p = Colliding(seed, 14, 2.0);
    for (const auto& [s, n] : {std::pair{1, 4}, {2, 2}, {2, 4}, {4, 2}}) {
      PhysicsParams inner = Inner(s, n);
      inner.stiffness = 0.0;
      inner.damping = 0.0;
      inner.pressure = 0.0;
      inner.drag_normal = 0.0;
      inner.drag_tangential = 0.0;
      PhysicsParams plain = inner;
      plain.contact_inner_substeps = 0;
      plain.substeps = s * n;
      SoftBody a(p.body, inner);
      SoftBody b(p.body, plain);
      a.SetActuation(p.expand, p.contract);
      b.SetActuation(p.expand, p.contract);
      MotionState x = p.start;
      MotionState y = p.start;
      double deepest = 0.0;
      for (int step = 0; step < 300; ++step) {
        a.Step(&x);
        b.Step(&y);
        ASSERT_EQ(x.position, y.position)
            << "seed " << seed << " step " << step;
        ASSERT_EQ(x.velocity, y.velocity)
            << "seed " << seed << " step " << step;
        deepest = std::max(deepest, a.DeepestUnjoinedOverlap(x));
      }
      // The contacts acted.
      EXPECT_GT(deepest, 0.0) << "seed " << seed;
    }
  }
}

// Without contacts the scheme is velocity Verlet's kick-drift-kick for
// all forces, second order (the drift made of n equal parts).
TEST(ContactInnerSubstepsTest, IsSecondOrderWithoutContacts) {
  Problem p = Colliding(11, 12, 0.2);
  const auto params = [](int substeps, int inner, Integrator integrator) {
    PhysicsParams q = Inner(substeps, inner);
    q.integrator = integrator;
    q.contact_rule = ContactRule::kNone;
    q.drag_normal = 0.0;  // |v| v is only once differentiable at v = 0.
    q.drag_tangential = 0.0;
    return q;
  };
  const int steps = 40;
  const MotionState reference =
      Simulate(p, params(64, 0, Integrator::kRk4), steps);
  for (const int n : {1, 3}) {
    const double coarse = MaxDistance(
        Simulate(p, params(2, n, Integrator::kVelocityVerlet), steps),
        reference);
    const double fine = MaxDistance(
        Simulate(p, params(4, n, Integrator::kVelocityVerlet), steps),
        reference);
    ASSERT_GT(fine, 0.0);
    EXPECT_GT(coarse / fine, 3.4) << "n " << n;
    EXPECT_LT(coarse / fine, 4.8) << "n " << n;
  }
}

// Contacts are equal and opposite, like every other internal force: the
// centre of mass keeps its motion without drag.
TEST(ContactInnerSubstepsTest, KeepsTheCentreOfMassWithoutDrag) {
  Problem p = Colliding(21, 16, 1.5);
  Vec2 mean;
  for (const Vec2& v : p.start.velocity) mean += v;
  mean = mean / static_cast<double>(p.start.velocity.size());
  for (Vec2& v : p.start.velocity) v -= mean;
  PhysicsParams params = Inner(2, 3);
  params.drag_normal = 0.0;
  params.drag_tangential = 0.0;
  const Vec2 before = CentreOfMass(p.start);
  const MotionState end = Simulate(p, params, 500);
  EXPECT_LT(Length(CentreOfMass(end) - before), 1e-10);
  EXPECT_EQ(CheckState(end, 1e6), "");
}

TEST(ContactInnerSubstepsTest, LeavesARestingBodyAtRest) {
  Source source(8);
  const Body body_def = RandomBody(source, 10, 4.0);
  const std::vector<double> zero(body_def.nodes(), 0.0);
  PhysicsParams params = Inner(2, 2);
  params.contact_rule = ContactRule::kNone;  // Random centres may overlap.
  SoftBody body(body_def, params);
  body.SetActuation(zero, zero);
  MotionState state = AtRest(body_def);
  for (int s = 0; s < 50; ++s) body.Step(&state);
  for (int i = 0; i < body_def.nodes(); ++i) {
    EXPECT_EQ(state.position[i], body_def.position[i]);
    EXPECT_EQ(state.velocity[i], Vec2{});
  }
}

// What the inner sub-steps are for: rings thrown inward hard at the
// default k_c. Two sub-steps with the contacts in two inner ones each come
// far nearer to a fine reference than two plain sub-steps, and within 4
// times of four plain ones, which is what the other forces' own second
// order error at twice the step costs (without contacts, the same
// sub-steps lie about 4.2 times apart).
TEST(ContactInnerSubstepsTest, StiffContactsAreNearlyAsAccurateAsTheFineStep) {
  double plain2 = 0.0, plain4 = 0.0, inner2x2 = 0.0, deepest = 0.0;
  for (const uint64_t seed : {5u, 6u, 7u, 8u}) {
    const Problem p = Colliding(seed, 16, 8.0);
    PhysicsParams reference = Inner(64, 0);
    reference.integrator = Integrator::kRk4;
    const int steps = 10;  // Half a time unit: the first collisions.
    const MotionState ref = Simulate(p, reference, steps);
    plain2 += MaxDistance(Simulate(p, Inner(2, 0), steps), ref);
    plain4 += MaxDistance(Simulate(p, Inner(4, 0), steps), ref);
    inner2x2 += MaxDistance(Simulate(p, Inner(2, 2), steps), ref);
    SoftBody body(p.body, reference);
    deepest = std::max(deepest, body.DeepestUnjoinedOverlap(ref));
  }
  EXPECT_GT(deepest, 0.0);  // Cells are in contact at the end.
  EXPECT_LT(inner2x2, 0.1 * plain2) << plain2 << " " << plain4;
  EXPECT_LT(inner2x2, 4.0 * plain4) << plain2 << " " << plain4;
}

TEST(ContactInnerSubstepsConfigTest, RoundTripsAndRefusesWhatItCannotDo) {
  EXPECT_EQ(PhysicsParams{}.contact_inner_substeps, 0);
  PhysicsParams params;
  params.contact_inner_substeps = 3;
  PhysicsParams back;
  ASSERT_TRUE(PhysicsParamsFromProto(PhysicsParamsToProto(params), &back).ok());
  EXPECT_EQ(back.contact_inner_substeps, 3);
  const auto refused = [](const v1::PhysicsConfig& bad, const char* prefix) {
    EXPECT_EQ(ExpectRefused(bad, prefix).contact_inner_substeps, 0);
  };
  for (const int bad : {-1, 1025}) {
    v1::PhysicsConfig m;
    m.set_contact_inner_substeps(bad);
    refused(m, "physics.contact_inner_substeps: ");
  }
  v1::PhysicsConfig rk4;
  rk4.set_contact_inner_substeps(2);
  rk4.set_integrator(v1::PhysicsConfig::RK4);
  refused(rk4, "physics.contact_inner_substeps: only VELOCITY_VERLET");
  v1::PhysicsConfig both;
  both.set_contact_inner_substeps(2);
  both.set_contact_substeps(4);
  refused(both, "physics.contact_inner_substeps: not with");
}

}  // namespace
}  // namespace animat
