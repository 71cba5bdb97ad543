#include "common/evaluation/signal_saturation.h"

#include <algorithm>
#include <cmath>

namespace animat {

long long SignalSaturation::values() const {
  long long n = 0;
  for (const MorphogenSaturation& m : morphogens) n += m.values;
  return n;
}

long long SignalSaturation::capped() const {
  long long n = 0;
  for (const MorphogenSaturation& m : morphogens) n += m.capped;
  return n;
}

void SaturationCounter::OnSignals(int step, std::span<const int> nodes,
                                  int cells, std::span<const double> signal) {
  (void)step;
  ++steps_;
  for (size_t m = 0; m < nodes.size(); ++m) {
    auto it = std::find_if(
        morphogens_.begin(), morphogens_.end(),
        [&](const MorphogenSaturation& s) { return s.node == nodes[m]; });
    if (it == morphogens_.end()) {
      // Kept in node order, whatever order the rows come in.
      it = morphogens_.insert(
          std::upper_bound(morphogens_.begin(), morphogens_.end(), nodes[m],
                           [](int node, const MorphogenSaturation& s) {
                             return node < s.node;
                           }),
          MorphogenSaturation{nodes[m], 0, 0});
    }
    const double* row = signal.data() + m * static_cast<size_t>(cells);
    it->values += cells;
    for (int i = 0; i < cells; ++i) it->capped += row[i] >= 1.0;
  }
}

void SaturationCounter::OnBody(const Body& body, std::span<const double>,
                               std::span<const double>) {
  positions_ = body.position;
}

double Diameter(std::span<const Vec2> positions) {
  double widest = 0.0;
  for (size_t i = 0; i < positions.size(); ++i) {
    for (size_t k = i + 1; k < positions.size(); ++k) {
      widest = std::max(widest, Length(positions[k] - positions[i]));
    }
  }
  return widest;
}

std::vector<double> KernelSums(std::span<const Vec2> positions,
                               const SignalParams& params) {
  std::vector<double> sums;
  for (const Vec2 p : positions) {
    double sum = 0.0;
    for (const Vec2 q : positions) {
      sum += std::exp(-Length(q - p) / params.kernel_length);
    }
    sums.push_back(sum);
  }
  return sums;
}

int SignalDelay(double distance, const SignalParams& params) {
  const double steps = std::floor(distance / params.delay_length + 0.5);
  return steps >= params.max_delay ? params.max_delay : static_cast<int>(steps);
}

Result<SignalSaturation> MeasureSignalSaturation(const Genome& genome,
                                                 const ModelConfig& config) {
  SaturationCounter counter;
  const EvaluationResult result = Evaluate(genome, config, &counter);
  if (result.status != EvalStatus::kOk) {
    return Status::InvalidArgument(
        "the animat has no motion to measure: its evaluation ended " +
        std::string(EvalStatusName(result.status)) +
        (result.reason.empty() ? "" : " (" + result.reason + ")"));
  }
  SignalSaturation s;
  s.cells = result.cells;
  s.motion_steps = config.evaluation.motion_steps;
  s.diameter = Diameter(counter.body_positions());
  s.crossing_steps = SignalDelay(s.diameter, config.signals);
  s.morphogens = counter.morphogens();
  const std::vector<double> sums =
      KernelSums(counter.body_positions(), config.signals);
  for (const double sum : sums) {
    s.kernel_sum_mean += sum / static_cast<double>(sums.size());
    s.kernel_sum_max = std::max(s.kernel_sum_max, sum);
  }
  return s;
}

}  // namespace animat
