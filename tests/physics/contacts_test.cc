// Tests of the contacts between cells (docs/model.md §7.10, model v3) and of
// the deepest unjoined overlap (§8.6): the force of one pair by hand, which
// pairs each rule lets push, the pair list against testing every pair, bit
// for bit and in (i, j) order, conservation, and hard cases under every
// integrator.
//
// Expected forces are computed here from the model's equations, never by
// calling the code under test.
#include "common/physics/contacts.h"

#include <gtest/gtest.h>

#include <algorithm>
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
using testing::Joined;
using testing::RandomBody;
using testing::Source;

// A hand-made body: cells at `x` with radii `r`, springs between the pairs
// given (rest length their distance), no chamber, no skin.
Body Cells(const std::vector<Vec2>& x, const std::vector<double>& r,
           const std::vector<IndexEdge>& springs = {}) {
  Body body;
  body.position = x;
  body.radius = r;
  for (const IndexEdge& e : springs) {
    body.springs.push_back({e.a, e.b, Length(x[e.b] - x[e.a])});
  }
  return body;
}

// The rule given, k_c = 50 and gamma_c = 0.5 (the tests' numbers are worked
// out for them), no drag.
PhysicsParams Rule(ContactRule rule) {
  PhysicsParams params;
  params.contact_rule = rule;
  params.contact_stiffness = 50.0;
  params.contact_damping = 0.5;
  params.drag_normal = 0.0;
  params.drag_tangential = 0.0;
  return params;
}

// The model's contact forces by testing every pair i < j in order.
std::vector<Vec2> ReferenceForces(const Body& body, const PhysicsParams& p,
                                  const MotionState& state) {
  const int n = body.nodes();
  std::vector<Vec2> force(n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (p.contact_rule == ContactRule::kNone ||
          (Joined(body, i, j) && p.contact_rule == ContactRule::kUnjoined)) {
        continue;
      }
      const Vec2 d = state.position[j] - state.position[i];
      const double l = std::sqrt(d.x * d.x + d.y * d.y);
      const double delta = (body.radius[i] + body.radius[j]) - l;
      if (!(delta > 0.0)) continue;
      const Vec2 u = l > 0.0 ? d / l : Vec2{};
      const double w = -Dot(state.velocity[j] - state.velocity[i], u);
      const double f = p.contact_stiffness * delta + p.contact_damping * w;
      if (!(f > 0.0)) continue;
      force[j] += u * f;
      force[i] -= u * f;
    }
  }
  return force;
}

double ReferenceDeepest(const Body& body, const MotionState& state) {
  double deepest = 0.0;
  for (int i = 0; i < body.nodes(); ++i) {
    for (int j = i + 1; j < body.nodes(); ++j) {
      if (Joined(body, i, j)) continue;
      const double s = body.radius[i] + body.radius[j];
      const double l = Length(state.position[j] - state.position[i]);
      if (s - l > 0.0) deepest = std::max(deepest, (s - l) / s);
    }
  }
  return deepest;
}

TEST(ContactsTest, OverlappingCellsPushApartAlongTheLineOfCentres) {
  // Radii 1 and 0.5 at distance 1.2: delta = 0.3. Closing at speed 0.4.
  const Body body = Cells({{0, 0}, {0.72, 0.96}}, {1.0, 0.5});
  MotionState state = AtRest(body);           // l = 1.2, u = (0.6, 0.8).
  state.velocity = {{0, 0}, {-0.24, -0.32}};  // w = 0.4.
  const PhysicsParams p = Rule(ContactRule::kUnjoined);
  Contacts contacts(body, p, /*forces=*/true);
  std::vector<Vec2> force(2);
  contacts.AddForces(state.position, state.velocity, force.data());
  const double f = 50.0 * 0.3 + 0.5 * 0.4;  // k_c delta + gamma_c w.
  EXPECT_NEAR(force[1].x, f * 0.6, 1e-12);
  EXPECT_NEAR(force[1].y, f * 0.8, 1e-12);
  EXPECT_EQ(force[0], -force[1]);
  EXPECT_NEAR(contacts.DeepestUnjoinedOverlap(state.position), 0.3 / 1.5,
              1e-15);
}

TEST(ContactsTest, ContactsPushButNeverPull) {
  // Overlapping by 0.1 but separating fast: k_c delta + gamma_c w < 0.
  const Body body = Cells({{0, 0}, {1.9, 0}}, {1.0, 1.0});
  MotionState state = AtRest(body);
  state.velocity = {{-10, 0}, {10, 0}};  // w = -20: 5 - 10 < 0.
  Contacts contacts(body, Rule(ContactRule::kUnjoined), true);
  std::vector<Vec2> force(2);
  contacts.AddForces(state.position, state.velocity, force.data());
  EXPECT_EQ(force[0], Vec2{});
  EXPECT_EQ(force[1], Vec2{});
  // Touching exactly is no overlap: nothing, and no overlap reported.
  state.position[1] = {2.0, 0.0};
  state.velocity = {{0, 0}, {0, 0}};
  contacts.AddForces(state.position, state.velocity, force.data());
  EXPECT_EQ(force[1], Vec2{});
  EXPECT_EQ(contacts.DeepestUnjoinedOverlap(state.position), 0.0);
}

TEST(ContactsTest, EachRuleChoosesItsPairs) {
  // Cells 0-1 joined and overlapping, 1-2 unjoined and overlapping.
  const Body body =
      Cells({{0, 0}, {1.5, 0}, {3.0, 0}}, {1.0, 1.0, 1.0}, {{0, 1}});
  const MotionState state = AtRest(body);
  for (const ContactRule rule :
       {ContactRule::kNone, ContactRule::kUnjoined, ContactRule::kAll}) {
    Contacts contacts(body, Rule(rule), true);
    std::vector<Vec2> force(3);
    contacts.AddForces(state.position, state.velocity, force.data());
    const std::string name = ContactRuleName(rule);
    EXPECT_EQ(contacts.active(), rule != ContactRule::kNone) << name;
    // 0-1 pushes only under ALL; 1-2 under UNJOINED and ALL.
    EXPECT_EQ(force[0].x < 0.0, rule == ContactRule::kAll) << name;
    EXPECT_EQ(force[2].x > 0.0, rule != ContactRule::kNone) << name;
    EXPECT_EQ(force, ReferenceForces(body, Rule(rule), state)) << name;
    // The overlap reported is the unjoined pair's, whatever the rule.
    EXPECT_DOUBLE_EQ(contacts.DeepestUnjoinedOverlap(state.position), 0.25)
        << name;
  }
  // Without forces (the Bullet backend) nothing is added, but overlaps are
  // measured.
  Contacts measuring(body, Rule(ContactRule::kAll), /*forces=*/false);
  std::vector<Vec2> force(3);
  measuring.AddForces(state.position, state.velocity, force.data());
  EXPECT_EQ(force, std::vector<Vec2>(3));
  EXPECT_DOUBLE_EQ(measuring.DeepestUnjoinedOverlap(state.position), 0.25);
}

TEST(ContactsTest, CoincidentCentresGiveNoForceAndNoNaN) {
  const Body body = Cells({{1, 1}, {1, 1}}, {1.0, 1.0});
  const MotionState state = AtRest(body);
  Contacts contacts(body, Rule(ContactRule::kAll), true);
  std::vector<Vec2> force(2);
  contacts.AddForces(state.position, state.velocity, force.data());
  EXPECT_EQ(force[0], Vec2{});
  EXPECT_EQ(force[1], Vec2{});
  EXPECT_EQ(contacts.DeepestUnjoinedOverlap(state.position), 1.0);
}

// Random bodies squeezed and shaken over many steps: the pair list gives
// the forces and overlaps of testing every pair, bit for bit, before and
// after every rebuild.
// Also at positions met twice with other velocities, and with the
// overlap measured before the forces.
TEST(ContactsTest, PairListEqualsEveryPairBitForBit) {
  Source source(31);
  long long compared = 0, overlapping = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Body body = RandomBody(source, source.Int(3, 32), 7.0);
    body.radius.resize(body.nodes());
    for (double& r : body.radius) r = source.Uniform(0.6, 1.5);
    for (const ContactRule rule : {ContactRule::kUnjoined, ContactRule::kAll}) {
      const PhysicsParams p = Rule(rule);
      Contacts contacts(body, p, true);
      MotionState state = AtRest(body);
      for (int step = 0; step < 400; ++step) {
        for (int i = 0; i < body.nodes(); ++i) {
          state.velocity[i] = {source.Uniform(-2, 2), source.Uniform(-2, 2)};
          state.position[i] += state.velocity[i] * 0.02;
        }
        // Now and then the overlap is measured first, moving the shared
        // pair list to these positions before the forces look at them.
        if (step % 3 == 0) {
          ASSERT_EQ(contacts.DeepestUnjoinedOverlap(state.position),
                    ReferenceDeepest(body, state));
        }
        std::vector<Vec2> force(body.nodes());
        contacts.AddForces(state.position, state.velocity, force.data());
        ASSERT_EQ(force, ReferenceForces(body, p, state))
            << "trial " << trial << " step " << step;
        // The same positions again with other velocities, as an
        // integrator evaluates them (a sub-step's end, the next's start).
        for (int i = 0; i < body.nodes(); ++i) {
          state.velocity[i] = {source.Uniform(-2, 2), source.Uniform(-2, 2)};
        }
        std::vector<Vec2> again(body.nodes());
        contacts.AddForces(state.position, state.velocity, again.data());
        ASSERT_EQ(again, ReferenceForces(body, p, state))
            << "trial " << trial << " step " << step << ", other velocities";
        const double deepest = ReferenceDeepest(body, state);
        ASSERT_EQ(contacts.DeepestUnjoinedOverlap(state.position), deepest);
        ++compared;
        overlapping += deepest > 0.0;
      }
    }
  }
  EXPECT_GT(overlapping, compared / 4);  // The cases do overlap.
}

// Three cells in a row, 0-1-2, joined by springs 0-1 and 1-2 that the
// actuation shortens to a tenth: it drives the outer cells, which are not
// joined, into each other. Returns the deepest overlap over `steps` steps
// and the overlap at the end; fails the test if cell 2 ever passes cell 0.
struct Squeeze {
  double deepest = 0.0;
  double final = 0.0;
};

Squeeze SqueezeRow(const PhysicsParams& params, int steps) {
  const Body body =
      Cells({{0, 0}, {1.6, 0}, {3.2, 0}}, {1.0, 1.0, 1.0}, {{0, 1}, {1, 2}});
  SoftBody soft(body, params);
  soft.SetActuation(std::vector<double>(3, 0.0), std::vector<double>(3, 1.0));
  MotionState state = AtRest(body);
  Squeeze squeeze;
  for (int step = 0; step < steps; ++step) {
    soft.Step(&state);
    squeeze.final = soft.DeepestUnjoinedOverlap(state);
    squeeze.deepest = std::max(squeeze.deepest, squeeze.final);
    if (params.contact_rule != ContactRule::kNone) {
      EXPECT_GT(state.position[2].x, state.position[0].x) << "step " << step;
    }
  }
  EXPECT_EQ(CheckState(state, 1e6), "");
  return squeeze;
}

TEST(ContactsTest, UnjoinedCellsDrivenTogetherStayApartUnderEveryIntegrator) {
  const Integrator integrators[] = {
      Integrator::kSemiImplicitEuler, Integrator::kVelocityVerlet,
      Integrator::kRk4, Integrator::kSsprk3, Integrator::kRalston3};
  for (const Integrator integrator : integrators) {
    for (const DragUpdate drag : {DragUpdate::kExplicit, DragUpdate::kStable}) {
      for (const int substeps : {1, 3}) {
        for (const ContactRule rule :
             {ContactRule::kNone, ContactRule::kUnjoined}) {
          PhysicsParams p = Rule(rule);
          p.integrator = integrator;
          p.drag_update = drag;
          p.substeps = substeps;
          p.actuation_max = 0.45;  // L = max(0.1, 1 - 0.9) L0 = 0.1 L0.
          const std::string name = std::string(IntegratorName(integrator)) +
                                   " " + DragUpdateName(drag) + " x" +
                                   std::to_string(substeps) + " " +
                                   ContactRuleName(rule);
          SCOPED_TRACE(name);
          const Squeeze squeeze = SqueezeRow(p, 1000);
          if (rule == ContactRule::kNone) {
            // The springs bring the outer cells within 0.32 of each other.
            EXPECT_GT(squeeze.final, 0.8);
          } else {
            // At rest the contact holds the springs' pull, cell 1 in the
            // middle: 10 ((2 - delta) / 2 - 0.16) = 50 delta, so delta =
            // 8.4 / 55, 7.6% of r_0 + r_2.
            EXPECT_NEAR(squeeze.final, 8.4 / 55 / 2, 0.002);
            EXPECT_LT(squeeze.deepest, 0.5);
          }
        }
      }
    }
  }
}

TEST(ContactsTest, WithoutDragTheCentreOfMassStaysPutWithContacts) {
  Source source(5);
  for (int trial = 0; trial < 6; ++trial) {
    const Body body = RandomBody(source, source.Int(3, 32), 6.0);
    const int n = body.nodes();
    for (const ContactRule rule : {ContactRule::kUnjoined, ContactRule::kAll}) {
      PhysicsParams p = Rule(rule);
      p.actuation_max = 0.45;
      SoftBody soft(body, p);
      MotionState state = AtRest(body);
      const Vec2 start = CentreOfMass(state);
      std::vector<double> expand(n), contract(n);
      for (int step = 0; step < 500; ++step) {
        if (step % 50 == 0) {
          for (int i = 0; i < n; ++i) {
            expand[i] = source.Uniform(0, 1);
            contract[i] = source.Uniform(0, 1);
          }
          soft.SetActuation(expand, contract);
        }
        soft.Step(&state);
      }
      ASSERT_EQ(CheckState(state, 1e6), "") << "trial " << trial;
      EXPECT_LT(Length(CentreOfMass(state) - start), 1e-9)
          << "trial " << trial << " " << ContactRuleName(rule);
    }
  }
}

// ---------------------------------------------------------------------------
// Configuration.

TEST(ContactsConfigTest, DefaultIsUnjoinedAndRoundTrips) {
  PhysicsParams params;
  EXPECT_EQ(params.contact_rule, ContactRule::kUnjoined);
  params.contact_rule = ContactRule::kAll;
  params.contact_stiffness = 123.0;
  params.contact_damping = 0.25;
  const v1::PhysicsConfig message = PhysicsParamsToProto(params);
  EXPECT_FALSE(message.has_contacts());  // Only the v3 form is written.
  EXPECT_EQ(message.contact_rule(), v1::PhysicsConfig::ALL);
  PhysicsParams back;
  ASSERT_TRUE(PhysicsParamsFromProto(message, &back).ok());
  EXPECT_EQ(back.contact_rule, ContactRule::kAll);
  EXPECT_EQ(back.contact_stiffness, 123.0);
  EXPECT_EQ(back.contact_damping, 0.25);
}

TEST(ContactsConfigTest, ModelV2SwitchReadsAsNoneOrAll) {
  for (const bool contacts : {false, true}) {
    v1::PhysicsConfig message;
    message.set_contacts(contacts);
    PhysicsParams params;
    ASSERT_TRUE(PhysicsParamsFromProto(message, &params).ok());
    EXPECT_EQ(params.contact_rule,
              contacts ? ContactRule::kAll : ContactRule::kNone);
  }
}

TEST(ContactsConfigTest, BothFormsTogetherAreRefused) {
  v1::PhysicsConfig message;
  message.set_contacts(false);
  message.set_contact_rule(v1::PhysicsConfig::NONE);
  PhysicsParams params;
  params.contact_stiffness = 7.0;
  const Status status = PhysicsParamsFromProto(message, &params);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind("physics.contacts: ", 0), 0u)
      << status.message();
  EXPECT_EQ(params.contact_rule, ContactRule::kUnjoined);  // Unchanged.
}

TEST(ContactsConfigTest, OutOfRangeConstantsAreRefusedNamingTheField) {
  const auto refused = [](v1::PhysicsConfig message, const char* field) {
    PhysicsParams params;
    const Status status = PhysicsParamsFromProto(message, &params);
    EXPECT_FALSE(status.ok()) << field;
    EXPECT_EQ(status.message().rfind(field, 0), 0u) << status.message();
  };
  for (const double bad : {-1.0, std::nan(""), HUGE_VAL}) {
    v1::PhysicsConfig message;
    message.set_contact_stiffness(bad);
    refused(message, "physics.contact_stiffness: ");
    message.Clear();
    message.set_contact_damping(bad);
    refused(message, "physics.contact_damping: ");
  }
  v1::PhysicsConfig message;
  message.set_contact_rule(static_cast<v1::PhysicsConfig::ContactRule>(9));
  refused(message, "physics.contact_rule: ");
}

}  // namespace
}  // namespace animat
