// The Bullet backend (PhysicsConfig.backend BULLET): a Bullet
// btDiscreteDynamicsWorld integrates our forces, as the paper did.
//
// Each cell is a rigid sphere of its radius held in the plane: linear
// factor (1, 1, 0), no rotation, no gravity, no damping, never asleep. Each
// sub-step copies the MotionState into the world, applies SoftBody's forces
// (springs, pressure, explicit drag) as central forces and lets Bullet take
// exactly one step, which is semi-implicit Euler: v <- v + F (1/m) h, then
// x <- x + v h. Without contacts it agrees with SoftBody's own
// semi-implicit Euler to rounding (docs/model.md, "Backends"). With a
// contact rule other than NONE, cells also collide as spheres (Bullet's
// collision detection and contact solver; see bullet_stepper.cc for the
// constants): every pair under ALL, the pairs not joined by a spring under
// UNJOINED (the model's k_c and gamma_c are not used).
//
// Bullet is built in double precision (BT_USE_DOUBLE_PRECISION, which this
// target exports to every includer). This header exposes no Bullet type.
#ifndef ANIMAT_COMMON_PHYSICS_BULLET_BULLET_STEPPER_H_
#define ANIMAT_COMMON_PHYSICS_BULLET_BULLET_STEPPER_H_

#include <memory>

#include "common/body/body.h"
#include "common/physics/soft_body.h"

namespace animat {

// A stepper that owns a fresh Bullet world with one body per node of
// `body` (radius body.radius[i], or 1 where `body` has no radii; mass
// params.mass), and whose Step advances a MotionState (positions in radii,
// velocities in radii per unit time) by one simulation step of
// forces->params().dt, in forces->params().substeps sub-steps, under the
// forces of `forces` at its current actuation. Positions and velocities are
// read from the state at every sub-step, so callers may change them between
// steps.
//
// Ownership: `forces` is borrowed and must outlive the stepper; the caller
// keeps setting its actuation (SoftBody::SetActuation), which the next Step
// uses. Preconditions: forces->nodes() == body.nodes(), the MotionState
// passed to Step has that many entries, and forces->params() passed
// PhysicsParamsFromProto's checks for BULLET (semi-implicit Euler, explicit
// drag); other integrators or drag updates are never used.
// Thread safety: a stepper is not thread-safe; use one per simulation.
std::unique_ptr<MotionStepper> MakeBulletStepper(SoftBody* forces,
                                                 const Body& body);

}  // namespace animat

#endif  // ANIMAT_COMMON_PHYSICS_BULLET_BULLET_STEPPER_H_
