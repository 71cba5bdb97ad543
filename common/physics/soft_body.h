// Forces on a soft body and their integration (MODEL §7).
//
// SoftBody compiles a Body into flat arrays once; the running state
// (positions, velocities) is a MotionState owned by the caller. Rest lengths
// follow the actuation set by SetActuation. A SoftBody is not thread-safe
// (it keeps scratch buffers); use one per simulation.
#ifndef ANIMAT_COMMON_PHYSICS_SOFT_BODY_H_
#define ANIMAT_COMMON_PHYSICS_SOFT_BODY_H_

#include <span>
#include <string>
#include <vector>

#include "common/base/hash.h"
#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/physics/physics_params.h"

namespace animat {

struct MotionState {
  std::vector<Vec2> position;  // Radii.
  std::vector<Vec2> velocity;  // Radii per unit time.
};

class SoftBody {
 public:
  // Actuation starts at 0 (rest lengths L0). Precondition: the body's
  // indices are valid and chambers have rest_area > 0 (BuildBody and
  // SceneFromProto guarantee both).
  SoftBody(const Body& body, const PhysicsParams& params);

  int nodes() const { return nodes_; }
  const PhysicsParams& params() const { return params_; }

  // Rest lengths from each node's EXPAND and CONTRACT values:
  //   L = max(min_rest_fraction, 1 + A_max (e_a + e_b - c_a - c_b)) L0.
  void SetActuation(std::span<const double> expand,
                    std::span<const double> contract);
  // Current rest length of each spring.
  const std::vector<double>& rest_lengths() const { return rest_; }

  // Total force on every node at `state` (springs, pressure, drag).
  void ComputeForces(const MotionState& state, std::vector<Vec2>* force);
  // Each force family alone (for tests and analysis); forces are added.
  void AddSpringForces(const MotionState& state, Vec2* force) const;
  void AddPressureForces(const MotionState& state, Vec2* force) const;
  void AddDragForces(const MotionState& state, Vec2* force) const;

  // One semi-implicit Euler step of dt, all forces from (x_t, v_t):
  //   v <- v + F / m * dt, then x <- x + v * dt.
  void Step(MotionState* state);

  // Current signed area of each chamber along its rest walk.
  double ChamberArea(const MotionState& state, int chamber) const;
  int chambers() const { return static_cast<int>(rest_area_.size()); }

 private:
  PhysicsParams params_;
  int nodes_;
  std::vector<int> spring_a_, spring_b_;
  std::vector<double> rest0_, rest_;
  std::vector<int> walk_begin_, walk_;  // Chamber walks, flattened.
  std::vector<double> rest_area_;
  std::vector<int> skin_a_, skin_b_;
  std::vector<Vec2> force_;  // Scratch for Step.
};

// Checks that every position and velocity is finite and every coordinate
// within max_coordinate. Returns "" when all hold, else the reason
// ("non-finite velocity of node 3").
std::string CheckState(const MotionState& state, double max_coordinate);

// Adds the bits of every position and velocity, node by node (x, y, vx,
// vy), to `hash`.
void HashMotionState(const MotionState& state, StateHash* hash);

// Centre of mass (equal masses): the mean position, summed in node order.
Vec2 CentreOfMass(const MotionState& state);

}  // namespace animat

#endif  // ANIMAT_COMMON_PHYSICS_SOFT_BODY_H_
