#include "common/physics/physics_params.h"

#include <string>

#include "common/base/validate.h"

namespace animat {
namespace {

// "rk4" -> "RK4": the enum value's name in config files.
std::string UpperCase(const char* name) {
  std::string upper(name);
  for (char& c : upper) {
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  }
  return upper;
}

}  // namespace

const char* IntegratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::kSemiImplicitEuler:
      return "semi_implicit_euler";
    case Integrator::kVelocityVerlet:
      return "velocity_verlet";
    case Integrator::kRk4:
      return "rk4";
    case Integrator::kSsprk3:
      return "ssprk3";
    case Integrator::kRalston3:
      return "ralston3";
  }
  return "?";
}

const char* DragUpdateName(DragUpdate drag) {
  return drag == DragUpdate::kStable ? "stable" : "explicit";
}

const char* BackendName(PhysicsBackend backend) {
  return backend == PhysicsBackend::kBullet ? "bullet" : "native";
}

const char* ContactRuleName(ContactRule rule) {
  switch (rule) {
    case ContactRule::kNone:
      return "none";
    case ContactRule::kUnjoined:
      return "unjoined";
    case ContactRule::kAll:
      return "all";
  }
  return "?";
}

namespace {

// physics.contact_rule, or the deprecated physics.contacts of model v2.
Status ContactRuleFromProto(const v1::PhysicsConfig& m, ContactRule* rule) {
  if (m.has_contacts() && m.has_contact_rule()) {
    return Status::InvalidArgument(
        "physics.contacts: the model v2 form of physics.contact_rule "
        "(false is NONE, true is ALL); give only contact_rule");
  }
  if (m.has_contacts()) {
    *rule = m.contacts() ? ContactRule::kAll : ContactRule::kNone;
    return Status::Ok();
  }
  if (!m.has_contact_rule()) return Status::Ok();
  switch (m.contact_rule()) {
    case v1::PhysicsConfig::CONTACT_RULE_UNSPECIFIED:
      return Status::Ok();
    case v1::PhysicsConfig::NONE:
      *rule = ContactRule::kNone;
      return Status::Ok();
    case v1::PhysicsConfig::UNJOINED:
      *rule = ContactRule::kUnjoined;
      return Status::Ok();
    case v1::PhysicsConfig::ALL:
      *rule = ContactRule::kAll;
      return Status::Ok();
    default:
      return Status::InvalidArgument("physics.contact_rule: unknown value " +
                                     std::to_string(m.contact_rule()));
  }
}

v1::PhysicsConfig::ContactRule ContactRuleToProto(ContactRule rule) {
  switch (rule) {
    case ContactRule::kNone:
      return v1::PhysicsConfig::NONE;
    case ContactRule::kUnjoined:
      return v1::PhysicsConfig::UNJOINED;
    case ContactRule::kAll:
      return v1::PhysicsConfig::ALL;
  }
  return v1::PhysicsConfig::CONTACT_RULE_UNSPECIFIED;
}

}  // namespace

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
  if (m.has_integrator()) {
    switch (m.integrator()) {
      case v1::PhysicsConfig::INTEGRATOR_UNSPECIFIED:
        break;
      case v1::PhysicsConfig::SEMI_IMPLICIT_EULER:
        p.integrator = Integrator::kSemiImplicitEuler;
        break;
      case v1::PhysicsConfig::VELOCITY_VERLET:
        p.integrator = Integrator::kVelocityVerlet;
        break;
      case v1::PhysicsConfig::RK4:
        p.integrator = Integrator::kRk4;
        break;
      case v1::PhysicsConfig::SSPRK3:
        p.integrator = Integrator::kSsprk3;
        break;
      case v1::PhysicsConfig::RALSTON3:
        p.integrator = Integrator::kRalston3;
        break;
      default:
        return Status::InvalidArgument("physics.integrator: unknown value " +
                                       std::to_string(m.integrator()));
    }
  }
  if (m.has_substeps()) p.substeps = m.substeps();
  if (m.has_drag_update()) {
    switch (m.drag_update()) {
      case v1::PhysicsConfig::DRAG_UPDATE_UNSPECIFIED:
        break;
      case v1::PhysicsConfig::EXPLICIT:
        p.drag_update = DragUpdate::kExplicit;
        break;
      case v1::PhysicsConfig::STABLE:
        p.drag_update = DragUpdate::kStable;
        break;
      default:
        return Status::InvalidArgument("physics.drag_update: unknown value " +
                                       std::to_string(m.drag_update()));
    }
  }
  if (m.has_backend()) {
    switch (m.backend()) {
      case v1::PhysicsConfig::BACKEND_UNSPECIFIED:
        break;
      case v1::PhysicsConfig::NATIVE:
        p.backend = PhysicsBackend::kNative;
        break;
      case v1::PhysicsConfig::BULLET:
        p.backend = PhysicsBackend::kBullet;
        break;
      default:
        return Status::InvalidArgument("physics.backend: unknown value " +
                                       std::to_string(m.backend()));
    }
  }
  if (Status rule = ContactRuleFromProto(m, &p.contact_rule); !rule.ok()) {
    return rule;
  }
  if (m.has_contact_stiffness()) p.contact_stiffness = m.contact_stiffness();
  if (m.has_contact_damping()) p.contact_damping = m.contact_damping();
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
      RequireIntInRange("physics.substeps", p.substeps, 1, 1024),
      RequireNonNegative("physics.contact_stiffness", p.contact_stiffness),
      RequireNonNegative("physics.contact_damping", p.contact_damping),
      // Bullet integrates by semi-implicit Euler itself, with our forces
      // (drag among them) applied as given.
      p.backend == PhysicsBackend::kBullet &&
              p.integrator != Integrator::kSemiImplicitEuler
          ? Status::InvalidArgument(
                "physics.integrator: the BULLET backend integrates with "
                "semi-implicit Euler only, got " +
                UpperCase(IntegratorName(p.integrator)))
          : Status::Ok(),
      p.backend == PhysicsBackend::kBullet &&
              p.drag_update != DragUpdate::kExplicit
          ? Status::InvalidArgument(
                "physics.drag_update: the BULLET backend applies drag "
                "explicitly only, got " +
                UpperCase(DragUpdateName(p.drag_update)))
          : Status::Ok(),
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
  switch (p.integrator) {
    case Integrator::kSemiImplicitEuler:
      m.set_integrator(v1::PhysicsConfig::SEMI_IMPLICIT_EULER);
      break;
    case Integrator::kVelocityVerlet:
      m.set_integrator(v1::PhysicsConfig::VELOCITY_VERLET);
      break;
    case Integrator::kRk4:
      m.set_integrator(v1::PhysicsConfig::RK4);
      break;
    case Integrator::kSsprk3:
      m.set_integrator(v1::PhysicsConfig::SSPRK3);
      break;
    case Integrator::kRalston3:
      m.set_integrator(v1::PhysicsConfig::RALSTON3);
      break;
  }
  m.set_substeps(p.substeps);
  m.set_drag_update(p.drag_update == DragUpdate::kStable
                        ? v1::PhysicsConfig::STABLE
                        : v1::PhysicsConfig::EXPLICIT);
  m.set_backend(p.backend == PhysicsBackend::kBullet
                    ? v1::PhysicsConfig::BULLET
                    : v1::PhysicsConfig::NATIVE);
  m.set_contact_rule(ContactRuleToProto(p.contact_rule));
  m.set_contact_stiffness(p.contact_stiffness);
  m.set_contact_damping(p.contact_damping);
  return m;
}

}  // namespace animat
