#include "common/physics/scene.h"

#include <cmath>
#include <string>

#include "common/base/validate.h"

namespace animat {
namespace {

Status CheckNode(const std::string& field, uint32_t index, int nodes) {
  if (index >= static_cast<uint32_t>(nodes)) {
    return Status::InvalidArgument(field + ": node " + std::to_string(index) +
                                   " does not exist (" + std::to_string(nodes) +
                                   " nodes)");
  }
  return Status::Ok();
}

}  // namespace

Result<Scene> SceneFromProto(const v1::Scene& message) {
  Scene scene;
  Status status = PhysicsParamsFromProto(message.physics(), &scene.params);
  if (!status.ok()) return status;

  const v1::Body& body = message.body();
  const int n = body.nodes_size();
  if (n == 0) return Status::InvalidArgument("body.nodes: no nodes");
  for (int i = 0; i < n; ++i) {
    const v1::Node& node = body.nodes(i);
    const std::string where = "body.nodes[" + std::to_string(i) + "]";
    status = FirstError({
        RequireFinite(where + ".x", node.x()),
        RequireFinite(where + ".y", node.y()),
        RequireFinite(where + ".vx", node.vx()),
        RequireFinite(where + ".vy", node.vy()),
        RequireInRange(where + ".expand", node.expand(), 0.0, 1.0),
        RequireInRange(where + ".contract", node.contract(), 0.0, 1.0),
        node.has_radius() ? RequirePositive(where + ".radius", node.radius())
                          : Status::Ok(),
    });
    if (!status.ok()) return status;
    scene.body.position.push_back({node.x(), node.y()});
    scene.body.radius.push_back(node.has_radius() ? node.radius() : 1.0);
    scene.state.position.push_back({node.x(), node.y()});
    scene.state.velocity.push_back({node.vx(), node.vy()});
    scene.expand.push_back(node.expand());
    scene.contract.push_back(node.contract());
  }
  for (int s = 0; s < body.springs_size(); ++s) {
    const v1::Spring& spring = body.springs(s);
    const std::string where = "body.springs[" + std::to_string(s) + "]";
    status = FirstError({
        CheckNode(where + ".a", spring.a(), n),
        CheckNode(where + ".b", spring.b(), n),
        RequireNonNegative(where + ".rest_length", spring.rest_length()),
    });
    if (!status.ok()) return status;
    if (spring.a() == spring.b()) {
      return Status::InvalidArgument(where + ": joins node " +
                                     std::to_string(spring.a()) + " to itself");
    }
    scene.body.springs.push_back({static_cast<int>(spring.a()),
                                  static_cast<int>(spring.b()),
                                  spring.rest_length()});
  }
  for (int c = 0; c < body.chambers_size(); ++c) {
    const v1::Chamber& chamber = body.chambers(c);
    const std::string where = "body.chambers[" + std::to_string(c) + "]";
    if (chamber.nodes_size() < 3) {
      return Status::InvalidArgument(where +
                                     ".nodes: a chamber needs at least 3");
    }
    Chamber out;
    for (int k = 0; k < chamber.nodes_size(); ++k) {
      status = CheckNode(where + ".nodes[" + std::to_string(k) + "]",
                         chamber.nodes(k), n);
      if (!status.ok()) return status;
      out.walk.push_back(static_cast<int>(chamber.nodes(k)));
    }
    status = RequirePositive(where + ".rest_area", chamber.rest_area());
    if (!status.ok()) return status;
    out.rest_area = chamber.rest_area();
    scene.body.chambers.push_back(std::move(out));
  }
  for (int e = 0; e < body.skin_size(); ++e) {
    const v1::Edge& edge = body.skin(e);
    const std::string where = "body.skin[" + std::to_string(e) + "]";
    status = FirstError({CheckNode(where + ".a", edge.a(), n),
                         CheckNode(where + ".b", edge.b(), n)});
    if (!status.ok()) return status;
    if (edge.a() == edge.b()) {
      return Status::InvalidArgument(where + ": joins node " +
                                     std::to_string(edge.a()) + " to itself");
    }
    scene.body.skin.push_back(
        {static_cast<int>(edge.a()), static_cast<int>(edge.b())});
  }
  return scene;
}

v1::Body BodyToProto(const Body& body, std::span<const double> expand,
                     std::span<const double> contract) {
  v1::Body message;
  for (int i = 0; i < body.nodes(); ++i) {
    v1::Node* node = message.add_nodes();
    node->set_x(body.position[i].x);
    node->set_y(body.position[i].y);
    if (static_cast<size_t>(i) < body.radius.size()) {
      node->set_radius(body.radius[i]);
    }
    if (static_cast<size_t>(i) < expand.size()) node->set_expand(expand[i]);
    if (static_cast<size_t>(i) < contract.size()) {
      node->set_contract(contract[i]);
    }
  }
  for (const Spring& s : body.springs) {
    v1::Spring* spring = message.add_springs();
    spring->set_a(s.a);
    spring->set_b(s.b);
    spring->set_rest_length(s.rest_length);
  }
  for (const Chamber& c : body.chambers) {
    v1::Chamber* chamber = message.add_chambers();
    for (int v : c.walk) chamber->add_nodes(v);
    chamber->set_rest_area(c.rest_area);
  }
  for (const IndexEdge& e : body.skin) {
    v1::Edge* edge = message.add_skin();
    edge->set_a(e.a);
    edge->set_b(e.b);
  }
  return message;
}

}  // namespace animat
