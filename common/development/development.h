// Development of an embryo from one cell (docs/model.md §4).
//
// A Development owns the embryo, its network state and its morphogen
// field; the evaluation continues with them after development (signals,
// history and levels carry on into motion). S (double or float) is the
// network's arithmetic (GrnParams::precision); positions and mechanics are
// always double. It keeps a reference to the Network, which must outlive
// it. Not thread-safe; one per evaluation.
#ifndef ANIMAT_COMMON_DEVELOPMENT_DEVELOPMENT_H_
#define ANIMAT_COMMON_DEVELOPMENT_DEVELOPMENT_H_

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "common/base/vec2.h"
#include "common/development/development_params.h"
#include "common/development/signals.h"
#include "common/geometry/contact_pairs.h"
#include "common/geometry/gabriel.h"
#include "common/grn/grn_batch.h"
#include "common/grn/network.h"

namespace animat {

struct Embryo {
  std::vector<Vec2> position;  // Cell centres (radii).
  std::vector<double> radius;  // Radii (default cell radius 1).
  std::vector<double> angle;   // Orientation (radians).
  int cells() const { return static_cast<int>(position.size()); }
};

enum class DevelopmentStatus {
  kOk,
  kLateDivision,      // A division at or after last_division_step.
  kTooFewCells,       // Fewer than min_cells at the end.
  kNumericalFailure,  // A non-finite value or a runaway coordinate.
};

// The numerical check of model §4.4 and §8.3 during development: positions
// and radii must stay finite and every coordinate within max_coordinate
// (radii). Checked after the mechanics of every interval-th step, before a
// late division is reported, and at the end.
struct NumericalCheck {
  double max_coordinate = 1e6;
  int interval = 100;  // Development steps between checks, >= 1.
};

struct DevelopmentOutcome {
  DevelopmentStatus status = DevelopmentStatus::kOk;
  std::string reason;      // Why, when status is not kOk.
  int steps_run = 0;       // Development steps completed.
  int divisions = 0;       // Divisions that happened.
  int last_division = -1;  // Step of the last division, -1 if none.
};

template <typename S>
class DevelopmentT {
 public:
  DevelopmentT(const Network& network, const GrnParams& grn_params,
               const DevelopmentParams& params,
               const SignalParams& signal_params);

  // Called after each step's mechanics with the step number (0-based).
  using Observer = std::function<void(int step, const DevelopmentT&)>;

  // Runs development from the zygote. Stops at once on a late division
  // (its status takes priority over too few cells) or a failed numerical
  // check (which takes priority over both, whatever the cell count). Call
  // once.
  DevelopmentOutcome Run(const Observer& observer = nullptr,
                         const NumericalCheck& check = {});

  const Embryo& embryo() const { return embryo_; }
  GrnBatchT<S>& grn() { return grn_; }
  const GrnBatchT<S>& grn() const { return grn_; }
  MorphogenFieldT<S>& field() { return field_; }
  const MorphogenFieldT<S>& field() const { return field_; }
  const std::array<Vec2, 3>& maternal_sources() const { return sources_; }
  const DevelopmentParams& params() const { return params_; }

  // Computes, in the network and the signals, only the nodes marked in
  // `needed` (indexed by node; Network::NodesReaching). Run() restricts to
  // the nodes that can influence some output; the evaluation narrows this
  // to EXPAND and CONTRACT for motion.
  void RestrictTo(const std::vector<bool>& needed);
  const SignalParams& signal_params() const { return signal_params_; }

 private:
  // Divisions of step `step`; returns the number that happened.
  int Divide(int step, int* late_cell);
  void Mechanics();
  // "" when every position and radius is finite and within the bound,
  // else the reason.
  std::string CheckEmbryo(double max_coordinate) const;

  const Network& network_;
  DevelopmentParams params_;
  SignalParams signal_params_;
  std::array<Vec2, 3> sources_;
  Embryo embryo_;
  GrnBatchT<S> grn_;
  MorphogenFieldT<S> field_;
  std::vector<Vec2> force_;  // Scratch for the mechanics.
  ContactPairs contacts_;    // The pairs the mechanics examine.
};

using Development = DevelopmentT<double>;

extern template class DevelopmentT<double>;
extern template class DevelopmentT<float>;

}  // namespace animat

#endif  // ANIMAT_COMMON_DEVELOPMENT_DEVELOPMENT_H_
