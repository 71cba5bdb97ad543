// Tests of the motion physics (docs/model.md §7): spring, pressure and drag
// forces, rest lengths from actuation, semi-implicit Euler integration, and
// the state checks of model §8.3.
//
// Expected forces are computed in the tests from the model's equations (or
// by hand), never by calling the code under test.
#include "common/physics/soft_body.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <ostream>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/geometry/polygon.h"
#include "common/physics/physics_params.h"
#include "tests/physics/body_source.h"
#include "tests/test_util.h"

namespace animat {

// Lets gtest print vectors in failure messages (found by ADL).
inline void PrintTo(const Vec2& v, std::ostream* os) {
  *os << "(" << v.x << ", " << v.y << ")";
}

namespace {

using testing::AtRest;
using testing::MustBuild;
using testing::RandomBody;
using testing::Source;

// Signed area of the closed walk, shoelace (independent of the code).
double Shoelace(const std::vector<Vec2>& p, const std::vector<int>& walk) {
  double twice = 0.0;
  for (size_t k = 0; k < walk.size(); ++k) {
    const Vec2 a = p[walk[k]];
    const Vec2 b = p[walk[(k + 1) % walk.size()]];
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * twice;
}

PhysicsParams NoDrag() {
  PhysicsParams p;
  p.integrator = Integrator::kSemiImplicitEuler;  // As written in
  p.substeps = 1;                                 // model §7.6.
  // One step of dt holds contacts at k_c 200, not at the default 1500 (a
  // contact between two cells rings in 2.3 steps): model §7.10, §11.4.
  p.contact_stiffness = 200.0;
  p.drag_normal = 0.0;
  p.drag_tangential = 0.0;
  return p;
}

void ExpectVecNear(Vec2 actual, Vec2 expected, double tolerance,
                   const std::string& what) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << what;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << what;
}

// ---------------------------------------------------------------------------
// Equilibrium and conservation.

TEST(SoftBodyTest, BodyAtRestShapeWithoutActuationFeelsNoForce) {
  Source source(11);
  int with_chambers = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const Body body = RandomBody(source, source.Int(2, 30), 9.0);
    with_chambers += !body.chambers.empty();
    // Random centres may put unjoined cells closer than their radii, where
    // contacts push even at rest (contacts_test.cc); springs and pressure
    // alone here.
    PhysicsParams no_contacts;
    no_contacts.contact_rule = ContactRule::kNone;
    SoftBody soft(body, no_contacts);
    const std::vector<double> zero(body.nodes(), 0.0);
    for (int actuated = 0; actuated < 2; ++actuated) {
      if (actuated) soft.SetActuation(zero, zero);
      std::vector<Vec2> force;
      soft.ComputeForces(AtRest(body), &force);
      ASSERT_EQ(static_cast<int>(force.size()), body.nodes());
      for (int i = 0; i < body.nodes(); ++i) {
        EXPECT_LT(std::fabs(force[i].x), 1e-12)
            << "trial " << trial << " node " << i;
        EXPECT_LT(std::fabs(force[i].y), 1e-12)
            << "trial " << trial << " node " << i;
      }
    }
  }
  EXPECT_GT(with_chambers, 40);  // The cases exercise pressure.
}

TEST(SoftBodyTest, WithoutDragTheCentreOfMassStaysPutWhateverTheActuation) {
  Source source(2024);
  for (int trial = 0; trial < 6; ++trial) {
    const Body body = RandomBody(source, source.Int(3, 24), 7.0);
    const int n = body.nodes();
    PhysicsParams params = NoDrag();
    params.actuation_max = trial % 2 ? 0.45 : 0.2;
    SoftBody soft(body, params);
    MotionState state = AtRest(body);
    Vec2 mean;
    for (int i = 0; i < n; ++i) {
      state.velocity[i] = {source.Uniform(-0.5, 0.5),
                           source.Uniform(-0.5, 0.5)};
      mean += state.velocity[i];
    }
    mean = mean / static_cast<double>(n);
    for (Vec2& v : state.velocity) v -= mean;  // Zero total momentum.

    const Vec2 start = CentreOfMass(state);
    std::vector<double> expand(n), contract(n);
    std::vector<Vec2> force;
    double worst_sum = 0.0;
    for (int step = 0; step < 2000; ++step) {
      if (step % 50 == 0) {  // A new random actuation now and then.
        for (int i = 0; i < n; ++i) {
          expand[i] = source.Uniform(0, 1);
          contract[i] = source.Uniform(0, 1);
        }
        soft.SetActuation(expand, contract);
      }
      soft.ComputeForces(state, &force);
      Vec2 sum;
      for (const Vec2& f : force) sum += f;
      worst_sum = std::max(worst_sum, Length(sum));
      soft.Step(&state);
    }
    ASSERT_EQ(CheckState(state, 1e6), "") << "trial " << trial;
    EXPECT_LT(worst_sum, 1e-10) << "trial " << trial;
    EXPECT_LT(Length(CentreOfMass(state) - start), 1e-9)
        << "trial " << trial << " with " << n << " nodes";
  }
}

// ---------------------------------------------------------------------------
// Springs and rest lengths.

TEST(SoftBodyTest, RestLengthsStartAtL0AndFollowActuation) {
  const std::vector<Vec2> c = {{0, 0}, {4, 0}, {1, 3}};
  const Body body = MustBuild(c);
  ASSERT_EQ(body.springs.size(), 3u);
  PhysicsParams params;
  params.actuation_max = 0.45;
  SoftBody soft(body, params);
  ASSERT_EQ(soft.rest_lengths().size(), 3u);
  for (size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(soft.rest_lengths()[s], body.springs[s].rest_length);
  }

  const std::vector<double> expand = {1.0, 0.5, 0.0};
  const std::vector<double> contract = {0.0, 0.2, 0.9};
  soft.SetActuation(expand, contract);
  for (size_t s = 0; s < 3; ++s) {
    const int a = body.springs[s].a;
    const int b = body.springs[s].b;
    const double factor = std::max(
        0.1, 1.0 + 0.45 * (expand[a] + expand[b] - contract[a] - contract[b]));
    EXPECT_DOUBLE_EQ(soft.rest_lengths()[s],
                     factor * body.springs[s].rest_length)
        << "spring " << a << "-" << b;
  }
  // Spring 0-1 (L0 = 4) by hand: 1 + 0.45 (1 + 0.5 - 0 - 0.2) = 1.585;
  // spring 1-2 (L0 = sqrt(18)): 1 + 0.45 (0.5 + 0 - 0.2 - 0.9) = 0.73.
  int checked = 0;
  for (size_t s = 0; s < 3; ++s) {
    if (body.springs[s].a == 0 && body.springs[s].b == 1) {
      EXPECT_DOUBLE_EQ(soft.rest_lengths()[s], 1.585 * 4.0);
      ++checked;
    }
    if (body.springs[s].a == 1 && body.springs[s].b == 2) {
      EXPECT_DOUBLE_EQ(soft.rest_lengths()[s], 0.73 * std::sqrt(18.0));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 2);

  // Full contraction at A_max = 0.45: 1 - 0.9 = 0.1, the floor.
  const std::vector<double> none = {0, 0, 0};
  const std::vector<double> full = {1, 1, 1};
  soft.SetActuation(none, full);
  for (size_t s = 0; s < 3; ++s) {
    EXPECT_DOUBLE_EQ(soft.rest_lengths()[s], 0.1 * body.springs[s].rest_length);
  }
  // Full expansion: 1 + 0.9.
  soft.SetActuation(full, none);
  for (size_t s = 0; s < 3; ++s) {
    EXPECT_DOUBLE_EQ(soft.rest_lengths()[s], 1.9 * body.springs[s].rest_length);
  }
  // Equal expansion and contraction cancel.
  soft.SetActuation(full, full);
  for (size_t s = 0; s < 3; ++s) {
    EXPECT_DOUBLE_EQ(soft.rest_lengths()[s], body.springs[s].rest_length);
  }
}

TEST(SoftBodyTest, RestLengthNeverFallsBelowTheFloor) {
  const Body body = MustBuild({{0, 0}, {2, 0}});
  const std::vector<double> none = {0, 0};
  const std::vector<double> full = {1, 1};
  PhysicsParams params;
  params.actuation_max = 0.49;  // 1 - 0.98 = 0.02 < 0.1.
  SoftBody soft(body, params);
  soft.SetActuation(none, full);
  EXPECT_DOUBLE_EQ(soft.rest_lengths()[0], 0.1 * 2.0);
  // Half contraction of one node: 1 - 0.49 = 0.51, above the floor.
  soft.SetActuation(none, std::vector<double>{0.0, 1.0});
  EXPECT_DOUBLE_EQ(soft.rest_lengths()[0], 0.51 * 2.0);

  // The default A_max = 0.2 [paper]: full contraction gives 0.6 L0.
  SoftBody paper(body, PhysicsParams{});
  paper.SetActuation(none, full);
  EXPECT_DOUBLE_EQ(paper.rest_lengths()[0], 0.6 * 2.0);
  paper.SetActuation(full, none);
  EXPECT_DOUBLE_EQ(paper.rest_lengths()[0], 1.4 * 2.0);

  // The floor is a constant of the configuration.
  params.min_rest_fraction = 0.3;
  SoftBody floored(body, params);
  floored.SetActuation(none, full);
  EXPECT_DOUBLE_EQ(floored.rest_lengths()[0], 0.3 * 2.0);
}

// Two nodes joined by one spring, no chambers, no skin.
Body OneSpring(Vec2 a, Vec2 b, double rest_length) {
  Body body;
  body.position = {a, b};
  body.springs = {{0, 1, rest_length}};
  return body;
}

TEST(SoftBodyTest, StretchedSpringPullsItsEndsTogether) {
  const Body body = OneSpring({0, 0}, {1.5, 0}, 1.0);
  SoftBody soft(body, PhysicsParams{});  // k = 10.
  std::vector<Vec2> f(2);
  soft.AddSpringForces(AtRest(body), f.data());
  ExpectVecNear(f[0], {5.0, 0.0}, 1e-12, "node 0 pulled towards 1");
  ExpectVecNear(f[1], {-5.0, 0.0}, 1e-12, "node 1 pulled towards 0");
}

TEST(SoftBodyTest, CompressedSpringPushesItsEndsApart) {
  const Body body = OneSpring({0, 0}, {0, 0.5}, 1.0);
  SoftBody soft(body, PhysicsParams{});
  std::vector<Vec2> f(2);
  soft.AddSpringForces(AtRest(body), f.data());
  ExpectVecNear(f[0], {0.0, -5.0}, 1e-12, "node 0 pushed away");
  ExpectVecNear(f[1], {0.0, 5.0}, 1e-12, "node 1 pushed away");
}

TEST(SoftBodyTest, SpringForceIsStiffnessPlusDampingAlongTheSpring) {
  // u = (0.6, 0.8), l = 5, L = 4; (vb - va).u = 1.4.
  // F_a = [10 (5 - 4) + 0.5 * 1.4] u = 10.7 u.
  const Body body = OneSpring({1, 2}, {4, 6}, 4.0);
  SoftBody soft(body, PhysicsParams{});
  MotionState state = AtRest(body);
  state.velocity = {{0, 0}, {1, 1}};
  std::vector<Vec2> f(2);
  soft.AddSpringForces(state, f.data());
  ExpectVecNear(f[0], {6.42, 8.56}, 1e-12, "node a");
  ExpectVecNear(f[1], {-6.42, -8.56}, 1e-12, "node b");
}

TEST(SoftBodyTest, SpringDampingOpposesRelativeVelocityAlongTheSpring) {
  const Body body = OneSpring({0, 0}, {2, 0}, 2.0);  // At rest length.
  PhysicsParams params;
  params.damping = 0.5;
  SoftBody soft(body, params);
  MotionState state = AtRest(body);

  // Separating: each end is pulled back towards the other.
  state.velocity = {{-1, 0}, {1, 0}};
  std::vector<Vec2> f(2);
  soft.AddSpringForces(state, f.data());
  ExpectVecNear(f[0], {1.0, 0.0}, 1e-12, "separating, node 0");  // 0.5 * 2.
  ExpectVecNear(f[1], {-1.0, 0.0}, 1e-12, "separating, node 1");

  // Approaching: each end is held back.
  state.velocity = {{0.5, 0}, {-0.5, 0}};
  f.assign(2, Vec2{});
  soft.AddSpringForces(state, f.data());
  ExpectVecNear(f[0], {-0.5, 0.0}, 1e-12, "approaching, node 0");
  ExpectVecNear(f[1], {0.5, 0.0}, 1e-12, "approaching, node 1");

  // Relative velocity across the spring is not damped.
  state.velocity = {{0, -1}, {0, 1}};
  f.assign(2, Vec2{});
  soft.AddSpringForces(state, f.data());
  ExpectVecNear(f[0], {0.0, 0.0}, 1e-12, "rotating, node 0");
  ExpectVecNear(f[1], {0.0, 0.0}, 1e-12, "rotating, node 1");

  // Common translation is not damped.
  state.velocity = {{3, -2}, {3, -2}};
  f.assign(2, Vec2{});
  soft.AddSpringForces(state, f.data());
  ExpectVecNear(f[0], {0.0, 0.0}, 1e-12, "translating, node 0");
}

TEST(SoftBodyTest, ZeroLengthSpringExertsNoForceAndNoNaN) {
  // u = 0 when l = 0 (model §7.2); FP traps are on, so 0/0 would fail here.
  const Body body = OneSpring({1, 1}, {1, 1}, 1.0);
  SoftBody soft(body, PhysicsParams{});
  MotionState state = AtRest(body);
  state.velocity = {{1, 0}, {0, 1}};
  std::vector<Vec2> f;
  soft.ComputeForces(state, &f);
  EXPECT_EQ(f[0], Vec2(0, 0));
  EXPECT_EQ(f[1], Vec2(0, 0));
}

// ---------------------------------------------------------------------------
// Pressure.

Body Triangle345(double rest_area) {
  Body body;
  body.position = {{0, 0}, {3, 0}, {0, 4}};  // Counter-clockwise, S = 6.
  body.chambers = {{{0, 1, 2}, rest_area}};
  return body;
}

TEST(SoftBodyTest, CompressedTrianglePushesOutAlongItsEdgeNormals) {
  // S = 6, S0 = 8, c_p = 10: c_p (1 - S/S0) = 2.5.
  //   0->1: l = 3, n = (0, -1):        F = 2.5 * 3 * n = (0, -7.5)
  //   1->2: l = 5, n = (4, 3) / 5:     F = 2.5 * 5 * n = (10, 7.5)
  //   2->0: l = 4, n = (-4, 0) / 4:    F = 2.5 * 4 * n = (-10, 0)
  // Half of each to each end.
  const Body body = Triangle345(8.0);
  SoftBody soft(body, PhysicsParams{});
  std::vector<Vec2> f(3);
  soft.AddPressureForces(AtRest(body), f.data());
  ExpectVecNear(f[0], {-5.0, -3.75}, 1e-12, "node 0");
  ExpectVecNear(f[1], {5.0, 0.0}, 1e-12, "node 1");
  ExpectVecNear(f[2], {0.0, 3.75}, 1e-12, "node 2");
}

TEST(SoftBodyTest, StretchedTrianglePullsInAlongItsEdgeNormals) {
  // S = 6, S0 = 4: c_p (1 - S/S0) = -5, twice and opposite the above.
  const Body body = Triangle345(4.0);
  SoftBody soft(body, PhysicsParams{});
  std::vector<Vec2> f(3);
  soft.AddPressureForces(AtRest(body), f.data());
  ExpectVecNear(f[0], {10.0, 7.5}, 1e-12, "node 0");
  ExpectVecNear(f[1], {-10.0, 0.0}, 1e-12, "node 1");
  ExpectVecNear(f[2], {0.0, -7.5}, 1e-12, "node 2");
}

// docs/model.md §7.3's pressure written one edge at a time: the area by
// WalkArea, then each edge's push added to its start, then to its end, in
// the walk's order.
std::vector<Vec2> PressureOneEdgeAtATime(const Body& body,
                                         const std::vector<Vec2>& x,
                                         double cp) {
  std::vector<Vec2> force(body.nodes());
  for (const Chamber& ch : body.chambers) {
    const double area = WalkArea(
        x.data(), std::span<const int>(ch.walk.data(), ch.walk.size()));
    const double half = 0.5 * cp * (1.0 - area / ch.rest_area);
    const size_t m = ch.walk.size();
    for (size_t k = 0; k < m; ++k) {
      const int a = ch.walk[k];
      const int b = ch.walk[(k + 1) % m];
      const Vec2 push = Vec2{x[b].y - x[a].y, -(x[b].x - x[a].x)} * half;
      force[a] += push;
      force[b] += push;
    }
  }
  return force;
}

// The formula to rounding; and the bits of the rule written one edge at a
// time, on triangles and on longer walks alike.
TEST(SoftBodyTest, PressureMatchesTheModelFormulaOnRandomChambers) {
  Source source(8);
  int triangles = 0;
  int longer = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Body body = RandomBody(source, source.Int(3, 24), 6.0);
    for (const Chamber& ch : body.chambers) {
      ++(ch.walk.size() == 3 ? triangles : longer);
    }
    PhysicsParams params;
    params.pressure = source.Uniform(1, 20);
    SoftBody soft(body, params);
    MotionState state = AtRest(body);
    for (Vec2& x : state.position) {
      x += Vec2{source.Uniform(-0.2, 0.2), source.Uniform(-0.2, 0.2)};
    }
    std::vector<Vec2> expected(body.nodes());
    for (const Chamber& ch : body.chambers) {
      const double s = Shoelace(state.position, ch.walk);
      const size_t m = ch.walk.size();
      for (size_t k = 0; k < m; ++k) {
        const Vec2 a = state.position[ch.walk[k]];
        const Vec2 b = state.position[ch.walk[(k + 1) % m]];
        const double l = Length(b - a);
        const Vec2 n = Vec2{b.y - a.y, -(b.x - a.x)} / l;
        const Vec2 f = n * (params.pressure * l * (1.0 - s / ch.rest_area));
        expected[ch.walk[k]] += f * 0.5;
        expected[ch.walk[(k + 1) % m]] += f * 0.5;
      }
    }
    std::vector<Vec2> f(body.nodes());
    soft.AddPressureForces(state, f.data());
    const std::vector<Vec2> bits =
        PressureOneEdgeAtATime(body, state.position, params.pressure);
    for (int i = 0; i < body.nodes(); ++i) {
      ExpectVecNear(
          f[i], expected[i], 1e-9,
          "trial " + std::to_string(trial) + " node " + std::to_string(i));
      EXPECT_EQ(f[i].x, bits[i].x) << "trial " << trial << " node " << i;
      EXPECT_EQ(f[i].y, bits[i].y) << "trial " << trial << " node " << i;
    }
  }
  EXPECT_GT(triangles, 0);
  EXPECT_GT(longer, 0);
}

TEST(SoftBodyTest, PressurePushesOnAnEdgeDanglingIntoAChamberCancel) {
  // Ring 3-4-5-6-1-2 with cell 0 hanging from 3 into the chamber; the walk
  // passes 3-0 both ways.
  const std::vector<Vec2> c = {{8, 7}, {5.5, 0},  {9, 5.5}, {8.5, 7},
                               {9, 8}, {7.5, 10}, {0, 9.5}};
  const Body body = MustBuild(c);
  ASSERT_EQ(body.chambers.size(), 1u);
  ASSERT_EQ(body.chambers[0].walk.size(), 8u);
  SoftBody soft(body, PhysicsParams{});
  MotionState state = AtRest(body);
  for (Vec2& x : state.position) x = x * 0.9;  // Compressed: S < S0.
  EXPECT_LT(soft.ChamberArea(state, 0), body.chambers[0].rest_area);
  EXPECT_NEAR(soft.ChamberArea(state, 0),
              0.81 * Shoelace(c, {3, 4, 5, 6, 1, 2}), 1e-9);
  std::vector<Vec2> f(body.nodes());
  soft.AddPressureForces(state, f.data());
  EXPECT_LT(Length(f[0]), 1e-12) << "the dangling cell";
  EXPECT_GT(Length(f[4]), 0.1) << "a ring cell";
}

TEST(SoftBodyTest, CollapsedChamberEdgeGivesFinitePressure) {
  // Two nodes of a triangle on top of each other: a zero-length edge. The
  // pressure needs no division by its length (FP traps are on).
  Body body = Triangle345(8.0);
  body.skin = {{0, 1}, {0, 2}, {1, 2}};
  body.springs = {{0, 1, 3.0}, {0, 2, 4.0}, {1, 2, 5.0}};
  SoftBody soft(body, PhysicsParams{});
  MotionState state = AtRest(body);
  state.position[2] = state.position[1];
  state.velocity = {{1, 0}, {0, 1}, {-1, -1}};
  std::vector<Vec2> f;
  soft.ComputeForces(state, &f);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(IsFinite(f[i])) << "node " << i;
  soft.Step(&state);
  EXPECT_EQ(CheckState(state, 1e6), "");
}

// Scales a state's positions about their mean.
void ScaleAboutCentre(MotionState* state, double factor) {
  const Vec2 centre = CentreOfMass(*state);
  for (Vec2& x : state->position) x = centre + (x - centre) * factor;
}

TEST(SoftBodyTest, CompressedChamberReturnsToItsRestArea) {
  const std::vector<std::vector<Vec2>> shapes = {
      {{0, 0}, {2, 0}, {1, std::sqrt(3.0)}},  // Triangle.
      {{0, 0}, {2, 0}, {2, 2}, {0, 2}},       // Square (no diagonals).
  };
  for (const std::vector<Vec2>& shape : shapes) {
    const Body body = MustBuild(shape);
    ASSERT_EQ(body.chambers.size(), 1u);
    const double s0 = body.chambers[0].rest_area;
    for (double stiffness : {0.0, 10.0}) {
      PhysicsParams params;
      params.stiffness = stiffness;
      SoftBody soft(body, params);
      MotionState state = AtRest(body);
      ScaleAboutCentre(&state, 0.8);
      EXPECT_NEAR(soft.ChamberArea(state, 0), 0.64 * s0, 1e-12);
      for (int step = 0; step < 2000; ++step) soft.Step(&state);
      ASSERT_EQ(CheckState(state, 1e6), "");
      EXPECT_NEAR(soft.ChamberArea(state, 0) / s0, 1.0, 0.01)
          << shape.size() << " cells, stiffness " << stiffness;
    }
  }
}

TEST(SoftBodyTest, ChamberPushedInsideOutTurnsBack) {
  // One vertex of a triangle reflected across the opposite edge: the area
  // along the rest walk is -S0. (Asymmetric triangles: an exactly symmetric
  // one can stall on its axis, see below.)
  const std::vector<std::vector<Vec2>> triangles = {
      {{0, 0}, {4, 0}, {1, 3}}, {{0, 0}, {3, 0}, {1.2, 2.5}}};
  for (const std::vector<Vec2>& c : triangles) {
    const Body body = MustBuild(c);
    ASSERT_EQ(body.chambers.size(), 1u);
    const double s0 = body.chambers[0].rest_area;
    for (double stiffness : {0.0, 10.0}) {
      PhysicsParams params;
      params.stiffness = stiffness;
      SoftBody soft(body, params);
      MotionState state = AtRest(body);
      state.position[2] = {c[2].x, -c[2].y};
      EXPECT_NEAR(soft.ChamberArea(state, 0), -s0, 1e-12);
      // The pressure pushes the reflected apex back across the edge 0-1
      // (towards +y) and the edge's ends the other way.
      std::vector<Vec2> f(3);
      soft.AddPressureForces(state, f.data());
      EXPECT_GT(f[2].y, 0.0);
      EXPECT_LT(f[0].y, 0.0);
      EXPECT_LT(f[1].y, 0.0);
      for (int step = 0; step < 100; ++step) soft.Step(&state);
      EXPECT_GT(soft.ChamberArea(state, 0), 0.0)
          << "apex " << c[2].x << ", stiffness " << stiffness;
      for (int step = 0; step < 900; ++step) soft.Step(&state);
      ASSERT_EQ(CheckState(state, 1e6), "");
      EXPECT_NEAR(soft.ChamberArea(state, 0) / s0, 1.0, 0.01)
          << "apex " << c[2].x << ", stiffness " << stiffness;
    }
  }
}

// ---------------------------------------------------------------------------
// Drag.

TEST(SoftBodyTest, DragIsQuadraticAndOpposesTheEdgeVelocity) {
  // One skin edge, random end velocities: the force from model §7.4, with the
  // centre velocity v = (vi + vj)/2, half to each end.
  Source source(41);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec2 a{source.Uniform(-3, 3), source.Uniform(-3, 3)};
    const Vec2 b{source.Uniform(-3, 3), source.Uniform(-3, 3)};
    Body body;
    body.position = {a, b};
    body.skin = {{0, 1}};
    PhysicsParams params;
    params.drag_normal = source.Uniform(0.1, 3);
    params.drag_tangential = source.Uniform(0.001, 0.5);
    SoftBody soft(body, params);
    MotionState state = AtRest(body);
    state.velocity = {{source.Uniform(-2, 2), source.Uniform(-2, 2)},
                      {source.Uniform(-2, 2), source.Uniform(-2, 2)}};
    const double l = Length(b - a);
    const Vec2 t = (b - a) / l;
    const Vec2 n{-t.y, t.x};  // Either normal gives the same force.
    const Vec2 v = (state.velocity[0] + state.velocity[1]) * 0.5;
    const double vt = Dot(v, t);
    const double vn = Dot(v, n);
    const double st = vt > 0 ? 1.0 : (vt < 0 ? -1.0 : 0.0);
    const double sn = vn > 0 ? 1.0 : (vn < 0 ? -1.0 : 0.0);
    const Vec2 total = t * (-params.drag_tangential * l * st * vt * vt) +
                       n * (-params.drag_normal * l * sn * vn * vn);
    std::vector<Vec2> f(2);
    soft.AddDragForces(state, f.data());
    const std::string what = "trial " + std::to_string(trial);
    ExpectVecNear(f[0], total * 0.5, 1e-12, what);
    ExpectVecNear(f[1], total * 0.5, 1e-12, what);
    EXPECT_LE(Dot(f[0] + f[1], v), 0.0) << what;  // Never pushes along.
  }
}

// A two-cell body (one spring at rest length, the skin that edge, no
// chamber) translating with velocity v0 along `direction`, a unit vector
// along or across the edge. Returns the relative errors of the speed and
// of the distance travelled after `steps` steps of dt, against the exact
// solution of M dv/dt = -D v^2: v(t) = v0 / (1 + D v0 t / M) and
// s(t) = (M / D) ln(1 + D v0 t / M), with M = 2 m and D = d l.
struct DragRun {
  double speed_error;
  double distance_error;
  double off_axis;  // Largest velocity component off `direction`.
};
DragRun TranslateEdge(const PhysicsParams& params, double d, Vec2 direction,
                      double v0, double dt, int steps) {
  // l = 2 along (0.6, 0.8).
  const std::vector<Vec2> c = {{1, 1}, {2.2, 2.6}};
  const Body body = MustBuild(c);
  EXPECT_EQ(body.skin.size(), 1u);
  EXPECT_TRUE(body.chambers.empty());
  PhysicsParams p = params;
  p.dt = dt;
  SoftBody soft(body, p);
  MotionState state = AtRest(body);
  state.velocity = {direction * v0, direction * v0};
  const Vec2 start = CentreOfMass(state);
  const Vec2 across{-direction.y, direction.x};
  double off_axis = 0.0;
  for (int step = 0; step < steps; ++step) {
    soft.Step(&state);
    for (const Vec2& v : state.velocity) {
      off_axis = std::max(off_axis, std::fabs(Dot(v, across)));
    }
  }
  const double big_m = 2.0 * p.mass;
  const double big_d = d * 2.0;
  const double t = dt * steps;
  const double v_exact = v0 / (1.0 + big_d * v0 * t / big_m);
  const double s_exact = big_m / big_d * std::log(1.0 + big_d * v0 * t / big_m);
  // The ends move together (the spring stays at its rest length).
  EXPECT_LT(Length(state.velocity[0] - state.velocity[1]), 1e-12);
  const double v =
      Dot((state.velocity[0] + state.velocity[1]) * 0.5, direction);
  const double s = Dot(CentreOfMass(state) - start, direction);
  return {(v - v_exact) / v_exact, (s - s_exact) / s_exact, off_axis};
}

TEST(SoftBodyTest, EdgeMovingAcrossItselfSlowsAsQuadraticNormalDragPredicts) {
  PhysicsParams params;
  params.integrator = Integrator::kSemiImplicitEuler;
  params.mass = 2.0;  // M = 4, D = d_N l = 2: D / M = 0.5.
  params.drag_normal = 1.0;
  params.drag_tangential = 0.005;
  const Vec2 normal{0.8, -0.6};
  for (double sign : {1.0, -1.0}) {
    const DragRun coarse = TranslateEdge(params, params.drag_normal,
                                         normal * sign, 1.0, 0.05, 200);
    const DragRun fine = TranslateEdge(params, params.drag_normal,
                                       normal * sign, 1.0, 0.025, 400);
    EXPECT_LT(std::fabs(coarse.speed_error), 1e-2) << "sign " << sign;
    EXPECT_LT(std::fabs(coarse.distance_error), 2e-2) << "sign " << sign;
    // Semi-implicit Euler is first order: halving dt halves the error.
    const double ratio = coarse.speed_error / fine.speed_error;
    EXPECT_GT(ratio, 1.8) << "sign " << sign;
    EXPECT_LT(ratio, 2.2) << "sign " << sign;
    const double distance_ratio = coarse.distance_error / fine.distance_error;
    EXPECT_GT(distance_ratio, 1.8) << "sign " << sign;
    EXPECT_LT(distance_ratio, 2.2) << "sign " << sign;
    EXPECT_LT(coarse.off_axis, 1e-12);
  }
}

TEST(SoftBodyTest,
     EdgeMovingAlongItselfSlowsAsQuadraticTangentialDragPredicts) {
  PhysicsParams params;
  params.integrator = Integrator::kSemiImplicitEuler;
  params.mass = 1.0;  // M = 2, D = d_T l = 0.5: D / M = 0.25.
  params.drag_tangential = 0.25;
  params.drag_normal = 200 * 0.25;  // d_N = 200 d_T [paper]; unused here.
  const Vec2 tangent{0.6, 0.8};
  for (double sign : {1.0, -1.0}) {
    const DragRun coarse = TranslateEdge(params, params.drag_tangential,
                                         tangent * sign, 2.0, 0.05, 200);
    const DragRun fine = TranslateEdge(params, params.drag_tangential,
                                       tangent * sign, 2.0, 0.025, 400);
    EXPECT_LT(std::fabs(coarse.speed_error), 1e-2) << "sign " << sign;
    EXPECT_LT(std::fabs(coarse.distance_error), 2e-2) << "sign " << sign;
    const double ratio = coarse.speed_error / fine.speed_error;
    EXPECT_GT(ratio, 1.8) << "sign " << sign;
    EXPECT_LT(ratio, 2.2) << "sign " << sign;
    const double distance_ratio = coarse.distance_error / fine.distance_error;
    EXPECT_GT(distance_ratio, 1.8) << "sign " << sign;
    EXPECT_LT(distance_ratio, 2.2) << "sign " << sign;
    EXPECT_LT(coarse.off_axis, 1e-12);
  }
}

TEST(SoftBodyTest, OnlySkinEdgesFeelDrag) {
  // A square with its centre: four chambers, the centre's springs are not
  // skin, so moving the centre alone drags nothing.
  const Body body = MustBuild({{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 1}});
  ASSERT_EQ(body.chambers.size(), 4u);
  ASSERT_EQ(body.skin.size(), 4u);
  for (const IndexEdge& e : body.skin) {
    EXPECT_NE(e.a, 4);
    EXPECT_NE(e.b, 4);
  }
  SoftBody soft(body, PhysicsParams{});
  MotionState state = AtRest(body);
  state.velocity[4] = {1, 2};
  std::vector<Vec2> f(5);
  soft.AddDragForces(state, f.data());
  for (int i = 0; i < 5; ++i) EXPECT_EQ(f[i], Vec2(0, 0)) << "node " << i;
  // Moving a corner drags its two skin edges.
  state.velocity[4] = {0, 0};
  state.velocity[0] = {1, 2};
  soft.AddDragForces(state, f.data());
  EXPECT_LT(f[0].x, 0.0);
  EXPECT_LT(f[0].y, 0.0);
}

// ---------------------------------------------------------------------------
// Integration and checks.

TEST(SoftBodyTest, StepIsSemiImplicitEulerWithForcesFromTheCurrentState) {
  // k (l - L) = 10 * 0.5 = 5; damping 0.5 * ((1) - (-1)) = 1: F_0 = (6, 0).
  // v_0 = -1 + 6 / 2 * 0.1 = -0.7, then x_0 = 0 + (-0.7) * 0.1 (new v).
  const Body body = OneSpring({0, 0}, {1.5, 0}, 1.0);
  PhysicsParams params = NoDrag();
  params.mass = 2.0;
  params.dt = 0.1;
  SoftBody soft(body, params);
  MotionState state = AtRest(body);
  state.velocity = {{-1, 0.5}, {1, 0}};
  soft.Step(&state);
  ExpectVecNear(state.velocity[0], {-0.7, 0.5}, 1e-14, "v0");
  ExpectVecNear(state.velocity[1], {0.7, 0.0}, 1e-14, "v1");
  ExpectVecNear(state.position[0], {-0.07, 0.05}, 1e-14, "x0");
  ExpectVecNear(state.position[1], {1.57, 0.0}, 1e-14, "x1");
}

TEST(SoftBodyTest, ComputeForcesIsTheSumOfTheFourFamilies) {
  Source source(17);
  const Body body = RandomBody(source, 12, 6.0);
  SoftBody soft(body, PhysicsParams{});
  MotionState state = AtRest(body);
  for (int i = 0; i < body.nodes(); ++i) {
    state.position[i] +=
        Vec2{source.Uniform(-0.3, 0.3), source.Uniform(-0.3, 0.3)};
    state.velocity[i] = {source.Uniform(-1, 1), source.Uniform(-1, 1)};
  }
  std::vector<Vec2> total;
  soft.ComputeForces(state, &total);
  std::vector<Vec2> parts(body.nodes());
  soft.AddSpringForces(state, parts.data());
  soft.AddPressureForces(state, parts.data());
  soft.AddDragForces(state, parts.data());
  soft.AddContactForces(state, parts.data());
  for (int i = 0; i < body.nodes(); ++i) {
    ExpectVecNear(total[i], parts[i], 1e-12, "node " + std::to_string(i));
  }
}

TEST(SoftBodyTest, SimulationIsDeterministic) {
  Source source(4);
  const Body body = RandomBody(source, 16, 7.0);
  std::vector<double> expand(body.nodes()), contract(body.nodes());
  for (int i = 0; i < body.nodes(); ++i) {
    expand[i] = source.Uniform(0, 1);
    contract[i] = source.Uniform(0, 1);
  }
  MotionState runs[2];
  for (MotionState& state : runs) {
    SoftBody soft(body, PhysicsParams{});
    soft.SetActuation(expand, contract);
    state = AtRest(body);
    for (int step = 0; step < 300; ++step) soft.Step(&state);
  }
  EXPECT_EQ(runs[0].position, runs[1].position);
  EXPECT_EQ(runs[0].velocity, runs[1].velocity);
}

TEST(SoftBodyTest, CheckStateAcceptsAFiniteStateWithinBounds) {
  MotionState state;
  state.position = {{0, 0}, {1e6, -1e6}, {-3, 2}};
  state.velocity = {{1, 1}, {0, 0}, {-1e300, 5}};
  EXPECT_EQ(CheckState(state, 1e6), "");  // |x| = 1e6 is not beyond.
}

TEST(SoftBodyTest, CheckStateNamesTheNodeWithANaNPosition) {
  testing::FpTrapsOff traps_off;
  MotionState state;
  state.position = {
      {0, 0}, {1, 0}, {2, std::numeric_limits<double>::quiet_NaN()}};
  state.velocity.assign(3, Vec2{});
  const std::string reason = CheckState(state, 1e6);
  EXPECT_NE(reason, "");
  EXPECT_NE(reason.find("node 2"), std::string::npos) << reason;
}

TEST(SoftBodyTest, CheckStateNamesTheNodeWithAnInfiniteVelocity) {
  testing::FpTrapsOff traps_off;
  MotionState state;
  state.position = {{0, 0}, {1, 0}, {2, 0}};
  state.velocity = {
      {0, 0}, {-std::numeric_limits<double>::infinity(), 0}, {0, 0}};
  const std::string reason = CheckState(state, 1e6);
  EXPECT_NE(reason, "");
  EXPECT_NE(reason.find("node 1"), std::string::npos) << reason;
  EXPECT_NE(reason.find("velocity"), std::string::npos) << reason;
}

TEST(SoftBodyTest, CheckStateNamesTheNodeBeyondTheCoordinateBound) {
  MotionState state;
  state.position = {{0, 0}, {1, 0}, {2, 0}, {3, -1.5e6}};
  state.velocity.assign(4, Vec2{});
  std::string reason = CheckState(state, 1e6);
  EXPECT_NE(reason, "");
  EXPECT_NE(reason.find("node 3"), std::string::npos) << reason;

  state.position[3] = {3, 0};
  state.position[0] = {1e6 * (1 + 1e-15), 0};
  reason = CheckState(state, 1e6);
  EXPECT_NE(reason.find("node 0"), std::string::npos) << reason;

  // The bound is a parameter.
  state.position[0] = {0, 0};
  state.position[2] = {0, 20};
  reason = CheckState(state, 10);
  EXPECT_NE(reason.find("node 2"), std::string::npos) << reason;
}

TEST(SoftBodyTest, CentreOfMassIsTheMeanPosition) {
  MotionState state;
  state.position = {{0, 0}, {4, 0}, {2, 6}};
  state.velocity.assign(3, Vec2{});
  ExpectVecNear(CentreOfMass(state), {2, 2}, 1e-15, "centre");
}

}  // namespace
}  // namespace animat
