// Tests of the physics scene read from an animat.v1.Scene and of bodies
// written as animat.v1.Body: validation with errors naming the field,
// defaults where the file is silent (docs/model.md §7.8's constants), round
// trips.
#include "common/physics/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "animat/v1/body.pb.h"
#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"
#include "tests/test_util.h"

namespace animat {

// Lets gtest print vectors in failure messages (found by ADL).
inline void PrintTo(const Vec2& v, std::ostream* os) {
  *os << "(" << v.x << ", " << v.y << ")";
}

namespace {

// A valid scene: a triangle 0, 1, 2 with a fourth node hanging from 2.
v1::Scene ValidScene() {
  v1::Scene scene;
  v1::Body* body = scene.mutable_body();
  const double xy[4][2] = {{0, 0}, {4, 0}, {1, 3}, {1, 6}};
  for (int i = 0; i < 4; ++i) {
    v1::Node* node = body->add_nodes();
    node->set_x(xy[i][0]);
    node->set_y(xy[i][1]);
    node->set_vx(0.1 * i);
    node->set_vy(-0.2 * i);
    node->set_expand(0.25 * i);
    node->set_contract(1.0 - 0.25 * i);
  }
  const int springs[4][2] = {{0, 1}, {1, 2}, {0, 2}, {2, 3}};
  for (const auto& s : springs) {
    v1::Spring* spring = body->add_springs();
    spring->set_a(s[0]);
    spring->set_b(s[1]);
    spring->set_rest_length(1.5 + s[0] + s[1]);
  }
  v1::Chamber* chamber = body->add_chambers();
  for (int v : {0, 1, 2}) chamber->add_nodes(v);
  chamber->set_rest_area(6.0);
  for (const auto& s : springs) {
    v1::Edge* edge = body->add_skin();
    edge->set_a(s[0]);
    edge->set_b(s[1]);
  }
  return scene;
}

// Expects SceneFromProto to fail with kInvalidArgument and a message that
// starts with (names) `field`.
void ExpectErrorNaming(const v1::Scene& message, const std::string& field) {
  Result<Scene> scene = SceneFromProto(message);
  ASSERT_FALSE(scene.ok()) << "expected an error naming " << field;
  EXPECT_EQ(scene.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(scene.status().message().find(field), std::string::npos)
      << "message: " << scene.status().message() << "\nfield: " << field;
}

// Applies `edit` to a valid scene and expects an error naming `field`.
void ExpectEditRejected(const std::function<void(v1::Scene*)>& edit,
                        const std::string& field) {
  v1::Scene message = ValidScene();
  edit(&message);
  SCOPED_TRACE(field);
  ExpectErrorNaming(message, field);
}

TEST(SceneTest, ValidSceneConverts) {
  Result<Scene> scene = SceneFromProto(ValidScene());
  ASSERT_TRUE(scene.ok()) << scene.status().ToString();
  const Body& body = scene->body;
  ASSERT_EQ(body.nodes(), 4);
  EXPECT_EQ(body.position[2].x, 1.0);
  EXPECT_EQ(body.position[2].y, 3.0);
  ASSERT_EQ(scene->state.position.size(), 4u);
  ASSERT_EQ(scene->state.velocity.size(), 4u);
  EXPECT_EQ(scene->state.position[3].x, 1.0);
  EXPECT_EQ(scene->state.position[3].y, 6.0);
  EXPECT_DOUBLE_EQ(scene->state.velocity[3].x, 0.3);
  EXPECT_DOUBLE_EQ(scene->state.velocity[3].y, -0.6);
  ASSERT_EQ(scene->expand.size(), 4u);
  ASSERT_EQ(scene->contract.size(), 4u);
  EXPECT_EQ(scene->expand[1], 0.25);
  EXPECT_EQ(scene->contract[1], 0.75);
  EXPECT_EQ(scene->expand[3], 0.75);
  EXPECT_EQ(scene->contract[3], 0.25);

  ASSERT_EQ(body.springs.size(), 4u);
  EXPECT_EQ(body.springs[1].a, 1);
  EXPECT_EQ(body.springs[1].b, 2);
  EXPECT_EQ(body.springs[1].rest_length, 4.5);
  EXPECT_EQ(body.springs[3].a, 2);
  EXPECT_EQ(body.springs[3].b, 3);
  ASSERT_EQ(body.chambers.size(), 1u);
  EXPECT_EQ(body.chambers[0].walk, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(body.chambers[0].rest_area, 6.0);
  ASSERT_EQ(body.skin.size(), 4u);
  EXPECT_EQ(body.skin[3].a, 2);
  EXPECT_EQ(body.skin[3].b, 3);
}

TEST(SceneTest, AbsentPhysicsTakesTheModelDefaults) {
  Result<Scene> scene = SceneFromProto(ValidScene());
  ASSERT_TRUE(scene.ok()) << scene.status().ToString();
  const PhysicsParams& p = scene->params;
  // model §7.8: m = 1, k = 10, gamma = 0.5, c_p = 10, d_N = 1, dt = 0.05,
  // A_max = 0.2 [paper]; d_T = d_N / 200 [paper]; floor 0.1.
  EXPECT_EQ(p.mass, 1.0);
  EXPECT_EQ(p.stiffness, 10.0);
  EXPECT_EQ(p.damping, 0.5);
  EXPECT_EQ(p.pressure, 10.0);
  EXPECT_EQ(p.drag_normal, 1.0);
  EXPECT_DOUBLE_EQ(p.drag_tangential, 1.0 / 200.0);
  EXPECT_EQ(p.dt, 0.05);
  EXPECT_EQ(p.actuation_max, 0.2);
  EXPECT_EQ(p.min_rest_fraction, 0.1);
}

TEST(SceneTest, PresentPhysicsFieldsOverrideOnlyThemselves) {
  v1::Scene message = ValidScene();
  message.mutable_physics()->set_stiffness(3.0);
  message.mutable_physics()->set_dt(0.01);
  message.mutable_physics()->set_damping(0.0);  // Present though zero.
  Result<Scene> scene = SceneFromProto(message);
  ASSERT_TRUE(scene.ok()) << scene.status().ToString();
  EXPECT_EQ(scene->params.stiffness, 3.0);
  EXPECT_EQ(scene->params.dt, 0.01);
  EXPECT_EQ(scene->params.damping, 0.0);
  EXPECT_EQ(scene->params.mass, 1.0);
  EXPECT_EQ(scene->params.pressure, 10.0);
  EXPECT_EQ(scene->params.actuation_max, 0.2);
}

TEST(SceneTest, SpringNodeOutOfRangeIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_body()->mutable_springs(1)->set_b(4); },
      "body.springs[1].b");
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_body()->mutable_springs(2)->set_a(99); },
      "body.springs[2].a");
}

TEST(SceneTest, ChamberNodeOutOfRangeIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_chambers(0)->set_nodes(2, 4);
      },
      "body.chambers[0].nodes[2]");
}

TEST(SceneTest, SkinNodeOutOfRangeIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_body()->mutable_skin(3)->set_a(7); },
      "body.skin[3].a");
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_body()->mutable_skin(0)->set_b(4); },
      "body.skin[0].b");
}

TEST(SceneTest, SpringJoiningANodeToItselfIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_body()->mutable_springs(2)->set_b(0); },
      "body.springs[2]");
}

TEST(SceneTest, SkinEdgeJoiningANodeToItselfIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_body()->mutable_skin(1)->set_a(2); },
      "body.skin[1]");
}

TEST(SceneTest, ChamberWithTwoNodesIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_chambers(0)->mutable_nodes()->RemoveLast();
      },
      "body.chambers[0]");
}

TEST(SceneTest, NonPositiveRestAreaIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_chambers(0)->set_rest_area(0.0);
      },
      "body.chambers[0].rest_area");
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_chambers(0)->set_rest_area(-6.0);
      },
      "body.chambers[0].rest_area");
}

TEST(SceneTest, NegativeRestLengthIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_springs(3)->set_rest_length(-1.0);
      },
      "body.springs[3].rest_length");
}

TEST(SceneTest, ActuationOutsideTheUnitIntervalIsRejected) {
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_nodes(1)->set_expand(1.5);
      },
      "body.nodes[1].expand");
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_nodes(2)->set_expand(-0.01);
      },
      "body.nodes[2].expand");
  ExpectEditRejected(
      [](v1::Scene* m) {
        m->mutable_body()->mutable_nodes(0)->set_contract(1.0001);
      },
      "body.nodes[0].contract");
  // The ends of [0, 1] are allowed.
  v1::Scene message = ValidScene();
  message.mutable_body()->mutable_nodes(0)->set_expand(1.0);
  message.mutable_body()->mutable_nodes(0)->set_contract(0.0);
  EXPECT_TRUE(SceneFromProto(message).ok());
}

TEST(SceneTest, NonFiniteNodeValuesAreRejected) {
  testing::FpTrapsOff traps_off;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  ExpectEditRejected(
      [&](v1::Scene* m) { m->mutable_body()->mutable_nodes(0)->set_x(nan); },
      "body.nodes[0].x");
  ExpectEditRejected(
      [&](v1::Scene* m) { m->mutable_body()->mutable_nodes(3)->set_y(-inf); },
      "body.nodes[3].y");
  ExpectEditRejected(
      [&](v1::Scene* m) { m->mutable_body()->mutable_nodes(2)->set_vx(inf); },
      "body.nodes[2].vx");
  ExpectEditRejected(
      [&](v1::Scene* m) {
        m->mutable_body()->mutable_nodes(1)->set_expand(nan);
      },
      "body.nodes[1].expand");
  ExpectEditRejected(
      [&](v1::Scene* m) {
        m->mutable_body()->mutable_springs(0)->set_rest_length(nan);
      },
      "body.springs[0].rest_length");
  ExpectEditRejected(
      [&](v1::Scene* m) {
        m->mutable_body()->mutable_chambers(0)->set_rest_area(inf);
      },
      "body.chambers[0].rest_area");
}

TEST(SceneTest, PhysicsConstantsOutOfRangeAreRejected) {
  ExpectEditRejected([](v1::Scene* m) { m->mutable_physics()->set_mass(-1); },
                     "physics.mass");
  ExpectEditRejected([](v1::Scene* m) { m->mutable_physics()->set_mass(0); },
                     "physics.mass");
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_physics()->set_actuation_max(0.5); },
      "physics.actuation_max");
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_physics()->set_actuation_max(-0.1); },
      "physics.actuation_max");
  ExpectEditRejected([](v1::Scene* m) { m->mutable_physics()->set_dt(0); },
                     "physics.dt");
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_physics()->set_stiffness(-10); },
      "physics.stiffness");
  ExpectEditRejected(
      [](v1::Scene* m) { m->mutable_physics()->set_drag_normal(-1); },
      "physics.drag_normal");
  // A_max just below 0.5 and 0 are valid (model §7.2: [0, 0.5)).
  v1::Scene message = ValidScene();
  message.mutable_physics()->set_actuation_max(0.4999);
  EXPECT_TRUE(SceneFromProto(message).ok());
  message.mutable_physics()->set_actuation_max(0.0);
  EXPECT_TRUE(SceneFromProto(message).ok());
}

TEST(SceneTest, SceneWithoutNodesIsRejected) {
  v1::Scene message;
  ExpectErrorNaming(message, "body.nodes");
}

TEST(SceneTest, BodyToProtoRoundTripsThroughSceneFromProto) {
  const std::vector<Vec2> centres = {{0, 0},     {2.1, 0.2}, {1.0, 1.9},
                                     {3.3, 1.7}, {0.4, 3.6}, {2.5, 3.9},
                                     {4.6, 0.1}, {1.9, 5.8}};
  Result<Body> built = BuildBody(centres);
  ASSERT_TRUE(built.ok()) << built.status().ToString();
  const Body& body = *built;
  ASSERT_FALSE(body.chambers.empty());
  std::vector<double> expand, contract;
  for (int i = 0; i < body.nodes(); ++i) {
    expand.push_back(i / 8.0);
    contract.push_back(1.0 - i / 16.0);
  }
  v1::Scene message;
  *message.mutable_body() = BodyToProto(body, expand, contract);
  EXPECT_EQ(message.body().nodes_size(), body.nodes());
  EXPECT_EQ(message.body().springs_size(),
            static_cast<int>(body.springs.size()));
  EXPECT_EQ(message.body().chambers_size(),
            static_cast<int>(body.chambers.size()));
  EXPECT_EQ(message.body().skin_size(), static_cast<int>(body.skin.size()));

  // Through the wire format too.
  v1::Scene parsed;
  ASSERT_TRUE(parsed.ParseFromString(message.SerializeAsString()));
  Result<Scene> scene = SceneFromProto(parsed);
  ASSERT_TRUE(scene.ok()) << scene.status().ToString();
  const Body& back = scene->body;
  ASSERT_EQ(back.nodes(), body.nodes());
  for (int i = 0; i < body.nodes(); ++i) {
    EXPECT_EQ(back.position[i], body.position[i]) << "node " << i;
    EXPECT_EQ(scene->state.position[i], body.position[i]) << "node " << i;
    EXPECT_EQ(scene->state.velocity[i], Vec2(0, 0)) << "node " << i;
    EXPECT_EQ(scene->expand[i], expand[i]);
    EXPECT_EQ(scene->contract[i], contract[i]);
  }
  ASSERT_EQ(back.springs.size(), body.springs.size());
  for (size_t s = 0; s < body.springs.size(); ++s) {
    EXPECT_EQ(back.springs[s].a, body.springs[s].a);
    EXPECT_EQ(back.springs[s].b, body.springs[s].b);
    EXPECT_EQ(back.springs[s].rest_length, body.springs[s].rest_length);
  }
  ASSERT_EQ(back.chambers.size(), body.chambers.size());
  for (size_t c = 0; c < body.chambers.size(); ++c) {
    EXPECT_EQ(back.chambers[c].walk, body.chambers[c].walk);
    EXPECT_EQ(back.chambers[c].rest_area, body.chambers[c].rest_area);
  }
  EXPECT_EQ(back.skin, body.skin);

  // The converted scene is at rest: no force.
  SoftBody soft(back, scene->params);
  std::vector<Vec2> force;
  soft.ComputeForces(scene->state, &force);
  for (const Vec2& f : force) EXPECT_LT(Length(f), 1e-12);
}

TEST(SceneTest, BodyToProtoWithoutActuationWritesZeros) {
  Result<Body> body = BuildBody(std::vector<Vec2>{{0, 0}, {2, 0}, {1, 1.5}});
  ASSERT_TRUE(body.ok());
  const v1::Body message = BodyToProto(*body, {}, {});
  ASSERT_EQ(message.nodes_size(), 3);
  for (const v1::Node& node : message.nodes()) {
    EXPECT_EQ(node.expand(), 0.0);
    EXPECT_EQ(node.contract(), 0.0);
    EXPECT_EQ(node.vx(), 0.0);
    EXPECT_EQ(node.vy(), 0.0);
  }
  EXPECT_EQ(message.nodes(1).x(), 2.0);
  EXPECT_EQ(message.nodes(2).y(), 1.5);
}

TEST(SceneTest, PhysicsParamsRoundTripThroughTheirMessage) {
  PhysicsParams p;
  p.mass = 1.5;
  p.stiffness = 7;
  p.damping = 0.25;
  p.pressure = 3;
  p.drag_normal = 2;
  p.drag_tangential = 0.01;
  p.dt = 0.02;
  p.actuation_max = 0.3;
  p.min_rest_fraction = 0.2;
  PhysicsParams q;
  ASSERT_TRUE(PhysicsParamsFromProto(PhysicsParamsToProto(p), &q).ok());
  EXPECT_EQ(q.mass, p.mass);
  EXPECT_EQ(q.stiffness, p.stiffness);
  EXPECT_EQ(q.damping, p.damping);
  EXPECT_EQ(q.pressure, p.pressure);
  EXPECT_EQ(q.drag_normal, p.drag_normal);
  EXPECT_EQ(q.drag_tangential, p.drag_tangential);
  EXPECT_EQ(q.dt, p.dt);
  EXPECT_EQ(q.actuation_max, p.actuation_max);
  EXPECT_EQ(q.min_rest_fraction, p.min_rest_fraction);
}

TEST(SceneTest, RejectedPhysicsLeavesTheParamsUnchanged) {
  PhysicsParams p;
  v1::PhysicsConfig message;
  message.set_stiffness(4);
  message.set_dt(0);
  const Status status = PhysicsParamsFromProto(message, &p);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("physics.dt"), std::string::npos);
  EXPECT_EQ(p.stiffness, 10.0);
  EXPECT_EQ(p.dt, 0.05);
}

}  // namespace
}  // namespace animat
