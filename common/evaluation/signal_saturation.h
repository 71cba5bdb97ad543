// How saturated an animat's morphogen signals are during motion, and how
// long a signal takes to cross its body (docs/analysis.md, "Signal
// saturation"): a measurement of the model (docs/model.md §5.2), not part
// of it.
//
// The signal a cell sees is M = min(1, sum of K(d) L(t - tau(d))) over
// every cell. The cap binds where that sum reaches 1: M then reads exactly
// 1 and says nothing of how far the sources are or how strongly they
// make. A signal from one end of the body reaches the other after
// tau(diameter) steps, the largest delay between two cells.
//
// Pure functions of their arguments; thread-safe.
#ifndef ANIMAT_COMMON_EVALUATION_SIGNAL_SATURATION_H_
#define ANIMAT_COMMON_EVALUATION_SIGNAL_SATURATION_H_

#include <span>
#include <string>
#include <vector>

#include "common/base/status.h"
#include "common/base/vec2.h"
#include "common/development/development_params.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"

namespace animat {

// One morphogen's signal over the motion phase.
struct MorphogenSaturation {
  int node = -1;         // The unit that makes it (model §2.1).
  long long values = 0;  // (cell, step) pairs seen: cells x motion steps.
  long long capped = 0;  // Of those, M at the cap (the sum reached 1).
  // The share of values at the cap, in [0, 1]; 0 without values.
  double share() const {
    return values > 0 ? static_cast<double>(capped) / values : 0.0;
  }
};

struct SignalSaturation {
  int cells = 0;
  int motion_steps = 0;
  // The largest distance between two cell centres of the body (radii).
  double diameter = 0.0;
  // tau(diameter) (model §5.2): the steps a signal takes to cross the body.
  int crossing_steps = 0;
  // The kernel sum of each cell, sum over cells k of K(d_ik) (itself
  // included: >= 1), its mean and largest over the cells. Levels all at L
  // make M = min(1, L x that sum): a cell's signal is at the cap for any
  // L >= 1 / its sum.
  double kernel_sum_mean = 0.0;
  double kernel_sum_max = 0.0;
  // Every morphogen motion computes, in node order (empty if none: then
  // no signal changes during motion).
  std::vector<MorphogenSaturation> morphogens;
  // All morphogens together.
  long long values() const;
  long long capped() const;
};

// Counts, from the signals an evaluation shows its observer, the values at
// the cap. Feed it to Evaluate, or call OnSignals directly.
class SaturationCounter : public EvaluationObserver {
 public:
  void OnSignals(int step, std::span<const int> nodes, int cells,
                 std::span<const double> signal) override;
  void OnBody(const Body& body, std::span<const double> expand,
              std::span<const double> contract) override;

  const std::vector<MorphogenSaturation>& morphogens() const {
    return morphogens_;
  }
  const std::vector<Vec2>& body_positions() const { return positions_; }
  int steps() const { return steps_; }

 private:
  std::vector<MorphogenSaturation> morphogens_;
  std::vector<Vec2> positions_;
  int steps_ = 0;
};

// The largest distance between two of `positions` (0 for fewer than two).
double Diameter(std::span<const Vec2> positions);

// Each cell's sum over every cell k of K(d_ik) = exp(-d_ik / kernel_length)
// (model §5.2), itself included.
std::vector<double> KernelSums(std::span<const Vec2> positions,
                               const SignalParams& params);

// tau(d) = min(max_delay, floor(d / delay_length + 0.5)) (model §5.2).
int SignalDelay(double distance, const SignalParams& params);

// Evaluates `genome` under `config` and measures its signals. Fails
// (kInvalidArgument, with the status and reason) when the evaluation does
// not end OK: a failed animat has no motion to measure. With guidance,
// the first trial's motion.
Result<SignalSaturation> MeasureSignalSaturation(const Genome& genome,
                                                 const ModelConfig& config);

}  // namespace animat

#endif  // ANIMAT_COMMON_EVALUATION_SIGNAL_SATURATION_H_
