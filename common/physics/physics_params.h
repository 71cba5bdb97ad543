// Constants of the motion physics (model §7) and their configuration
// message.
#ifndef ANIMAT_COMMON_PHYSICS_PHYSICS_PARAMS_H_
#define ANIMAT_COMMON_PHYSICS_PHYSICS_PARAMS_H_

#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "common/io/param_table.h"

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
// Which overlapping pairs of cells push apart (docs/model.md §7.10).
enum class ContactRule {
  kNone,      // None (model v2): cells pass through each other.
  kUnjoined,  // Pairs not joined by a spring (model v3's default).
  kAll        // Every pair, joined ones too.
};

// "semi_implicit_euler", "velocity_verlet", "rk4", "ssprk3", "ralston3";
// "explicit", "stable";
// "native", "bullet";
// "none", "unjoined", "all".
const char* IntegratorName(Integrator integrator);
const char* DragUpdateName(DragUpdate drag);
const char* BackendName(PhysicsBackend backend);
const char* ContactRuleName(ContactRule rule);

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
  // Velocity Verlet with four sub-steps: the cheapest setting that meets
  // model §7.6's accuracy rule with contacts at k_c 3000 (model v3;
  // docs/accuracy.md, docs/model.md §11.4).
  Integrator integrator = Integrator::kVelocityVerlet;
  int substeps = 4;  // Physics sub-steps per simulation step.
  // Sub-steps instead of `substeps` in a step that starts with an admitted
  // pair of cells within (1 + contact_near) · (r_i + r_j) of each other
  // (0: `substeps` in every step). NATIVE with contacts only (model §7.6).
  int contact_substeps = 0;
  double contact_near = 0.1;
  // Velocity Verlet only: contacts integrated in this many inner sub-steps
  // of each sub-step, the other forces once per sub-step (impulse
  // multiple time stepping, model §7.6); 0: every force once per sub-step.
  int contact_inner_substeps = 0;
  DragUpdate drag_update = DragUpdate::kExplicit;
  PhysicsBackend backend = PhysicsBackend::kNative;
  ContactRule contact_rule = ContactRule::kUnjoined;
  // k_c (force per radius of overlap) and gamma_c (force per unit approach
  // speed) of the native backend's contacts; Bullet's world uses its own
  // contact solver.
  double contact_stiffness = 3000.0;  // Chosen by measurement, §7.10.
  double contact_damping = 0.5;
};

// Overwrites the fields present after checking them; on error `params` is
// unchanged and the message names the field ("physics.mass: ..."). The
// deprecated physics.contacts (model v2) reads as contact_rule NONE when
// false and ALL when true; giving it with contact_rule is an error.
Status PhysicsParamsFromProto(const v1::PhysicsConfig& message,
                              PhysicsParams* params);
// Every field set but the deprecated physics.contacts.
v1::PhysicsConfig PhysicsParamsToProto(const PhysicsParams& params);
// The parameters' tables (common/io/param_table.h), which both
// conversions and the checks read, and their lines for
// `animat config defaults`.
ParamTable<PhysicsParams> PhysicsParamTable();
EnumTable<PhysicsParams> PhysicsEnumTable();
std::vector<ParamDoc> PhysicsParamDocs();

}  // namespace animat

#endif  // ANIMAT_COMMON_PHYSICS_PHYSICS_PARAMS_H_
