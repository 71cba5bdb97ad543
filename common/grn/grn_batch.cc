#include "common/grn/grn_batch.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "common/base/fast_math.h"

namespace animat {

GrnBatch::GrnBatch(const Network& network, const GrnParams& params,
                   int capacity)
    : network_(&network), dt_(params.dt), capacity_(capacity) {
  assert(capacity > 0);
  const size_t cap = static_cast<size_t>(capacity);
  levels_.assign(network.node_count() * cap, 0.0);
  signals_.assign(network.morphogen_count() * cap, 0.0);
  activation_.assign(network.targets().size() * cap, 0.0);
}

int GrnBatch::AddCell() {
  assert(cells_ < capacity_);
  const int cell = cells_++;
  for (int v = 0; v < network_->node_count(); ++v) {
    levels_[static_cast<size_t>(v) * capacity_ + cell] = 0.0;
  }
  for (int m = 0; m < network_->morphogen_count(); ++m) {
    signals_[static_cast<size_t>(m) * capacity_ + cell] = 0.0;
  }
  frozen_ = false;
  return cell;
}

int GrnBatch::CopyCell(int mother) {
  assert(cells_ < capacity_ && mother >= 0 && mother < cells_);
  const int cell = cells_++;
  for (int v = 0; v < network_->node_count(); ++v) {
    double* row = &levels_[static_cast<size_t>(v) * capacity_];
    row[cell] = row[mother];
  }
  for (int m = 0; m < network_->morphogen_count(); ++m) {
    double* row = &signals_[static_cast<size_t>(m) * capacity_];
    row[cell] = row[mother];
  }
  frozen_ = false;
  return cell;
}

void GrnBatch::SetInputs(int cell,
                         const std::array<double, kInputChannels>& values) {
  for (int c = 0; c < kInputChannels; ++c) {
    for (int v : network_->input_nodes(c)) {
      levels_[static_cast<size_t>(v) * capacity_ + cell] = values[c];
    }
  }
  frozen_ = false;
}

void GrnBatch::SetOwnSignals() {
  const std::vector<int>& nodes = network_->morphogen_nodes();
  for (size_t m = 0; m < nodes.size(); ++m) {
    const double* level = level_row(nodes[m]);
    double* signal = signal_row(static_cast<int>(m));
    for (int c = 0; c < cells_; ++c) {
      signal[c] = level[c] > 1.0 ? 1.0 : level[c];
    }
  }
}

void GrnBatch::AccumulateSources(int first, int last) {
  const Network& net = *network_;
  const std::vector<Source>& sources = net.sources();
  const std::vector<int>& begin = net.row_begin();
  const int* target = net.weight_target().data();
  const double* weight = net.weight_value().data();
  const int n = cells_;
  for (int s = first; s < last; ++s) {
    const Source& source = sources[s];
    const double* value =
        source.kind == SourceKind::kMorphogen
            ? &signals_[static_cast<size_t>(
                            net.nodes()[source.node].morphogen) *
                        capacity_]
            : &levels_[static_cast<size_t>(source.node) * capacity_];
    for (int k = begin[s]; k < begin[s + 1]; ++k) {
      double* a = &activation_[static_cast<size_t>(target[k]) * capacity_];
      const double w = weight[k];
      for (int c = 0; c < n; ++c) a[c] += w * value[c];
    }
  }
}

void GrnBatch::FreezeInputs() {
  std::fill(activation_.begin(), activation_.end(), 0.0);
  AccumulateSources(0, network_->input_source_count());
  input_partial_ = activation_;
  frozen_ = true;
}

void GrnBatch::Step() {
  const Network& net = *network_;
  const int sources = static_cast<int>(net.sources().size());
  if (frozen_) {
    std::copy(input_partial_.begin(), input_partial_.end(),
              activation_.begin());
    AccumulateSources(net.input_source_count(), sources);
  } else {
    std::fill(activation_.begin(), activation_.end(), 0.0);
    AccumulateSources(0, sources);
  }
  // All activations are computed before any level changes: synchronous.
  const std::vector<int>& targets = net.targets();
  const double dt = dt_;
  const int n = cells_;
  for (size_t t = 0; t < targets.size(); ++t) {
    double* a = &activation_[t * capacity_];
    double* level = &levels_[static_cast<size_t>(targets[t]) * capacity_];
    for (int c = 0; c < n; ++c) {
      const double l = level[c];
      const double x = l + (Tanh(a[c] * 0.5) - l) * dt;
      level[c] = x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);
    }
  }
}

double GrnBatch::Output(int cell, OutputChannel channel) const {
  // Levels lie in [0, 1], so starting from 0 gives the maximum (and 0 for
  // a channel without nodes). A NaN level is returned, never hidden.
  double value = 0.0;
  for (int v : network_->output_nodes(static_cast<int>(channel))) {
    const double l = level(cell, v);
    if (std::isnan(l)) return l;
    value = std::max(value, l);
  }
  return value;
}

void GrnBatch::ResetOutput(int cell, OutputChannel channel) {
  for (int v : network_->output_nodes(static_cast<int>(channel))) {
    levels_[static_cast<size_t>(v) * capacity_ + cell] = 0.0;
  }
}

}  // namespace animat
