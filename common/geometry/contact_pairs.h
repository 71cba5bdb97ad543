// The cell pairs near enough to interact: a Verlet list, so that a force
// evaluation looks at the pairs near each other instead of all n(n-1)/2.
// Development's mechanics (docs/model.md §4.3) and the motion's contacts
// (§7.10) use it.
//
// A pair interacts while d < range · (r_i + r_j). The list holds every
// pair i < j within that reach plus a margin `skin` (radii) of where the
// cells were when it was built, in increasing (i, j) order, less the pairs
// excluded once and for all (Exclude). It stays valid while no cell has
// moved more than a fraction of the skin since then: two cells that were
// farther apart than reach + skin cannot have come within reach. Update()
// rebuilds it when a cell has moved that far, when the cell count or the range
// has changed, and whenever a coordinate is not finite or beyond 2^20 radii
// (where the rounding of the distances is no longer far below the margin). A
// pair left out (and not excluded) therefore fails the exact test d < range ·
// s: visiting only the listed pairs, in the same order, gives the same forces
// bit for bit. Radii must not change between rebuilds (development fixes a
// cell's radius at its birth; a rebuild after a radius changed heeds it). An
// Update at the very positions (the same bits) of the one before costs a
// comparison of the positions only: integrators evaluate forces more than
// once at one state. A rebuild tests every pair in vectors
// (kernels::NearPairs on the instruction-set path in use; the same list on
// every path), against each pair's bound computed once.
//
// Lengths in cell radii. Owns its storage; not thread-safe (one per
// simulation); copies are independent.
#ifndef ANIMAT_COMMON_GEOMETRY_CONTACT_PAIRS_H_
#define ANIMAT_COMMON_GEOMETRY_CONTACT_PAIRS_H_

#include <span>
#include <vector>

#include "common/base/vec2.h"
#include "common/geometry/gabriel.h"

namespace animat {

class ContactPairs {
 public:
  // `skin` > 0: radii added to every pair's reach when the list is built.
  explicit ContactPairs(double skin);

  // Pairs never to list (a, b in either order; any number of times),
  // replacing those given before. Takes effect at the next Update.
  void Exclude(std::span<const IndexEdge> pairs);

  // Makes the list valid for these positions and radii (one per cell, in
  // cell order) and the interaction range (> 0), rebuilding it if needed.
  void Update(std::span<const Vec2> position, std::span<const double> radius,
              double range);

  // After Update(): the cells j > i listed with cell i, increasing.
  std::span<const int> Partners(int i) const {
    return {partner_.data() + begin_[i], partner_.data() + begin_[i + 1]};
  }

  // Times the list was built (for tests and benchmarks).
  long long builds() const { return builds_; }

  // Counts the Updates at positions other than the last Update's (their
  // bits), or at another range: equal counts mean the same positions, so
  // what a caller computed from them at that count still holds.
  long long moves() const { return moves_; }

  // The reach of a pair in the mechanics' pre-filter: a pair farther
  // apart than this (squared distances compared) is out of range, with a
  // relative margin of 1e-9 so that every pair near the range goes to
  // the exact test.
  static double Reach(double range, double s) {
    return range * s * (1.0 + 1e-9);
  }

 private:
  bool Valid(std::span<const Vec2> position) const;
  void Build(std::span<const Vec2> position, std::span<const double> radius,
             double range);
  // Makes the pairs' bounds for these radii and range, unless they are
  // already theirs.
  void MakeBounds(std::span<const double> radius, double range);

  double skin_;
  long long builds_ = 0;
  long long moves_ = 0;
  double built_range_ = 0.0;    // The range of the last Build.
  std::vector<Vec2> built_at_;  // Positions when the list was built.
  // The positions of the last Update: the same bits again need no check.
  std::vector<Vec2> last_seen_;
  std::vector<int> begin_;  // Cell i's partners: [begin_[i], begin_[i+1]).
  std::vector<int> partner_;
  // Cell i's excluded partners j > i, increasing, in
  // [excluded_begin_[i], excluded_begin_[i+1]) (empty: none excluded).
  std::vector<int> excluded_begin_;
  std::vector<int> excluded_;
  // Every pair i < j, row by row (cell i's j = i + 1 .. n - 1 from
  // row_begin_[i]), with the square of its reach plus the skin (Build's
  // bound), or -1 for an excluded pair: computed once for the radii and
  // range it was made for (made again when either changes, or by Exclude).
  double bounds_range_ = 0.0;
  std::vector<double> bounds_radius_;
  std::vector<int> row_begin_;
  std::vector<double> bound2_;
  // The positions of the last Build, coordinate by coordinate.
  std::vector<double> x_;
  std::vector<double> y_;
};

}  // namespace animat

#endif  // ANIMAT_COMMON_GEOMETRY_CONTACT_PAIRS_H_
