#include "common/development/signals.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "common/base/fast_math.h"
#include "common/kernels/kernels.h"

namespace animat {

std::array<Vec2, 3> MaternalSources(const SignalParams& params) {
  std::array<Vec2, 3> sources;
  constexpr double kPi = 3.14159265358979323846;
  for (int k = 0; k < 3; ++k) {
    const double angle = kPi / 2.0 + 2.0 * kPi / 3.0 * k;
    double s, c;
    SinCos(angle, &s, &c);
    sources[k] = {params.maternal_distance * c, params.maternal_distance * s};
  }
  return sources;
}

std::array<double, kInputChannels> InputValuesAt(
    Vec2 p, const std::array<Vec2, 3>& sources, const SignalParams& params) {
  std::array<double, kInputChannels> values{};  // CHEMICAL: 0.
  for (int k = 0; k < 3; ++k) {
    values[k] = Exp(-Length(p - sources[k]) / params.maternal_length);
  }
  values[static_cast<int>(InputChannel::kUniform)] = 1.0;
  return values;
}

template <typename S>
MorphogenFieldT<S>::MorphogenFieldT(int morphogens, int capacity,
                                    const SignalParams& params)
    : morphogens_(morphogens),
      stride_(Stride(morphogens)),
      capacity_(capacity),
      params_(params) {
  const size_t cap = static_cast<size_t>(capacity);
  kernel_.assign(cap * cap, 0.0);
  delay_.assign(cap * cap, 0);
  source_offset_.assign(cap * cap, 0);
  history_.assign(kRing * cap * stride_, 0.0);
  sum_.assign(cap * stride_, 0.0);
  for (int m = 0; m < morphogens; ++m) keep_.push_back(m);
  UpdateOffsets();
}

template <typename S>
void MorphogenFieldT<S>::UpdateOffsets() {
  for (size_t at = 0; at < source_offset_.size(); ++at) {
    source_offset_[at] = OffsetOf(delay_[at]);
  }
}

template <typename S>
void MorphogenFieldT<S>::Restrict(const std::vector<int>& keep) {
  const int kept = static_cast<int>(keep.size());
  const int stride = Stride(kept);
  // keep[j] indexes the current compacted layout through keep_.
  std::vector<int> from_index(kept);
  for (int j = 0; j < kept; ++j) {
    from_index[j] = static_cast<int>(
        std::find(keep_.begin(), keep_.end(), keep[j]) - keep_.begin());
  }
  std::vector<S> history(kRing * static_cast<size_t>(capacity_) * stride);
  for (int cell = 0; kept > 0 && cell < cells_; ++cell) {
    for (int s = 0; s < kRing; ++s) {
      const S* from = ring_slot(s, cell);
      S* to = &history[(static_cast<size_t>(s) * capacity_ + cell) * stride];
      for (int j = 0; j < kept; ++j) to[j] = from[from_index[j]];
    }
  }
  history_ = std::move(history);
  keep_ = keep;
  morphogens_ = kept;
  stride_ = stride;
  sum_.assign(static_cast<size_t>(capacity_) * stride_, 0.0);
  UpdateOffsets();
}

template <typename S>
void MorphogenFieldT<S>::Silence(int morphogen, GrnBatchT<S>* grn) {
  std::vector<int> keep;
  for (int m : keep_) {
    if (m != morphogen) keep.push_back(m);
  }
  if (keep.size() != keep_.size()) Restrict(keep);
  std::fill_n(grn->signal_row(morphogen), grn->capacity(), S{0});
}

template <typename S>
void MorphogenFieldT<S>::AddCell() {
  assert(cells_ < capacity_);
  const int cell = cells_++;
  if (morphogens_ == 0) return;  // No history to keep.
  for (int s = 0; s < kRing; ++s) {
    std::fill_n(ring_slot(s, cell), stride_, S{0});
  }
}

template <typename S>
void MorphogenFieldT<S>::CopyCell(int mother) {
  assert(cells_ < capacity_ && mother >= 0 && mother < cells_);
  const int cell = cells_++;
  if (morphogens_ == 0) return;  // No history to copy.
  for (int s = 0; s < kRing; ++s) {
    std::copy_n(ring_slot(s, mother), stride_, ring_slot(s, cell));
  }
}

template <typename S>
void MorphogenFieldT<S>::SetGeometry(std::span<const Vec2> positions) {
  assert(static_cast<int>(positions.size()) == cells_);
  const int n = cells_;
  // Distances of the pairs i < k, in order, then kernels and delays in
  // contiguous (vectorised) passes, then both halves of the matrices.
  pair_distance_.clear();
  for (int i = 0; i < n; ++i) {
    for (int k = i + 1; k < n; ++k) {
      pair_distance_.push_back(Length(positions[k] - positions[i]));
    }
  }
  const size_t pairs = pair_distance_.size();
  pair_kernel_.resize(pairs);
  pair_delay_.resize(pairs);
  kernels::PairKernelArgs args;
  args.pairs = pairs;
  args.distance = pair_distance_.data();
  args.kernel_length = params_.kernel_length;
  args.delay_length = params_.delay_length;
  args.max_delay = params_.max_delay;
  args.kernel = pair_kernel_.data();
  args.delay = pair_delay_.data();
  kernels::PairKernels(args);
  size_t p = 0;
  for (int i = 0; i < n; ++i) {
    kernel_[i * capacity_ + i] = S{1};
    delay_[i * capacity_ + i] = 0;
    source_offset_[i * capacity_ + i] = OffsetOf(0);
    for (int k = i + 1; k < n; ++k, ++p) {
      kernel_[i * capacity_ + k] = kernel_[k * capacity_ + i] =
          static_cast<S>(pair_kernel_[p]);
      const uint8_t delay = static_cast<uint8_t>(pair_delay_[p]);
      delay_[i * capacity_ + k] = delay_[k * capacity_ + i] = delay;
      source_offset_[i * capacity_ + k] = source_offset_[k * capacity_ + i] =
          OffsetOf(delay);
    }
  }
}

template <typename S>
void MorphogenFieldT<S>::Record(int step, const GrnBatchT<S>& grn) {
  const std::vector<int>& nodes = grn.network().morphogen_nodes();
  for (int m = 0; m < morphogens_; ++m) {
    const S* level = grn.level_row(nodes[keep_[m]]);
    for (int cell = 0; cell < cells_; ++cell) {
      S* at = slot(step, cell);
      at[m] = level[cell];
      at[kHistory * slot_size() + m] = level[cell];
    }
  }
}

namespace {

// M_j(i) for every cell i: sums over source cells k in increasing order.
// kM > 0 fixes the morphogen count at compile time (sums in registers,
// vectorised); kM == 0 handles any count. `now` is the history's first
// copy of the slot of `step`, whose cell k's values are at now + k * m;
// cell i reads cell k's at now + k * m + offset[i][k]. Kernels and offsets
// are symmetric, so row k holds what cells i, i + 1, ... read from k, side
// by side.
template <int kM, typename S>
void ApplyKernel(int n, int m_count, int capacity, const S* kernel,
                 const uint32_t* offset, const S* now, S* out) {
  if constexpr (kM > 0) m_count = kM;
  int i = 0;
  if constexpr (kM > 0) {
    // Four receiving cells at once: four independent chains of additions
    // (the adds' latency, not their number, bounds one chain), each sum
    // still taken over k in increasing order.
    constexpr int kBlock = 4;
    for (; i + kBlock <= n; i += kBlock) {
      S sum[kBlock][kM] = {};
      const S* now_k = now;
      for (int k = 0; k < n; ++k, now_k += kM) {
        const size_t row = static_cast<size_t>(k) * capacity + i;
        const S* w = &kernel[row];
        const uint32_t* o = &offset[row];
        for (int r = 0; r < kBlock; ++r) {
          const S* h = now_k + o[r];
          for (int m = 0; m < kM; ++m) sum[r][m] += w[r] * h[m];
        }
      }
      for (int r = 0; r < kBlock; ++r) {
        for (int m = 0; m < kM; ++m) {
          out[static_cast<size_t>(i + r) * kM + m] = sum[r][m];
        }
      }
    }
  }
  for (; i < n; ++i) {
    S sum[kM > 0 ? kM : 1] = {};
    S* acc = kM > 0 ? sum : &out[static_cast<size_t>(i) * m_count];
    if constexpr (kM == 0) std::fill_n(acc, m_count, S{0});
    const S* kernel_row = &kernel[static_cast<size_t>(i) * capacity];
    const uint32_t* offset_row = &offset[static_cast<size_t>(i) * capacity];
    const S* now_k = now;
    for (int k = 0; k < n; ++k, now_k += m_count) {
      const S w = kernel_row[k];
      const S* h = now_k + offset_row[k];
      for (int m = 0; m < m_count; ++m) acc[m] += w * h[m];
    }
    if constexpr (kM > 0) {
      for (int m = 0; m < kM; ++m) {
        out[static_cast<size_t>(i) * kM + m] = sum[m];
      }
    }
  }
}

}  // namespace

template <typename S>
void MorphogenFieldT<S>::Apply(int step, GrnBatchT<S>* grn) const {
  const int n = cells_;
  const int m_count = morphogens_;
  const int stride = stride_;
  S* sum = sum_.data();
  const S* kernel = kernel_.data();
  const uint32_t* offset = source_offset_.data();
  const S* now = history_.data() +
                 static_cast<size_t>(step & (kHistory - 1)) * slot_size();
  // The padding lanes (stride > m_count) sum zeros and are not read.
  switch (stride) {
#define ANIMAT_APPLY_CASE(M)                                           \
  case M:                                                              \
    ApplyKernel<M, S>(n, stride, capacity_, kernel, offset, now, sum); \
    break;
    ANIMAT_APPLY_CASE(4)
    ANIMAT_APPLY_CASE(8)
#undef ANIMAT_APPLY_CASE
    default:
      ApplyKernel<0>(n, stride, capacity_, kernel, offset, now, sum);
      break;
  }
  for (int m = 0; m < m_count; ++m) {
    S* signal = grn->signal_row(keep_[m]);
    for (int i = 0; i < n; ++i) {
      // NaN passes through (never clamped to a number).
      const S v = sum[static_cast<size_t>(i) * stride + m];
      signal[i] = v > S{1} ? S{1} : v;
    }
  }
}

template class MorphogenFieldT<double>;
template class MorphogenFieldT<float>;

}  // namespace animat
