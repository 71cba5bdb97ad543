#include "common/evaluation/signal_saturation.h"

#include <algorithm>

#include "common/kernels/kernels.h"

namespace animat {
namespace {

// K(d) and tau(d) of each distance, by the model's own kernels (those
// development and motion use).
void PairKernelsOf(const std::vector<double>& distance,
                   const SignalParams& params, std::vector<double>* kernel,
                   std::vector<double>* delay) {
  kernel->resize(distance.size());
  delay->resize(distance.size());
  kernels::PairKernelArgs args;
  args.pairs = distance.size();
  args.distance = distance.data();
  args.kernel_length = params.kernel_length;
  args.delay_length = params.delay_length;
  args.max_delay = params.max_delay;
  args.kernel = kernel->data();
  args.delay = delay->data();
  kernels::PairKernels(args);
}

}  // namespace

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
  const size_t n = positions.size();
  std::vector<double> distance, kernel, delay;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = i + 1; k < n; ++k) {
      distance.push_back(Length(positions[k] - positions[i]));
    }
  }
  PairKernelsOf(distance, params, &kernel, &delay);
  std::vector<double> sums(n, 1.0);  // K(0) = 1: the cell itself.
  size_t pair = 0;
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = i + 1; k < n; ++k, ++pair) {
      sums[i] += kernel[pair];
      sums[k] += kernel[pair];
    }
  }
  return sums;
}

int SignalDelay(double distance, const SignalParams& params) {
  std::vector<double> kernel, delay;
  PairKernelsOf({distance}, params, &kernel, &delay);
  return static_cast<int>(delay[0]);
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
