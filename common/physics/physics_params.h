// Constants of the motion physics (model §7) and their configuration
// message.
#ifndef ANIMAT_COMMON_PHYSICS_PHYSICS_PARAMS_H_
#define ANIMAT_COMMON_PHYSICS_PHYSICS_PARAMS_H_

#include "animat/v1/config.pb.h"
#include "common/base/status.h"

namespace animat {

enum class Integrator {
  kSemiImplicitEuler,
  kVelocityVerlet,
  kRk4,
  kSsprk3,
  kRalston3
};
enum class DragUpdate { kExplicit, kStable };
enum class PhysicsBackend { kNative, kBullet };

// "semi_implicit_euler", "velocity_verlet", "rk4", "ssprk3", "ralston3";
// "explicit", "stable";
// "native", "bullet".
const char* IntegratorName(Integrator integrator);
const char* DragUpdateName(DragUpdate drag);
const char* BackendName(PhysicsBackend backend);

struct PhysicsParams {
  double mass = 1.0;               // Of every cell.
  double stiffness = 10.0;         // Spring k (force per radius).
  double damping = 0.5;            // Spring gamma (force per unit speed).
  double pressure = 10.0;          // Chamber c_p.
  double drag_normal = 1.0;        // d_N.
  double drag_tangential = 0.005;  // d_T (the paper: d_N / 200).
  double dt = 0.05;                // Time per simulation step.
  double actuation_max = 0.2;      // A_max, in [0, 0.5).
  double min_rest_fraction = 0.1;  // Rest length never below this * L0.
  // Ralston's third order with one sub-step: the cheapest setting that
  // meets model §7.6's accuracy rule (docs/accuracy.md, docs/model.md).
  Integrator integrator = Integrator::kRalston3;
  int substeps = 1;  // Physics sub-steps per simulation step.
  DragUpdate drag_update = DragUpdate::kExplicit;
  PhysicsBackend backend = PhysicsBackend::kNative;
  bool contacts = false;  // Cell-cell contacts (Bullet backend only).
};

// Overwrites the fields present after checking them; on error `params` is
// unchanged and the message names the field ("physics.mass: ...").
Status PhysicsParamsFromProto(const v1::PhysicsConfig& message,
                              PhysicsParams* params);
// Every field set.
v1::PhysicsConfig PhysicsParamsToProto(const PhysicsParams& params);

}  // namespace animat

#endif  // ANIMAT_COMMON_PHYSICS_PHYSICS_PARAMS_H_
