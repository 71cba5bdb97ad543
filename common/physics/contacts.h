// Contacts between cells during equilibration and motion (docs/model.md
// §7.10, model v3), and the deepest overlap of cells not joined by a spring
// that every evaluation reports (§8.6).
//
// For a pair i < j whose cells overlap, δ = r_i + r_j − l > 0 (l the
// distance of the centres, u the unit vector from i to j, u = 0 when
// l = 0), with approach speed w = −(v_j − v_i) · u:
//
//   f = max(0, k_c · δ + γ_c · w),   F_j += f · u,   F_i −= f · u.
//
// The rule says which pairs: none, those not joined by a spring, or all.
// Pairs are visited in increasing (i, j) order; pairs that do not overlap,
// or whose f is not positive, add nothing. A Verlet list (ContactPairs)
// finds the candidates, so the result is exactly that of testing every
// pair. The overlapping pairs' geometry (u, δ) is found once per positions
// and kept while the velocities change (an integrator evaluates the forces
// twice at each sub-step's end positions), with the same arithmetic.
// Radii are the cells' radii at the end of development.
//
// Lengths in radii, velocities in radii per unit time, forces in the
// model's units. Owns its storage; not thread-safe (scratch state in the
// pair lists): one per simulation; copies are independent.
#ifndef ANIMAT_COMMON_PHYSICS_CONTACTS_H_
#define ANIMAT_COMMON_PHYSICS_CONTACTS_H_

#include <span>
#include <vector>

#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/geometry/contact_pairs.h"
#include "common/physics/physics_params.h"

namespace animat {

class Contacts {
 public:
  // The cells of `body` (its radii, or 1 where it has none) under
  // params' rule, k_c and γ_c. `forces` false: AddForces adds nothing
  // whatever the rule (the Bullet backend's world makes its own contacts);
  // overlaps are measured all the same.
  Contacts(const Body& body, const PhysicsParams& params, bool forces);

  // Whether AddForces can add anything.
  bool active() const { return active_; }

  // Adds the contact forces at positions x and velocities v (one per
  // cell) to `force`.
  void AddForces(std::span<const Vec2> x, std::span<const Vec2> v, Vec2* force);

  // Whether some pair that AddForces admits lies closer than
  // (1 + margin) · (r_i + r_j) at positions x (squared distances
  // compared): a contact acts there now or may within a step (docs/model.md
  // §7.6, contact sub-steps). `margin` >= 0; false when !active().
  bool Near(std::span<const Vec2> x, double margin);

  // The deepest overlap of two cells not joined by a spring at positions
  // x: the largest δ / (r_i + r_j), in (0, 1], or 0 when no such pair
  // overlaps. Pairs whose δ is not a number are ignored (the evaluation's
  // numerical check reports them).
  double DeepestUnjoinedOverlap(std::span<const Vec2> x);

 private:
  // A pair that overlaps at the positions of the forces' list's last
  // move: its cells, unit vector from i to j, δ and r_i + r_j.
  // The positions are met twice (a sub-step's end is the next one's
  // start), and only the velocities change between; under UNJOINED the
  // deepest overlap reads them too.
  struct Touch {
    int i;
    int j;
    Vec2 u;
    double delta;
    double s;
  };
  // Makes touching_ for the positions x of `pairs`' last Update.
  void FindTouching(std::span<const Vec2> x, const ContactPairs& pairs);

  std::vector<double> radius_;
  double stiffness_;
  double damping_;
  bool active_;
  // Candidates for pairs not joined by a spring (overlap measurement; the
  // forces too under UNJOINED) and for every pair (forces under ALL).
  ContactPairs unjoined_;
  ContactPairs all_;
  // Candidates for Near: the admitted pairs, listed at its wider reach.
  ContactPairs near_;
  bool forces_use_all_;
  std::vector<Touch> touching_;
  long long touching_moves_ = -1;  // The list's moves() it is for.
};

}  // namespace animat

#endif  // ANIMAT_COMMON_PHYSICS_CONTACTS_H_
