#include "common/physics/soft_body.h"

#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "common/geometry/polygon.h"
#include "common/kernels/kernels.h"
#include "common/physics/edge_geometry.h"

namespace animat {
namespace {

// Shu and Osher's strong-stability-preserving scheme (c = 0, 1, 1/2).
constexpr SoftBody::Rk3Tableau kSsprk3Tableau = {
    1.0, 0.25, 0.25, 1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0};
// Ralston's, with the smallest truncation error bound of the three-stage
// third-order schemes (c = 0, 1/2, 3/4).
constexpr SoftBody::Rk3Tableau kRalston3Tableau = {
    0.5, 0.0, 0.75, 2.0 / 9.0, 1.0 / 3.0, 4.0 / 9.0};

}  // namespace

SoftBody::SoftBody(const Body& body, const PhysicsParams& params)
    : params_(params),
      nodes_(body.nodes()),
      contacts_(body, params, params.backend == PhysicsBackend::kNative) {
  for (const Spring& s : body.springs) {
    spring_a_.push_back(s.a);
    spring_b_.push_back(s.b);
    rest0_.push_back(s.rest_length);
  }
  rest_ = rest0_;
  rest_change_.assign(rest0_.size(), 0.0);
  walk_begin_.push_back(0);
  for (const Chamber& c : body.chambers) {
    walk_.insert(walk_.end(), c.walk.begin(), c.walk.end());
    for (size_t k = 0; k < c.walk.size(); ++k) {
      walk_next_.push_back(c.walk[k + 1 < c.walk.size() ? k + 1 : 0]);
    }
    walk_begin_.push_back(static_cast<int>(walk_.size()));
    rest_area_.push_back(c.rest_area);
  }
  for (const IndexEdge& e : body.skin) {
    skin_a_.push_back(e.a);
    skin_b_.push_back(e.b);
  }
}

void SoftBody::SetActuation(std::span<const double> expand,
                            std::span<const double> contract) {
  assert(static_cast<int>(expand.size()) >= nodes_ &&
         static_cast<int>(contract.size()) >= nodes_);
  const double amax = params_.actuation_max;
  const double floor = params_.min_rest_fraction;
  for (size_t s = 0; s < rest0_.size(); ++s) {
    const int a = spring_a_[s];
    const int b = spring_b_[s];
    const double factor =
        1.0 + amax * (expand[a] + expand[b] - contract[a] - contract[b]);
    // NaN actuation stays NaN (never replaced by the floor).
    const double rest = (factor < floor ? floor : factor) * rest0_[s];
    rest_change_[s] = rest - rest_[s];
    rest_[s] = rest;
  }
  work_pending_ = true;
}

double SoftBody::HeldActuation() const {
  double held = 0.0;
  for (size_t s = 0; s < rest_.size(); ++s) {
    held += std::fabs(rest_[s] - rest0_[s]);
  }
  return held;
}

void SoftBody::AddSpringForces(const MotionState& state, Vec2* force) const {
  AddSprings<false>(state, force);
}

template <bool kWork>
double SoftBody::AddSprings(const MotionState& state, Vec2* force) const {
  const Vec2* x = state.position.data();
  const Vec2* v = state.velocity.data();
  const double k = params_.stiffness;
  const double gamma = params_.damping;
  double work = 0.0;
  for (size_t s = 0; s < rest_.size(); ++s) {
    const int a = spring_a_[s];
    const int b = spring_b_[s];
    const Vec2 d = x[b] - x[a];
    const double l = Length(d);
    const Vec2 u = l > 0.0 ? d / l : Vec2{};
    const double elastic = k * (l - rest_[s]);
    if constexpr (kWork) work += std::fabs(elastic * rest_change_[s]);
    const double f = elastic + gamma * Dot(v[b] - v[a], u);
    const Vec2 fa = u * f;
    force[a] += fa;
    force[b] -= fa;
  }
  return work;
}

void SoftBody::AddPressureForces(const MotionState& state, Vec2* force) const {
  AddPressure(state.position.data(), force);
}

void SoftBody::AddPressure(const Vec2* x, Vec2* force) const {
  const double cp = params_.pressure;
  const int* walk = walk_.data();
  const int* next = walk_next_.data();
  for (size_t c = 0; c < rest_area_.size(); ++c) {
    const int begin = walk_begin_[c];
    const int end = walk_begin_[c + 1];
    // WalkArea's operations, in its order (so S == S0 at rest, bit for
    // bit): the shoelace sum relative to the first vertex.
    const Vec2 origin = x[walk[begin]];
    double twice = 0.0;
    Vec2 from = x[walk[begin + 1]] - origin;
    for (int k = begin + 1; k + 1 < end; ++k) {
      const Vec2 to = x[walk[k + 1]] - origin;
      twice += Cross(from, to);
      from = to;
    }
    const double area = 0.5 * twice;
    // c_p * l * (1 - S / S0) * n with n = (dy, -dx) / l, half to each end.
    const double half = 0.5 * cp * (1.0 - area / rest_area_[c]);
    const auto push = [&](int k) {
      const int a = walk[k];
      const int b = next[k];
      return Vec2{x[b].y - x[a].y, -(x[b].x - x[a].x)} * half;
    };
    // Edge k adds its push to its start, then to its end; its end is edge
    // k + 1's start. The same additions in the same order, but each vertex
    // taken once into a register for its two, not stored and read back.
    Vec2 before = push(begin);
    force[walk[begin]] += before;
    for (int k = begin + 1; k < end; ++k) {
      const Vec2 after = push(k);
      Vec2 sum = force[walk[k]];
      sum += before;
      sum += after;
      force[walk[k]] = sum;
      before = after;
    }
    force[walk[begin]] += before;  // The last edge ends where the walk began.
  }
}

void SoftBody::AddDragForces(const MotionState& state, Vec2* force) const {
  const Vec2* x = state.position.data();
  const Vec2* v = state.velocity.data();
  const double dn = params_.drag_normal;
  const double dt = params_.drag_tangential;
  for (size_t e = 0; e < skin_a_.size(); ++e) {
    const int a = skin_a_[e];
    const int b = skin_b_[e];
    const Vec2 d = x[b] - x[a];
    const double l = Length(d);
    if (!(l > 0.0)) continue;  // No length, no drag.
    const Vec2 t = d / l;
    const Vec2 n{t.y, -t.x};
    const Vec2 vc = (v[a] + v[b]) * 0.5;
    const double vt = Dot(vc, t);
    const double vn = Dot(vc, n);
    // -d l sign(v) v^2 = -d l |v| v.
    const Vec2 f =
        t * (-dt * l * std::fabs(vt) * vt) + n * (-dn * l * std::fabs(vn) * vn);
    const Vec2 half = f * 0.5;
    force[a] += half;
    force[b] += half;
  }
}

void SoftBody::ComputeForces(const MotionState& state, std::vector<Vec2>* force,
                             bool drag) {
  force->assign(nodes_, Vec2{});
  if (work_pending_) {
    work_ += AddSprings<true>(state, force->data());
    work_pending_ = false;
  } else {
    AddSprings<false>(state, force->data());
  }
  AddPressureForces(state, force->data());
  if (drag) AddDragForces(state, force->data());
  AddContactForces(state, force->data());
}

void SoftBody::AddContactForces(const MotionState& state, Vec2* force) {
  contacts_.AddForces(state.position, state.velocity, force);
}

void SoftBody::Step(MotionState* state) {
  int substeps = params_.substeps;
  if (params_.contact_substeps > 0 &&
      contacts_.Near(state->position, params_.contact_near)) {
    substeps = params_.contact_substeps;
  }
  // dt / 1 == dt: the default path is exactly docs/model.md §7.6's step.
  const double h = params_.dt / substeps;
  const bool stable = params_.drag_update == DragUpdate::kStable;
  for (int sub = 0; sub < substeps; ++sub) {
    if (stable) ApplyStableDrag(0.5 * h, state);
    switch (params_.integrator) {
      case Integrator::kSemiImplicitEuler:
        EulerStep(h, !stable, state);
        break;
      case Integrator::kVelocityVerlet:
        if (params_.contact_inner_substeps > 0) {
          VerletMtsStep(h, params_.contact_inner_substeps, !stable, state);
        } else {
          VerletStep(h, !stable, state);
        }
        break;
      case Integrator::kRk4:
        Rk4Step(h, !stable, state);
        break;
      case Integrator::kSsprk3:
        Rk3Step(h, !stable, kSsprk3Tableau, state);
        break;
      case Integrator::kRalston3:
        Rk3Step(h, !stable, kRalston3Tableau, state);
        break;
    }
    if (stable) ApplyStableDrag(0.5 * h, state);
  }
}

void SoftBody::EulerStep(double h, bool drag, MotionState* state) {
  ComputeForces(*state, &force_, drag);
  DivideByMass(&force_);
  for (int i = 0; i < nodes_; ++i) {
    state->velocity[i] += force_[i] * h;
    state->position[i] += state->velocity[i] * h;
  }
}

void SoftBody::DivideByMass(std::vector<Vec2>* force) const {
  // x / 1 is x exactly (IEEE division is correctly rounded), so the
  // default mass skips the divisions and keeps the bits.
  const double m = params_.mass;
  if (m == 1.0) return;
  for (Vec2& f : *force) f = f / m;
}

void SoftBody::Acceleration(const MotionState& state, bool drag,
                            std::vector<Vec2>* out) {
  ComputeForces(state, out, drag);
  DivideByMass(out);
}

void SoftBody::Measure(const std::vector<Vec2>& position,
                       Geometry* geometry) const {
  const Vec2* x = position.data();
  geometry->spring_length.resize(rest_.size());
  geometry->spring_unit.resize(rest_.size());
  MeasureEdges(x, spring_a_.data(), spring_b_.data(),
               static_cast<int>(rest_.size()), geometry->spring_length.data(),
               geometry->spring_unit.data());
  geometry->skin_length.resize(skin_a_.size());
  geometry->skin_tangent.resize(skin_a_.size());
  MeasureEdges(x, skin_a_.data(), skin_b_.data(),
               static_cast<int>(skin_a_.size()), geometry->skin_length.data(),
               geometry->skin_tangent.data());
  geometry->pressure.assign(nodes_, Vec2{});
  AddPressure(x, geometry->pressure.data());
}

void SoftBody::AccelerationFrom(const Geometry& geometry,
                                const MotionState& state, bool drag,
                                bool contacts, std::vector<Vec2>* out) {
  *out = geometry.pressure;
  // Plain pointers, so that the stores into `force` do not make the
  // compiler load the arrays' addresses again at every spring.
  Vec2* force = out->data();
  const Vec2* v = state.velocity.data();
  const int* spring_a = spring_a_.data();
  const int* spring_b = spring_b_.data();
  const double* rest = rest_.data();
  const double* length = geometry.spring_length.data();
  const Vec2* unit = geometry.spring_unit.data();
  const double k = params_.stiffness;
  const double gamma = params_.damping;
  // Springs sharing their first node follow each other (the body's order):
  // that node's force stays in a register through the run, with the same
  // additions in the same order as one spring at a time.
  const size_t springs = rest_.size();
  for (size_t s = 0; s < springs;) {
    const int a = spring_a[s];
    Vec2 force_a = force[a];
    for (; s < springs && spring_a[s] == a; ++s) {
      const int b = spring_b[s];
      const Vec2 u = unit[s];
      const double f = k * (length[s] - rest[s]) + gamma * Dot(v[b] - v[a], u);
      const Vec2 fa = u * f;
      force_a += fa;
      if (b == a) {
        force_a -= fa;  // A spring from a node to itself (never built).
      } else {
        force[b] -= fa;
      }
    }
    force[a] = force_a;
  }
  if (drag) {
    const double dn = params_.drag_normal;
    const double dt = params_.drag_tangential;
    const int* skin_a = skin_a_.data();
    const int* skin_b = skin_b_.data();
    const double* skin_length = geometry.skin_length.data();
    const Vec2* tangent = geometry.skin_tangent.data();
    const size_t edges = skin_a_.size();
    for (size_t e = 0; e < edges; ++e) {
      const double l = skin_length[e];
      if (!(l > 0.0)) continue;  // No length, no drag.
      const int a = skin_a[e];
      const int b = skin_b[e];
      const Vec2 t = tangent[e];
      const Vec2 n{t.y, -t.x};
      const Vec2 vc = (v[a] + v[b]) * 0.5;
      const double vt = Dot(vc, t);
      const double vn = Dot(vc, n);
      const Vec2 f = t * (-dt * l * std::fabs(vt) * vt) +
                     n * (-dn * l * std::fabs(vn) * vn);
      const Vec2 half = f * 0.5;
      force[a] += half;
      force[b] += half;
    }
  }
  if (contacts) AddContactForces(state, force);
  DivideByMass(out);
}

void SoftBody::ContactAcceleration(const MotionState& state,
                                   std::vector<Vec2>* out) {
  out->assign(nodes_, Vec2{});
  AddContactForces(state, out->data());
  DivideByMass(out);
}

void SoftBody::PrepareVerletStep(const MotionState& state) {
  const size_t bytes = static_cast<size_t>(nodes_) * sizeof(Vec2);
  if (measured_position_.size() != state.position.size() ||
      std::memcmp(measured_position_.data(), state.position.data(), bytes) !=
          0) {
    Measure(state.position, &geometry_);
  }
  if (work_pending_) {
    // The work at the step's start, from its measured spring lengths, in
    // AddSprings' order and arithmetic.
    const double k = params_.stiffness;
    double work = 0.0;
    for (size_t s = 0; s < rest_.size(); ++s) {
      work += std::fabs(k * (geometry_.spring_length[s] - rest_[s]) *
                        rest_change_[s]);
    }
    work_ += work;
    work_pending_ = false;
  }
}

namespace {

// Velocity Verlet's predictor: stage <- (x + v h + a h^2 / 2, v + a h).
void VerletPredict(const MotionState& state, const std::vector<Vec2>& a,
                   double h, MotionState* stage) {
  const size_t nodes = state.position.size();
  stage->position.resize(nodes);
  stage->velocity.resize(nodes);
  kernels::VerletPredictArgs args;
  args.points = nodes;
  args.x = state.position.data();
  args.v = state.velocity.data();
  args.a = a.data();
  args.stage_x = stage->position.data();
  args.stage_v = stage->velocity.data();
  args.h = h;
  args.half_h2 = 0.5 * h * h;
  kernels::VerletPredict(ActiveIsa(), args);
}

// Its corrector: x <- the stage's positions, v <- v + (a0 + a1) h / 2.
void VerletCorrect(const MotionState& stage, const std::vector<Vec2>& a0,
                   const std::vector<Vec2>& a1, double h, MotionState* state) {
  kernels::VerletCorrectArgs args;
  args.points = state->position.size();
  args.stage_x = stage.position.data();
  args.a0 = a0.data();
  args.a1 = a1.data();
  args.x = state->position.data();
  args.v = state->velocity.data();
  args.half_h = 0.5 * h;
  kernels::VerletCorrect(ActiveIsa(), args);
}

}  // namespace

void SoftBody::VerletStep(double h, bool drag, MotionState* state) {
  PrepareVerletStep(*state);
  std::vector<Vec2>& a0 = k_[0];
  std::vector<Vec2>& a1 = k_[1];
  AccelerationFrom(geometry_, *state, drag, /*contacts=*/true, &a0);
  VerletPredict(*state, a0, h, &stage_);
  Measure(stage_.position, &next_geometry_);
  AccelerationFrom(next_geometry_, stage_, drag, /*contacts=*/true, &a1);
  VerletCorrect(stage_, a0, a1, h, state);
  std::swap(geometry_, next_geometry_);
  measured_position_ = state->position;
}

void SoftBody::VerletMtsStep(double h, int inner, bool drag,
                             MotionState* state) {
  PrepareVerletStep(*state);
  std::vector<Vec2>& a0 = k_[0];
  std::vector<Vec2>& a1 = k_[1];
  // The slow forces' half kick.
  AccelerationFrom(geometry_, *state, drag, /*contacts=*/false, &a0);
  const double half_h = 0.5 * h;
  for (int i = 0; i < nodes_; ++i) state->velocity[i] += a0[i] * half_h;
  // The contacts alone, by velocity Verlet in `inner` sub-steps of h.
  ContactSubsteps(h / inner, inner, state);
  // The slow forces at the new positions, with the end velocity predicted
  // from the first half kick (as VerletStep predicts v + a0 h), then their
  // second half kick.
  Measure(state->position, &next_geometry_);
  stage_.velocity.resize(nodes_);
  for (int i = 0; i < nodes_; ++i) {
    stage_.velocity[i] = state->velocity[i] + a0[i] * half_h;
  }
  AccelerationFrom(next_geometry_, stage_, drag, /*contacts=*/false, &a1);
  for (int i = 0; i < nodes_; ++i) state->velocity[i] += a1[i] * half_h;
  std::swap(geometry_, next_geometry_);
  measured_position_ = state->position;
}

void SoftBody::ContactSubsteps(double h, int n, MotionState* state) {
  std::vector<Vec2>& c0 = k_[2];
  std::vector<Vec2>& c1 = k_[3];
  for (int j = 0; j < n; ++j) {
    ContactAcceleration(*state, &c0);
    VerletPredict(*state, c0, h, &inner_);
    ContactAcceleration(inner_, &c1);
    VerletCorrect(inner_, c0, c1, h, state);
  }
}

void SoftBody::Rk4Step(double h, bool drag, MotionState* state) {
  // k_[2s] = dx/dt, k_[2s + 1] = dv/dt at stage s.
  stage_.position.resize(nodes_);
  stage_.velocity.resize(nodes_);
  const double offsets[4] = {0.0, 0.5 * h, 0.5 * h, h};
  for (int s = 0; s < 4; ++s) {
    std::vector<Vec2>& dx = k_[2 * s];
    dx.resize(nodes_);
    if (s == 0) {
      for (int i = 0; i < nodes_; ++i) dx[i] = state->velocity[i];
      Acceleration(*state, drag, &k_[1]);
      continue;
    }
    const std::vector<Vec2>& prev_dx = k_[2 * s - 2];
    const std::vector<Vec2>& prev_dv = k_[2 * s - 1];
    for (int i = 0; i < nodes_; ++i) {
      stage_.position[i] = state->position[i] + prev_dx[i] * offsets[s];
      stage_.velocity[i] = state->velocity[i] + prev_dv[i] * offsets[s];
      dx[i] = stage_.velocity[i];
    }
    Acceleration(stage_, drag, &k_[2 * s + 1]);
  }
  const double sixth = h / 6.0;
  for (int i = 0; i < nodes_; ++i) {
    state->position[i] +=
        (k_[0][i] + k_[2][i] * 2.0 + k_[4][i] * 2.0 + k_[6][i]) * sixth;
    state->velocity[i] +=
        (k_[1][i] + k_[3][i] * 2.0 + k_[5][i] * 2.0 + k_[7][i]) * sixth;
  }
}

void SoftBody::Rk3Step(double h, bool drag, const Rk3Tableau& t,
                       MotionState* state) {
  // k_[2s] = dx/dt, k_[2s + 1] = dv/dt at stage s.
  std::vector<Vec2>& dx1 = k_[0];
  std::vector<Vec2>& dv1 = k_[1];
  std::vector<Vec2>& dx2 = k_[2];
  std::vector<Vec2>& dv2 = k_[3];
  std::vector<Vec2>& dx3 = k_[4];
  std::vector<Vec2>& dv3 = k_[5];
  stage_.position.resize(nodes_);
  stage_.velocity.resize(nodes_);
  dx1.resize(nodes_);
  dx2.resize(nodes_);
  dx3.resize(nodes_);
  for (int i = 0; i < nodes_; ++i) dx1[i] = state->velocity[i];
  Acceleration(*state, drag, &dv1);
  const double h21 = h * t.a21;
  for (int i = 0; i < nodes_; ++i) {
    stage_.position[i] = state->position[i] + dx1[i] * h21;
    stage_.velocity[i] = state->velocity[i] + dv1[i] * h21;
    dx2[i] = stage_.velocity[i];
  }
  Acceleration(stage_, drag, &dv2);
  for (int i = 0; i < nodes_; ++i) {
    stage_.position[i] =
        state->position[i] + (dx1[i] * t.a31 + dx2[i] * t.a32) * h;
    stage_.velocity[i] =
        state->velocity[i] + (dv1[i] * t.a31 + dv2[i] * t.a32) * h;
    dx3[i] = stage_.velocity[i];
  }
  Acceleration(stage_, drag, &dv3);
  for (int i = 0; i < nodes_; ++i) {
    state->position[i] += (dx1[i] * t.b1 + dx2[i] * t.b2 + dx3[i] * t.b3) * h;
    state->velocity[i] += (dv1[i] * t.b1 + dv2[i] * t.b2 + dv3[i] * t.b3) * h;
  }
}

void SoftBody::ApplyStableDrag(double h, MotionState* state) {
  const Vec2* x = state->position.data();
  Vec2* v = state->velocity.data();
  const double m = params_.mass;
  drag_matrix_.assign(3 * static_cast<size_t>(nodes_), 0.0);
  drag_rhs_.assign(nodes_, Vec2{});
  for (size_t e = 0; e < skin_a_.size(); ++e) {
    const int a = skin_a_[e];
    const int b = skin_b_[e];
    const Vec2 d = x[b] - x[a];
    const double l = Length(d);
    if (!(l > 0.0)) continue;
    const Vec2 t = d / l;
    const Vec2 n{t.y, -t.x};
    const Vec2 vc = (v[a] + v[b]) * 0.5;
    // G = l (d_T |v_T| t t^T + d_N |v_N| n n^T); the edge's force is -G vc,
    // half to each end, and each end takes G / 2 implicitly.
    const double gt = l * params_.drag_tangential * std::fabs(Dot(vc, t));
    const double gn = l * params_.drag_normal * std::fabs(Dot(vc, n));
    const double g11 = gt * t.x * t.x + gn * n.x * n.x;
    const double g12 = gt * t.x * t.y + gn * n.x * n.y;
    const double g22 = gt * t.y * t.y + gn * n.y * n.y;
    for (int end : {a, b}) {
      // F_end + (G / 2) v_end = (G / 2)(v_end - vc).
      const Vec2 rel = v[end] - vc;
      drag_matrix_[3 * end] += 0.5 * g11;
      drag_matrix_[3 * end + 1] += 0.5 * g12;
      drag_matrix_[3 * end + 2] += 0.5 * g22;
      drag_rhs_[end] +=
          Vec2{g11 * rel.x + g12 * rel.y, g12 * rel.x + g22 * rel.y} * 0.5;
    }
  }
  for (int i = 0; i < nodes_; ++i) {
    const double a11 = m + h * drag_matrix_[3 * i];
    const double a12 = h * drag_matrix_[3 * i + 1];
    const double a22 = m + h * drag_matrix_[3 * i + 2];
    const Vec2 r = v[i] * m + drag_rhs_[i] * h;
    const double det = a11 * a22 - a12 * a12;  // > 0: m I + PSD.
    v[i] = {(a22 * r.x - a12 * r.y) / det, (a11 * r.y - a12 * r.x) / det};
  }
}

double SoftBody::ChamberArea(const MotionState& state, int chamber) const {
  const int begin = walk_begin_[chamber];
  const int end = walk_begin_[chamber + 1];
  return WalkArea(state.position.data(),
                  std::span<const int>(&walk_[begin], end - begin));
}

std::string CheckState(const MotionState& state, double max_coordinate) {
  for (size_t i = 0; i < state.position.size(); ++i) {
    const Vec2 x = state.position[i];
    const Vec2 v = state.velocity[i];
    if (!IsFinite(x)) return "non-finite position of node " + std::to_string(i);
    if (!IsFinite(v)) return "non-finite velocity of node " + std::to_string(i);
    if (std::fabs(x.x) > max_coordinate || std::fabs(x.y) > max_coordinate) {
      char bound[32];
      std::snprintf(bound, sizeof(bound), "%g", max_coordinate);
      return "node " + std::to_string(i) +
             " left the region |x|, |y| <= " + bound;
    }
  }
  return "";
}

void HashMotionState(const MotionState& state, StateHash* hash) {
  for (size_t i = 0; i < state.position.size(); ++i) {
    hash->AddDouble(state.position[i].x);
    hash->AddDouble(state.position[i].y);
    hash->AddDouble(state.velocity[i].x);
    hash->AddDouble(state.velocity[i].y);
  }
}

Vec2 CentreOfMass(const MotionState& state) {
  if (state.position.empty()) return {};
  Vec2 sum;
  for (const Vec2& x : state.position) sum += x;
  const double n = static_cast<double>(state.position.size());
  return sum / n;
}

}  // namespace animat
