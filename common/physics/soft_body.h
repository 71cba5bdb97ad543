// Forces on a soft body and their integration (docs/model.md §7).
//
// SoftBody compiles a Body into flat arrays once; the running state
// (positions, velocities) is a MotionState owned by the caller. Rest lengths
// follow the actuation set by SetActuation. Step integrates with the
// params' integrator, sub-steps and drag update (other backends implement
// MotionStepper with SoftBody's forces). A SoftBody is not thread-safe (it
// keeps scratch buffers); use one per simulation.
#ifndef ANIMAT_COMMON_PHYSICS_SOFT_BODY_H_
#define ANIMAT_COMMON_PHYSICS_SOFT_BODY_H_

#include <span>
#include <string>
#include <vector>

#include "common/base/hash.h"
#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/physics/contacts.h"
#include "common/physics/physics_params.h"

namespace animat {

struct MotionState {
  std::vector<Vec2> position;  // Radii.
  std::vector<Vec2> velocity;  // Radii per unit time.
};

// Advances a MotionState by one simulation step (dt) under the forces of a
// SoftBody at its current actuation.
class MotionStepper {
 public:
  virtual ~MotionStepper() = default;
  virtual void Step(MotionState* state) = 0;
};

class SoftBody : public MotionStepper {
 public:
  // A three-stage explicit Runge-Kutta scheme, y' = f(y) with y = (x, v):
  //   k1 = f(y), k2 = f(y + h a21 k1), k3 = f(y + h (a31 k1 + a32 k2)),
  //   y <- y + h (b1 k1 + b2 k2 + b3 k3),
  // each product and sum evaluated as written, left to right.
  struct Rk3Tableau {
    double a21, a31, a32, b1, b2, b3;
  };

  // Actuation starts at 0 (rest lengths L0). Precondition: the body's
  // indices are valid and chambers have rest_area > 0 (BuildBody and
  // SceneFromProto guarantee both).
  SoftBody(const Body& body, const PhysicsParams& params);

  int nodes() const { return nodes_; }
  const PhysicsParams& params() const { return params_; }

  // Rest lengths from each node's EXPAND and CONTRACT values:
  //   L = max(min_rest_fraction, 1 + A_max (e_a + e_b - c_a - c_b)) L0.
  // The change of each rest length is charged as actuation work at the
  // next force evaluation (actuation_work()).
  void SetActuation(std::span<const double> expand,
                    std::span<const double> contract);
  // Current rest length of each spring.
  const std::vector<double>& rest_lengths() const { return rest_; }

  // The work of the actuators (docs/model.md §10.1): at the first force
  // evaluation after each SetActuation, the sum over springs, in index
  // order, of |f dL|, where dL is the change of the spring's rest length L
  // made by that SetActuation and f = k (l - L) its elastic force there
  // (l its length at the state the forces are computed at: the start of
  // the step). Summed since construction or the last reset; a constant
  // actuation adds 0 after its first step.
  double actuation_work() const { return work_; }
  void ResetActuationWork() { work_ = 0.0; }
  // How far the actuation holds the rest lengths from rest: the sum over
  // springs, in index order, of |L - L0| (radii). The holding cost of
  // docs/model.md §10.1 charges it once per motion step.
  double HeldActuation() const;

  // Total force on every node at `state`: springs, pressure, drag unless
  // `drag` is false, then contacts (model §7.10) on the native backend
  // (the Bullet backend's world makes its own).
  void ComputeForces(const MotionState& state, std::vector<Vec2>* force,
                     bool drag = true);
  // Each force family alone (for tests and analysis); forces are added.
  void AddSpringForces(const MotionState& state, Vec2* force) const;
  void AddPressureForces(const MotionState& state, Vec2* force) const;
  void AddDragForces(const MotionState& state, Vec2* force) const;
  void AddContactForces(const MotionState& state, Vec2* force);

  // The deepest overlap of two cells not joined by a spring at `state`
  // (model §8.6), whatever the contact rule: Contacts::
  // DeepestUnjoinedOverlap.
  double DeepestUnjoinedOverlap(const MotionState& state) {
    return contacts_.DeepestUnjoinedOverlap(state.position);
  }

  // One simulation step of dt in params().substeps sub-steps of
  // h = dt / substeps, each by params().integrator:
  //   semi-implicit Euler (model §7.6): v <- v + F(x, v) / m h; x <- x + v h;
  //   velocity Verlet: x <- x + v h + a0 h^2 / 2 with a0 = F(x, v) / m,
  //     a1 = F(x', v + a0 h) / m, v <- v + (a0 + a1) h / 2. The geometry
  //     of x' (spring and skin lengths and directions, pressure) serves
  //     the next sub-step's a0 as long as the positions are unchanged bit
  //     for bit, so each sub-step measures the geometry once; only the
  //     velocity-dependent terms and the rest lengths are evaluated twice;
  //   velocity Verlet with contact_inner_substeps n > 0 (impulse multiple
  //     time stepping): a0 = S(x, v) / m of the forces but contacts;
  //     v <- v + a0 h / 2; then n velocity Verlet sub-steps of h / n under
  //     the contacts alone; a1 = S(x', v + a0 h / 2) / m with the velocity
  //     after them; v <- v + a1 h / 2;
  //   RK4: the classical fourth-order Runge-Kutta on (x, v);
  //   SSPRK3, RALSTON3: three-stage third-order Runge-Kutta on (x, v)
  //     (Rk3Tableau below), three force evaluations.
  // With DragUpdate::kStable the integrator sees no drag; instead
  // ApplyStableDrag(h / 2) runs before and after it (Strang splitting).
  void Step(MotionState* state) override;

  // Drag alone over time h, linearly implicit in each node's velocity with
  // the drag coefficients of the current velocities:
  //   (m I + h D_i) v_i' = m v_i + h (F_i + D_i v_i),
  // where F_i is node i's explicit drag force (model §7.4) and D_i = sum over
  // its skin edges of l (d_T |v_T| t t^T + d_N |v_N| n n^T) / 2. Exact for a
  // translating edge (v' = v / (1 + c |v| h)); never reverses the velocity
  // of a translating body.
  void ApplyStableDrag(double h, MotionState* state);

  // Current signed area of each chamber along its rest walk.
  double ChamberArea(const MotionState& state, int chamber) const;
  int chambers() const { return static_cast<int>(rest_area_.size()); }

 private:
  PhysicsParams params_;
  int nodes_;
  std::vector<int> spring_a_, spring_b_;
  std::vector<double> rest0_, rest_;
  std::vector<double> rest_change_;  // dL of the last SetActuation.
  bool work_pending_ = false;        // It is not yet charged.
  double work_ = 0.0;
  std::vector<int> walk_begin_, walk_;  // Chamber walks, flattened.
  std::vector<int> walk_next_;          // The node after walk_[k] in its walk.
  std::vector<double> rest_area_;
  std::vector<int> skin_a_, skin_b_;
  Contacts contacts_;
  // Springs' forces added to `force`; returns, with kWork, the work of
  // the last rest-length change at `state` (actuation_work()), else 0.
  template <bool kWork>
  double AddSprings(const MotionState& state, Vec2* force) const;
  // One sub-step of h; `drag` says whether drag is among the forces.
  void EulerStep(double h, bool drag, MotionState* state);
  void VerletStep(double h, bool drag, MotionState* state);
  // Velocity Verlet's sub-step with the contacts integrated apart, in
  // `inner` sub-steps of h / inner (Step's comment).
  void VerletMtsStep(double h, int inner, bool drag, MotionState* state);
  // The contacts alone over n velocity Verlet sub-steps of h.
  void ContactSubsteps(double h, int n, MotionState* state);
  // geometry_ <- the geometry of state's positions unless already
  // measured there; charges the pending actuation work.
  void PrepareVerletStep(const MotionState& state);
  void Rk4Step(double h, bool drag, MotionState* state);
  void Rk3Step(double h, bool drag, const Rk3Tableau& tableau,
               MotionState* state);
  // What the forces need of the positions alone (model §7): each spring's
  // length and unit vector, each skin edge's length and tangent, and the
  // pressure force on each node.
  struct Geometry {
    std::vector<double> spring_length;
    std::vector<Vec2> spring_unit;
    std::vector<double> skin_length;
    std::vector<Vec2> skin_tangent;
    std::vector<Vec2> pressure;
  };
  void Measure(const std::vector<Vec2>& position, Geometry* geometry) const;
  // Pressure (AddPressureForces) at positions x.
  void AddPressure(const Vec2* x, Vec2* force) const;
  // out <- F / m from the geometry of `state`'s positions, its velocities
  // and the current rest lengths: pressure, then springs, then drag, then
  // contacts, each in index order.
  // Without `contacts`, the positions of `state` are not read.
  void AccelerationFrom(const Geometry& geometry, const MotionState& state,
                        bool drag, bool contacts, std::vector<Vec2>* out);
  // out <- the contact forces alone at `state`, over the mass.
  void ContactAcceleration(const MotionState& state, std::vector<Vec2>* out);
  // F <- F / m, node by node.
  void DivideByMass(std::vector<Vec2>* force) const;
  // force_ <- acceleration F / m at `state`.
  void Acceleration(const MotionState& state, bool drag,
                    std::vector<Vec2>* out);

  // Scratch, kept between steps to avoid allocation.
  std::vector<Vec2> force_;
  MotionState stage_;
  MotionState inner_;  // Contact sub-steps' stage.
  std::vector<Vec2> k_[8];
  std::vector<double> drag_matrix_;  // 3 per node: a11, a12, a22.
  // Velocity Verlet: the geometry of the positions the last sub-step left,
  // and of the next ones.
  Geometry geometry_, next_geometry_;
  std::vector<Vec2> measured_position_;  // Where geometry_ was measured.
  std::vector<Vec2> drag_rhs_;
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
