// A physics scene: a body with its state, constant actuation and physics
// constants, read from an animat.v1.Scene (`animat scene`), and the
// conversion of bodies to their protobuf message (traces).
#ifndef ANIMAT_COMMON_PHYSICS_SCENE_H_
#define ANIMAT_COMMON_PHYSICS_SCENE_H_

#include <span>
#include <vector>

#include "animat/v1/body.pb.h"
#include "common/base/status.h"
#include "common/body/body.h"
#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"

namespace animat {

struct Scene {
  Body body;                     // Rest lengths and areas as given.
  MotionState state;             // Initial positions and velocities.
  std::vector<double> expand;    // Per node, constant.
  std::vector<double> contract;  // Per node, constant.
  PhysicsParams params;          // Defaults where the file is silent.
};

// Converts and validates: finite values, node indices in range, springs
// between two different nodes with rest_length >= 0, chambers of at least
// 3 entries with rest_area > 0, expand and contract in [0, 1], physics
// constants in range. Errors name the field ("body.springs[3].b: ...").
Result<Scene> SceneFromProto(const v1::Scene& message);

// The body message: rest positions with zero velocity, the given per-node
// expand and contract values (empty spans: 0), springs, chambers, skin.
v1::Body BodyToProto(const Body& body, std::span<const double> expand,
                     std::span<const double> contract);

}  // namespace animat

#endif  // ANIMAT_COMMON_PHYSICS_SCENE_H_
