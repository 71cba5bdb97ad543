#include "common/physics/physics_params.h"

#include <string>

#include "common/base/validate.h"
#include "common/io/param_table.h"

namespace animat {
namespace {

// The numeric parameters, in the proto's order (docs/model.md §7).
constexpr ParamRow<PhysicsParams> kRows[] = {
    {"mass", &PhysicsParams::mass, ParamRange::Positive(),
     "the mass of every cell"},
    {"stiffness", &PhysicsParams::stiffness, ParamRange::NonNegative(),
     "spring k (force per radius)"},
    {"damping", &PhysicsParams::damping, ParamRange::NonNegative(),
     "spring gamma (force per unit speed)"},
    {"pressure", &PhysicsParams::pressure, ParamRange::NonNegative(),
     "c_p, the chambers' pressure coefficient"},
    {"drag_normal", &PhysicsParams::drag_normal, ParamRange::NonNegative(),
     "d_N, the normal drag coefficient"},
    {"drag_tangential", &PhysicsParams::drag_tangential,
     ParamRange::NonNegative(),
     "d_T, the tangential drag coefficient (the paper: d_N / 200)"},
    {"dt", &PhysicsParams::dt, ParamRange::Positive(),
     "time per simulation step"},
    {"actuation_max", &PhysicsParams::actuation_max,
     ParamRange::HalfOpen(0.0, 0.5), "A_max, the largest actuation amplitude"},
    {"min_rest_fraction", &PhysicsParams::min_rest_fraction,
     ParamRange::Positive(), "a rest length never below this times L0"},
    {"substeps", &PhysicsParams::substeps, ParamRange::Closed(1, 1024),
     "physics sub-steps per simulation step"},
    {"contact_stiffness", &PhysicsParams::contact_stiffness,
     ParamRange::NonNegative(),
     "k_c (force per radius of overlap); NATIVE only"},
    {"contact_damping", &PhysicsParams::contact_damping,
     ParamRange::NonNegative(),
     "gamma_c (force per unit approach speed); NATIVE only"},
    {"contact_substeps", &PhysicsParams::contact_substeps,
     ParamRange::Closed(0, 1024),
     "sub-steps in a step that starts with a contact near (0: substeps "
     "always); NATIVE only"},
    {"contact_near", &PhysicsParams::contact_near, ParamRange::NonNegative(),
     "a contact is near within (1 + this) (r_i + r_j)"},
    {"contact_inner_substeps", &PhysicsParams::contact_inner_substeps,
     ParamRange::Closed(0, 1024),
     "contact sub-steps within each sub-step, the other forces once "
     "(0: every force once per sub-step); VELOCITY_VERLET only"},
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

using PC = v1::PhysicsConfig;

constexpr EnumPair kIntegrators[] = {
    {static_cast<int>(Integrator::kSemiImplicitEuler), PC::SEMI_IMPLICIT_EULER},
    {static_cast<int>(Integrator::kVelocityVerlet), PC::VELOCITY_VERLET},
    {static_cast<int>(Integrator::kRk4), PC::RK4},
    {static_cast<int>(Integrator::kSsprk3), PC::SSPRK3},
    {static_cast<int>(Integrator::kRalston3), PC::RALSTON3},
};
constexpr EnumPair kDragUpdates[] = {
    {static_cast<int>(DragUpdate::kExplicit), PC::EXPLICIT},
    {static_cast<int>(DragUpdate::kStable), PC::STABLE},
};
constexpr EnumPair kBackends[] = {
    {static_cast<int>(PhysicsBackend::kNative), PC::NATIVE},
    {static_cast<int>(PhysicsBackend::kBullet), PC::BULLET},
};
constexpr EnumPair kContactRules[] = {
    {static_cast<int>(ContactRule::kNone), PC::NONE},
    {static_cast<int>(ContactRule::kUnjoined), PC::UNJOINED},
    {static_cast<int>(ContactRule::kAll), PC::ALL},
};

constexpr EnumRow<PhysicsParams> kEnums[] = {
    MakeEnumRow<&PhysicsParams::integrator>("integrator", kIntegrators,
                                            "the motion's integrator"),
    MakeEnumRow<&PhysicsParams::drag_update>(
        "drag_update", kDragUpdates,
        "drag from the step's start (EXPLICIT) or its end (STABLE)"),
    MakeEnumRow<&PhysicsParams::backend>("backend", kBackends,
                                         "who integrates the motion"),
    MakeEnumRow<&PhysicsParams::contact_rule>(
        "contact_rule", kContactRules,
        "which overlapping cells push apart (v3: UNJOINED)"),
};

// The deprecated physics.contacts of model v2, read into contact_rule.
Status ContactsFromProto(const v1::PhysicsConfig& m, ContactRule* rule) {
  if (m.has_contacts() && m.has_contact_rule()) {
    return Status::InvalidArgument(
        "physics.contacts: the model v2 form of physics.contact_rule "
        "(false is NONE, true is ALL); give only contact_rule");
  }
  if (m.has_contacts()) {
    *rule = m.contacts() ? ContactRule::kAll : ContactRule::kNone;
  }
  return Status::Ok();
}

}  // namespace

ParamTable<PhysicsParams> PhysicsParamTable() { return kRows; }
EnumTable<PhysicsParams> PhysicsEnumTable() { return kEnums; }

std::vector<ParamDoc> PhysicsParamDocs() {
  return DescribeParams<PhysicsParams>("physics", v1::PhysicsConfig(), kRows,
                                       kEnums);
}

Status PhysicsParamsFromProto(const v1::PhysicsConfig& m,
                              PhysicsParams* params) {
  PhysicsParams p = *params;
  ReadParams<PhysicsParams>(m, kRows, &p);
  Status status = FirstError({
      ReadEnums<PhysicsParams>("physics", m, kEnums, &p),
      ContactsFromProto(m, &p.contact_rule),
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
      p.contact_inner_substeps > 0 &&
              p.integrator != Integrator::kVelocityVerlet
          ? Status::InvalidArgument(
                "physics.contact_inner_substeps: only VELOCITY_VERLET "
                "integrates contacts in inner sub-steps, got " +
                UpperCase(IntegratorName(p.integrator)))
          : Status::Ok(),
      p.contact_inner_substeps > 0 && p.contact_substeps > 0
          ? Status::InvalidArgument("physics.contact_inner_substeps: not with "
                                    "physics.contact_substeps (choose one)")
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
  WriteParams<PhysicsParams>(p, kRows, &m, kEnums);
  return m;
}

}  // namespace animat
