// Tests of contact sub-steps (docs/model.md §7.6): a step that starts with
// an admitted pair of cells within (1 + contact_near) · (r_i + r_j) takes
// physics.contact_substeps sub-steps, every other step physics.substeps.
// Contacts::Near against testing every pair, and SoftBody::Step against
// the same choice made by hand with two uniform bodies, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/physics/contacts.h"
#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"
#include "tests/physics/body_source.h"

namespace animat {
namespace {

using testing::AtRest;
using testing::ExpectRefused;
using testing::Joined;
using testing::RandomBody;
using testing::Source;

// Near by testing every pair i < j that the rule admits.
bool ReferenceNear(const Body& body, ContactRule rule,
                   const std::vector<Vec2>& x, double margin) {
  if (rule == ContactRule::kNone) return false;
  for (int i = 0; i < body.nodes(); ++i) {
    for (int j = i + 1; j < body.nodes(); ++j) {
      if (rule == ContactRule::kUnjoined && Joined(body, i, j)) continue;
      const Vec2 d = x[j] - x[i];
      const double reach = (1.0 + margin) * (body.radius[i] + body.radius[j]);
      if (d.x * d.x + d.y * d.y < reach * reach) return true;
    }
  }
  return false;
}

TEST(ContactSubstepsTest, NearEqualsTestingEveryPair) {
  Source source(77);
  long long compared = 0, near = 0;
  for (int trial = 0; trial < 10; ++trial) {
    Body body = RandomBody(source, source.Int(3, 32), 8.0);
    body.radius.resize(body.nodes());
    for (double& r : body.radius) r = source.Uniform(0.4, 1.2);
    for (const ContactRule rule :
         {ContactRule::kNone, ContactRule::kUnjoined, ContactRule::kAll}) {
      PhysicsParams p;
      p.contact_rule = rule;
      Contacts contacts(body, p, /*forces=*/true);
      std::vector<Vec2> x = body.position;
      for (int step = 0; step < 300; ++step) {
        for (Vec2& xi : x) {
          xi += Vec2{source.Uniform(-0.05, 0.05), source.Uniform(-0.05, 0.05)};
        }
        for (const double margin : {0.0, 0.1, 0.7}) {
          const bool expected = ReferenceNear(body, rule, x, margin);
          ASSERT_EQ(contacts.Near(x, margin), expected)
              << "trial " << trial << " step " << step << " margin " << margin
              << " rule " << ContactRuleName(rule);
          ++compared;
          near += expected;
        }
      }
    }
  }
  // Both answers occur.
  EXPECT_GT(near, compared / 10);
  EXPECT_LT(near, compared * 9 / 10);
}

TEST(ContactSubstepsTest, NothingIsNearWithoutContactForces) {
  // Two unjoined cells of radius 1, 2.1 apart: within 1.1 (r_i + r_j).
  Body body;
  body.position = {{0, 0}, {2.1, 0}};
  body.radius = {1.0, 1.0};
  PhysicsParams p;
  Contacts bullet(body, p, /*forces=*/false);  // The Bullet backend's.
  EXPECT_FALSE(bullet.Near(body.position, 0.1));
  p.contact_rule = ContactRule::kNone;
  Contacts none(body, p, /*forces=*/true);
  EXPECT_FALSE(none.Near(body.position, 0.1));
  p.contact_rule = ContactRule::kUnjoined;
  Contacts unjoined(body, p, /*forces=*/true);
  EXPECT_TRUE(unjoined.Near(body.position, 0.1));
}

// Runs `steps` steps of `body` under random actuation changed every 40
// steps (A_max 0.45: the springs can drive cells into each other), by
// `adaptive` and by hand: each step by `uniform_near` when ReferenceNear
// says a contact is near at its start, else by `uniform_far`. Expects the
// same bits after every step; returns how many steps were near.
int CompareWithChoiceByHand(const Body& body, const PhysicsParams& adaptive_p,
                            int steps, uint64_t seed) {
  PhysicsParams far_p = adaptive_p;
  far_p.contact_substeps = 0;
  PhysicsParams near_p = far_p;
  near_p.substeps = adaptive_p.contact_substeps;
  SoftBody adaptive(body, adaptive_p);
  SoftBody uniform_far(body, far_p);
  SoftBody uniform_near(body, near_p);
  MotionState a = AtRest(body);
  MotionState b = AtRest(body);
  Source source(seed);
  const int n = body.nodes();
  std::vector<double> expand(n), contract(n);
  int near = 0;
  for (int step = 0; step < steps; ++step) {
    if (step % 40 == 0) {
      for (int i = 0; i < n; ++i) {
        expand[i] = source.Uniform(0, 1);
        contract[i] = source.Uniform(0, 1);
      }
      adaptive.SetActuation(expand, contract);
      uniform_far.SetActuation(expand, contract);
      uniform_near.SetActuation(expand, contract);
    }
    const bool is_near = ReferenceNear(body, adaptive_p.contact_rule,
                                       b.position, adaptive_p.contact_near);
    near += is_near;
    adaptive.Step(&a);
    (is_near ? uniform_near : uniform_far).Step(&b);
    EXPECT_EQ(a.position, b.position) << "step " << step;
    EXPECT_EQ(a.velocity, b.velocity) << "step " << step;
    if (a.position != b.position || a.velocity != b.velocity) break;
  }
  EXPECT_EQ(CheckState(a, 1e6), "");
  return near;
}

TEST(ContactSubstepsTest, StepTakesContactSubstepsExactlyWhenNear) {
  Source source(12);
  int near = 0, steps = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Body body = RandomBody(source, source.Int(6, 24), 6.0);
    for (const Integrator integrator :
         {Integrator::kVelocityVerlet, Integrator::kRk4}) {
      PhysicsParams p;  // k_c 1500, unjoined contacts, drag.
      p.integrator = integrator;
      p.substeps = 2;
      p.contact_substeps = 4;
      p.actuation_max = 0.45;
      SCOPED_TRACE("trial " + std::to_string(trial) + " " +
                   IntegratorName(integrator));
      near += CompareWithChoiceByHand(body, p, 400, 100 + trial);
      steps += 400;
    }
  }
  // Both kinds of step occur.
  EXPECT_GT(near, steps / 20);
  EXPECT_LT(near, steps * 19 / 20);
}

TEST(ContactSubstepsTest, ExtremesAreTheUniformSchemes) {
  Source source(3);
  const Body body = RandomBody(source, 16, 5.0);
  PhysicsParams p;
  p.substeps = 2;
  p.contact_substeps = 4;
  p.actuation_max = 0.45;
  // Everything near: every step takes 4 sub-steps.
  p.contact_near = 1e6;
  EXPECT_EQ(CompareWithChoiceByHand(body, p, 200, 1), 200);
  // No contacts, nothing near: every step takes 2.
  p.contact_rule = ContactRule::kNone;
  EXPECT_EQ(CompareWithChoiceByHand(body, p, 200, 1), 0);
}

TEST(ContactSubstepsConfigTest, RoundTripsAndRefusesOutOfRange) {
  PhysicsParams params;
  EXPECT_EQ(params.contact_substeps, 0);
  params.contact_substeps = 8;
  params.contact_near = 0.25;
  const v1::PhysicsConfig message = PhysicsParamsToProto(params);
  PhysicsParams back;
  ASSERT_TRUE(PhysicsParamsFromProto(message, &back).ok());
  EXPECT_EQ(back.contact_substeps, 8);
  EXPECT_EQ(back.contact_near, 0.25);
  const auto refused = [](const v1::PhysicsConfig& bad, const char* prefix) {
    EXPECT_EQ(ExpectRefused(bad, prefix).contact_substeps,
              PhysicsParams{}.contact_substeps);
  };
  for (const int bad : {-1, 1025}) {
    v1::PhysicsConfig m;
    m.set_contact_substeps(bad);
    refused(m, "physics.contact_substeps: ");
  }
  for (const double bad : {-0.1, std::nan(""), HUGE_VAL}) {
    v1::PhysicsConfig m;
    m.set_contact_near(bad);
    refused(m, "physics.contact_near: ");
  }
}

}  // namespace
}  // namespace animat
