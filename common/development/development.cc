#include "common/development/development.h"

#include <cmath>
#include <cstdio>

#include "common/base/fast_math.h"

namespace animat {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

// The skin of the mechanics' pair list (radii; ContactPairs), chosen by
// measurement (docs/benchmarks.md).
constexpr double kContactSkin = 0.5;

}  // namespace

template <typename S>
DevelopmentT<S>::DevelopmentT(const Network& network,
                              const GrnParams& grn_params,
                              const DevelopmentParams& params,
                              const SignalParams& signal_params)
    : network_(network),
      params_(params),
      signal_params_(signal_params),
      sources_(MaternalSources(signal_params)),
      grn_(network, grn_params, params.max_cells),
      field_(network.morphogen_count(), params.max_cells, signal_params),
      contacts_(kContactSkin) {}

template <typename S>
DevelopmentOutcome DevelopmentT<S>::Run(const Observer& observer,
                                        const NumericalCheck& check) {
  DevelopmentOutcome outcome;
  // The zygote: one cell at the origin, radius 1, angle 0, all levels 0.
  embryo_.position.push_back({0.0, 0.0});
  embryo_.radius.push_back(1.0);
  embryo_.angle.push_back(0.0);
  grn_.AddCell();
  field_.AddCell();
  // Nodes that cannot influence any output are not computed.
  RestrictTo(network_.NodesReaching(kAllOutputChannels));
  const bool signalling = field_.morphogens() > 0;

  for (int step = 0; step < params_.steps; ++step) {
    // 1. Network update, inputs and signals from the current positions.
    for (int cell = 0; cell < embryo_.cells(); ++cell) {
      grn_.SetInputs(cell, InputValuesAt(embryo_.position[cell], sources_,
                                         signal_params_));
    }
    if (signalling) {
      field_.SetGeometry(embryo_.position);
      field_.Record(step, grn_);
      field_.Apply(step, &grn_);
    }
    grn_.Step();
    // 2. Divisions.
    int late_cell = -1;
    const int divisions = Divide(step, &late_cell);
    if (divisions > 0) {
      outcome.divisions += divisions;
      outcome.last_division = step;
    }
    // 3. Mechanics.
    Mechanics();
    outcome.steps_run = step + 1;
    if (observer) observer(step, *this);
    const bool last = step + 1 == params_.steps;
    if (late_cell >= 0 || last || (step + 1) % check.interval == 0) {
      const std::string problem = CheckEmbryo(check.max_coordinate);
      if (!problem.empty()) {
        outcome.status = DevelopmentStatus::kNumericalFailure;
        outcome.reason =
            problem + " at development step " + std::to_string(step);
        return outcome;
      }
    }
    if (late_cell >= 0) {
      outcome.status = DevelopmentStatus::kLateDivision;
      outcome.reason = "cell " + std::to_string(late_cell) +
                       " divided at step " + std::to_string(step) +
                       "; divisions must end before step " +
                       std::to_string(params_.last_division_step);
      return outcome;
    }
  }

  if (embryo_.cells() < params_.min_cells) {
    outcome.status = DevelopmentStatus::kTooFewCells;
    outcome.reason = std::to_string(embryo_.cells()) +
                     (embryo_.cells() == 1 ? " cell" : " cells") +
                     " at the end of development; at least " +
                     std::to_string(params_.min_cells) + " needed";
  }
  return outcome;
}

template <typename S>
std::string DevelopmentT<S>::CheckEmbryo(double max_coordinate) const {
  for (int cell = 0; cell < embryo_.cells(); ++cell) {
    const Vec2 x = embryo_.position[cell];
    if (!IsFinite(x)) {
      return "non-finite position of cell " + std::to_string(cell);
    }
    if (!std::isfinite(embryo_.radius[cell])) {
      return "non-finite radius of cell " + std::to_string(cell);
    }
    if (std::fabs(x.x) > max_coordinate || std::fabs(x.y) > max_coordinate) {
      char bound[32];
      std::snprintf(bound, sizeof(bound), "%g", max_coordinate);
      return "cell " + std::to_string(cell) +
             " left the region |x|, |y| <= " + bound;
    }
  }
  return "";
}

template <typename S>
void DevelopmentT<S>::RestrictTo(const std::vector<bool>& needed) {
  grn_.Restrict(needed);
  std::vector<int> keep;
  const std::vector<int>& nodes = network_.morphogen_nodes();
  for (size_t m = 0; m < nodes.size(); ++m) {
    if (needed[nodes[m]]) keep.push_back(static_cast<int>(m));
  }
  field_.Restrict(keep);
}

template <typename S>
int DevelopmentT<S>::Divide(int step, int* late_cell) {
  int divisions = 0;
  const int cells_before = embryo_.cells();  // Daughters wait a step.
  for (int mother = 0; mother < cells_before; ++mother) {
    if (!(grn_.Output(mother, OutputChannel::kDivide) >=
          params_.divide_threshold)) {
      continue;
    }
    // Blocked by the cap: not a division; DIVIDE is not reset.
    if (embryo_.cells() >= params_.max_cells) continue;
    const double turn = grn_.Output(mother, OutputChannel::kRotateRight) -
                        grn_.Output(mother, OutputChannel::kRotateLeft);
    const double angle = embryo_.angle[mother] + kTwoPi * turn;
    double s, c;
    SinCos(angle, &s, &c);
    const double radius = embryo_.radius[mother];
    embryo_.position.push_back(embryo_.position[mother] + Vec2{c, s} * radius);
    embryo_.radius.push_back(
        1.0 + params_.size_gain * grn_.Output(mother, OutputChannel::kSize));
    embryo_.angle.push_back(angle);
    const int daughter = grn_.CopyCell(mother);
    field_.CopyCell(mother);
    grn_.ResetOutput(mother, OutputChannel::kDivide);
    grn_.ResetOutput(daughter, OutputChannel::kDivide);
    ++divisions;
    if (step >= params_.last_division_step && *late_cell < 0) {
      *late_cell = mother;
    }
  }
  return divisions;
}

template <typename S>
void DevelopmentT<S>::Mechanics() {
  const int n = embryo_.cells();
  const double k = params_.stiffness;
  const double adhesion = params_.adhesion_ratio * k;
  const double range = params_.interaction_range;
  const double dt = params_.mechanics_dt;
  std::vector<Vec2>& x = embryo_.position;
  force_.resize(n);
  for (int sub = 0; sub < params_.mechanics_substeps; ++sub) {
    for (int i = 0; i < n; ++i) force_[i] = {0.0, 0.0};
    // Only pairs near each other; the others cannot pass the test below.
    contacts_.Update(x, embryo_.radius, range);
    for (int i = 0; i < n; ++i) {
      for (int j : contacts_.Partners(i)) {
        const double s = embryo_.radius[i] + embryo_.radius[j];
        const Vec2 delta = x[j] - x[i];
        // Rule out pairs beyond the range without a square root. The
        // margin keeps every pair near the range for the exact test
        // below, so the outcome is the same bit for bit.
        const double reach = ContactPairs::Reach(range, s);
        const double d2 = delta.x * delta.x + delta.y * delta.y;
        if (d2 > reach * reach) continue;
        double d = std::sqrt(d2);
        if (!(d < range * s)) continue;
        Vec2 u;
        if (d < kCoincidentDistance) {
          // Coincident: the younger cell (j > i) moves forward along its
          // orientation, the older back.
          double sn, cs;
          SinCos(embryo_.angle[j], &sn, &cs);
          u = {cs, sn};
          d = 0.0;
        } else {
          u = delta / d;
        }
        const double f = d < s ? k * (d - s) : adhesion * (d - s);
        force_[i] += u * f;
        force_[j] -= u * f;
      }
    }
    for (int i = 0; i < n; ++i) x[i] += force_[i] * dt;
  }
}

template class DevelopmentT<double>;
template class DevelopmentT<float>;

}  // namespace animat
