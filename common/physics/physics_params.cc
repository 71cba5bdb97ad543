#include "common/physics/physics_params.h"

#include "common/base/validate.h"

namespace animat {

Status PhysicsParamsFromProto(const v1::PhysicsConfig& m,
                              PhysicsParams* params) {
  PhysicsParams p = *params;
  if (m.has_mass()) p.mass = m.mass();
  if (m.has_stiffness()) p.stiffness = m.stiffness();
  if (m.has_damping()) p.damping = m.damping();
  if (m.has_pressure()) p.pressure = m.pressure();
  if (m.has_drag_normal()) p.drag_normal = m.drag_normal();
  if (m.has_drag_tangential()) p.drag_tangential = m.drag_tangential();
  if (m.has_dt()) p.dt = m.dt();
  if (m.has_actuation_max()) p.actuation_max = m.actuation_max();
  if (m.has_min_rest_fraction()) p.min_rest_fraction = m.min_rest_fraction();
  Status status = FirstError({
      RequirePositive("physics.mass", p.mass),
      RequireNonNegative("physics.stiffness", p.stiffness),
      RequireNonNegative("physics.damping", p.damping),
      RequireNonNegative("physics.pressure", p.pressure),
      RequireNonNegative("physics.drag_normal", p.drag_normal),
      RequireNonNegative("physics.drag_tangential", p.drag_tangential),
      RequirePositive("physics.dt", p.dt),
      RequireInRange("physics.actuation_max", p.actuation_max, 0.0, 0.5,
                     /*include_hi=*/false),
      RequirePositive("physics.min_rest_fraction", p.min_rest_fraction),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::PhysicsConfig PhysicsParamsToProto(const PhysicsParams& p) {
  v1::PhysicsConfig m;
  m.set_mass(p.mass);
  m.set_stiffness(p.stiffness);
  m.set_damping(p.damping);
  m.set_pressure(p.pressure);
  m.set_drag_normal(p.drag_normal);
  m.set_drag_tangential(p.drag_tangential);
  m.set_dt(p.dt);
  m.set_actuation_max(p.actuation_max);
  m.set_min_rest_fraction(p.min_rest_fraction);
  return m;
}

}  // namespace animat
