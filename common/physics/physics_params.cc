#include "common/physics/physics_params.h"

#include <string>

#include "common/base/validate.h"
#include "common/io/param_table.h"

namespace animat {
namespace {

// The numeric parameters, in the proto's order (docs/model.md §7).
constexpr ParamRow<PhysicsParams> kRows[] = {
    {"mass", &PhysicsParams::mass, ParamRange::Positive(), "of every cell"},
    {"stiffness", &PhysicsParams::stiffness, ParamRange::NonNegative(),
     "spring k, force per radius"},
    {"damping", &PhysicsParams::damping, ParamRange::NonNegative(),
     "spring gamma, force per unit speed"},
    {"pressure", &PhysicsParams::pressure, ParamRange::NonNegative(),
     "chamber c_p"},
    {"drag_normal", &PhysicsParams::drag_normal, ParamRange::NonNegative(),
     "d_N"},
    {"drag_tangential", &PhysicsParams::drag_tangential,
     ParamRange::NonNegative(), "d_T"},
    {"dt", &PhysicsParams::dt, ParamRange::Positive(),
     "time per simulation step"},
    {"actuation_max", &PhysicsParams::actuation_max,
     ParamRange::HalfOpen(0.0, 0.5), "A_max"},
    {"min_rest_fraction", &PhysicsParams::min_rest_fraction,
     ParamRange::Positive(), "a rest length never below this times L0"},
    {"substeps", &PhysicsParams::substeps, ParamRange::Closed(1, 1024),
     "physics sub-steps per simulation step"},
    {"contact_stiffness", &PhysicsParams::contact_stiffness,
     ParamRange::NonNegative(), "k_c, force per radius of overlap"},
    {"contact_damping", &PhysicsParams::contact_damping,
     ParamRange::NonNegative(), "gamma_c, force per unit approach speed"},
};

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

ParamTable<PhysicsParams> PhysicsParamTable() { return kRows; }

namespace {

Status IntegratorFromProto(const v1::PhysicsConfig& m, PhysicsParams* p) {
  if (m.has_integrator()) {
    switch (m.integrator()) {
      case v1::PhysicsConfig::INTEGRATOR_UNSPECIFIED:
        break;
      case v1::PhysicsConfig::SEMI_IMPLICIT_EULER:
        p->integrator = Integrator::kSemiImplicitEuler;
        break;
      case v1::PhysicsConfig::VELOCITY_VERLET:
        p->integrator = Integrator::kVelocityVerlet;
        break;
      case v1::PhysicsConfig::RK4:
        p->integrator = Integrator::kRk4;
        break;
      case v1::PhysicsConfig::SSPRK3:
        p->integrator = Integrator::kSsprk3;
        break;
      case v1::PhysicsConfig::RALSTON3:
        p->integrator = Integrator::kRalston3;
        break;
      default:
        return Status::InvalidArgument("physics.integrator: unknown value " +
                                       std::to_string(m.integrator()));
    }
  }
  return Status::Ok();
}

Status DragUpdateFromProto(const v1::PhysicsConfig& m, PhysicsParams* p) {
  if (m.has_drag_update()) {
    switch (m.drag_update()) {
      case v1::PhysicsConfig::DRAG_UPDATE_UNSPECIFIED:
        break;
      case v1::PhysicsConfig::EXPLICIT:
        p->drag_update = DragUpdate::kExplicit;
        break;
      case v1::PhysicsConfig::STABLE:
        p->drag_update = DragUpdate::kStable;
        break;
      default:
        return Status::InvalidArgument("physics.drag_update: unknown value " +
                                       std::to_string(m.drag_update()));
    }
  }
  return Status::Ok();
}

Status BackendFromProto(const v1::PhysicsConfig& m, PhysicsParams* p) {
  if (m.has_backend()) {
    switch (m.backend()) {
      case v1::PhysicsConfig::BACKEND_UNSPECIFIED:
        break;
      case v1::PhysicsConfig::NATIVE:
        p->backend = PhysicsBackend::kNative;
        break;
      case v1::PhysicsConfig::BULLET:
        p->backend = PhysicsBackend::kBullet;
        break;
      default:
        return Status::InvalidArgument("physics.backend: unknown value " +
                                       std::to_string(m.backend()));
    }
  }
  return Status::Ok();
}

}  // namespace

Status PhysicsParamsFromProto(const v1::PhysicsConfig& m,
                              PhysicsParams* params) {
  PhysicsParams p = *params;
  ReadParams<PhysicsParams>(m, kRows, &p);
  Status status = FirstError({
      IntegratorFromProto(m, &p),
      DragUpdateFromProto(m, &p),
      BackendFromProto(m, &p),
      ContactRuleFromProto(m, &p.contact_rule),
  });
  if (!status.ok()) return status;
  status = FirstError({
      CheckParams<PhysicsParams>("physics", p, kRows),
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
  WriteParams<PhysicsParams>(p, kRows, &m);
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
  m.set_drag_update(p.drag_update == DragUpdate::kStable
                        ? v1::PhysicsConfig::STABLE
                        : v1::PhysicsConfig::EXPLICIT);
  m.set_backend(p.backend == PhysicsBackend::kBullet
                    ? v1::PhysicsConfig::BULLET
                    : v1::PhysicsConfig::NATIVE);
  m.set_contact_rule(ContactRuleToProto(p.contact_rule));
  return m;
}

}  // namespace animat
