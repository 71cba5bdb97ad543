#include "common/grn/grn_batch.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "common/kernels/kernels.h"

namespace animat {
template <typename S>
GrnBatchT<S>::GrnBatchT(const Network& network, const GrnParams& params,
                        int capacity)
    : network_(&network), dt_(static_cast<S>(params.dt)), capacity_(capacity) {
  assert(capacity > 0);
  const size_t cap = static_cast<size_t>(capacity);
  levels_.assign(network.node_count() * cap, 0.0);
  signals_.assign(network.morphogen_count() * cap, 0.0);
  activation_.assign(network.targets().size() * cap, 0.0);
  Restrict({});
}

template <typename S>
void GrnBatchT<S>::Restrict(const std::vector<bool>& needed) {
  const Network& net = *network_;
  active_targets_.clear();
  active_sources_.clear();
  active_static_sources_ = 0;
  for (size_t t = 0; t < net.targets().size(); ++t) {
    if (needed.empty() || needed[net.targets()[t]]) {
      active_targets_.push_back(static_cast<int>(t));
    }
  }
  // A source that is not needed has no path to a needed node, so it has
  // no weight onto one: dropping it changes no needed sum. Weights onto
  // targets that are not needed are dropped too.
  row_begin_.assign(1, 0);
  row_target_.clear();
  row_weight_.clear();
  const std::vector<int>& begin = net.row_begin();
  for (size_t s = 0; s < net.sources().size(); ++s) {
    if (!needed.empty() && !needed[net.sources()[s].node]) continue;
    active_sources_.push_back(static_cast<int>(s));
    if (static_cast<int>(s) < net.static_input_source_count()) {
      ++active_static_sources_;
    }
    for (int k = begin[s]; k < begin[s + 1]; ++k) {
      const int t = net.weight_target()[k];
      if (!needed.empty() && !needed[net.targets()[t]]) continue;
      row_target_.push_back(t);
      row_weight_.push_back(static_cast<S>(net.weight_value()[k]));
    }
    row_begin_.push_back(static_cast<int>(row_target_.size()));
  }
  frozen_ = false;
}

template <typename S>
int GrnBatchT<S>::AddCell() {
  assert(cells_ < capacity_);
  const int cell = cells_++;
  for (int v = 0; v < network_->node_count(); ++v) {
    levels_[static_cast<size_t>(v) * capacity_ + cell] = S{0};
  }
  for (int m = 0; m < network_->morphogen_count(); ++m) {
    signals_[static_cast<size_t>(m) * capacity_ + cell] = S{0};
  }
  frozen_ = false;
  return cell;
}

template <typename S>
int GrnBatchT<S>::CopyCell(int mother) {
  assert(cells_ < capacity_ && mother >= 0 && mother < cells_);
  const int cell = cells_++;
  for (int v = 0; v < network_->node_count(); ++v) {
    S* row = &levels_[static_cast<size_t>(v) * capacity_];
    row[cell] = row[mother];
  }
  for (int m = 0; m < network_->morphogen_count(); ++m) {
    S* row = &signals_[static_cast<size_t>(m) * capacity_];
    row[cell] = row[mother];
  }
  frozen_ = false;
  return cell;
}

template <typename S>
void GrnBatchT<S>::SetInputs(int cell,
                             const std::array<double, kInputChannels>& values) {
  for (int c = 0; c < kInputChannels; ++c) {
    for (int v : network_->input_nodes(c)) {
      levels_[static_cast<size_t>(v) * capacity_ + cell] =
          static_cast<S>(values[c]);
    }
  }
  frozen_ = false;
}

template <typename S>
void GrnBatchT<S>::SetChemical(std::span<const double> values) {
  assert(values.size() >= static_cast<size_t>(cells_));
  for (int v :
       network_->input_nodes(static_cast<int>(InputChannel::kChemical))) {
    S* row = &levels_[static_cast<size_t>(v) * capacity_];
    for (int c = 0; c < cells_; ++c) row[c] = static_cast<S>(values[c]);
  }
}

template <typename S>
void GrnBatchT<S>::SetOwnSignals() {
  const std::vector<int>& nodes = network_->morphogen_nodes();
  for (size_t m = 0; m < nodes.size(); ++m) {
    const S* level = level_row(nodes[m]);
    S* signal = signal_row(static_cast<int>(m));
    for (int c = 0; c < cells_; ++c) {
      signal[c] = level[c] > S{1} ? S{1} : level[c];
    }
  }
}

template <typename S>
const S* GrnBatchT<S>::SourceRow(int active) const {
  const Network& net = *network_;
  const Source& source = net.sources()[active_sources_[active]];
  return source.kind == SourceKind::kMorphogen
             ? &signals_[static_cast<size_t>(
                             net.nodes()[source.node].morphogen) *
                         capacity_]
             : &levels_[static_cast<size_t>(source.node) * capacity_];
}

template <typename S>
void GrnBatchT<S>::AccumulateSources(int first, int last) {
  // `first` and `last` index active_sources_.
  const int* target = row_target_.data();
  const S* weight = row_weight_.data();
  const int n = cells_;
  for (int a = first; a < last; ++a) {
    const S* value = SourceRow(a);
    for (int k = row_begin_[a]; k < row_begin_[a + 1]; ++k) {
      S* acc = &activation_[static_cast<size_t>(target[k]) * capacity_];
      const S w = weight[k];
      for (int c = 0; c < n; ++c) acc[c] += w * value[c];
    }
  }
}

template <typename S>
void GrnBatchT<S>::FreezeInputs() {
  std::fill(activation_.begin(), activation_.end(), S{0});
  AccumulateSources(0, active_static_sources_);
  input_partial_ = activation_;
  frozen_ = true;
}

template <typename S>
void GrnBatchT<S>::Step() {
  const Network& net = *network_;
  const int sources = static_cast<int>(active_sources_.size());
  int first = 0;
  if (frozen_) {
    std::copy(input_partial_.begin(), input_partial_.end(),
              activation_.begin());
    first = active_static_sources_;
  } else {
    std::fill(activation_.begin(), activation_.end(), S{0});
  }
  // The rows the kernel reads and writes; all activations are computed
  // before any level changes: synchronous.
  source_row_.clear();
  for (int a = first; a < sources; ++a) source_row_.push_back(SourceRow(a));
  target_level_.clear();
  for (int t : active_targets_) {
    target_level_.push_back(
        &levels_[static_cast<size_t>(net.targets()[t]) * capacity_]);
  }
  kernels::GrnStepArgs<S> args;
  args.cells = cells_;
  args.capacity = capacity_;
  args.sources = sources - first;
  args.source = source_row_.data();
  args.row_begin = &row_begin_[first];
  args.row_target = row_target_.data();
  args.row_weight = row_weight_.data();
  args.activation = activation_.data();
  args.targets = static_cast<int>(active_targets_.size());
  args.target_activation = active_targets_.data();
  args.level = target_level_.data();
  args.dt = dt_;
  kernels::GrnStep(args);
}

template <typename S>
double GrnBatchT<S>::Output(int cell, OutputChannel channel) const {
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

template <typename S>
void GrnBatchT<S>::OutputAll(OutputChannel channel, double* out) const {
  // Same order and rule as Output(): the maximum from 0, NaN kept.
  for (int c = 0; c < cells_; ++c) out[c] = 0.0;
  for (int v : network_->output_nodes(static_cast<int>(channel))) {
    const S* row = level_row(v);
    for (int c = 0; c < cells_; ++c) {
      const double l = row[c];
      if (std::isnan(out[c])) continue;  // The first NaN stays.
      if (std::isnan(l) || l > out[c]) out[c] = l;
    }
  }
}

template <typename S>
void GrnBatchT<S>::ResetOutput(int cell, OutputChannel channel) {
  for (int v : network_->output_nodes(static_cast<int>(channel))) {
    levels_[static_cast<size_t>(v) * capacity_ + cell] = S{0};
  }
}

template class GrnBatchT<double>;
template class GrnBatchT<float>;

}  // namespace animat
