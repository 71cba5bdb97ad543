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
    : morphogens_(morphogens), capacity_(capacity), params_(params) {
  const size_t cap = static_cast<size_t>(capacity);
  kernel_.assign(cap * cap, 0.0);
  delay_.assign(cap * cap, 0);
  history_.assign(kHistory * cap * morphogens, 0.0);
  sum_.assign(cap * morphogens, 0.0);
  for (int m = 0; m < morphogens; ++m) keep_.push_back(m);
}

template <typename S>
void MorphogenFieldT<S>::Restrict(const std::vector<int>& keep) {
  const int kept = static_cast<int>(keep.size());
  std::vector<S> history(kHistory * static_cast<size_t>(capacity_) * kept);
  for (int cell = 0; kept > 0 && cell < cells_; ++cell) {
    for (int s = 0; s < kHistory; ++s) {
      const S* from = slot(s, cell);
      S* to = &history[(static_cast<size_t>(cell) * kHistory + s) * kept];
      // keep[j] indexes the current compacted layout through keep_.
      for (int j = 0; j < kept; ++j) {
        const auto it = std::find(keep_.begin(), keep_.end(), keep[j]);
        to[j] = from[it - keep_.begin()];
      }
    }
  }
  history_ = std::move(history);
  keep_ = keep;
  morphogens_ = kept;
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
  for (int s = 0; s < kHistory; ++s) {
    std::fill_n(slot(s, cell), morphogens_, S{0});
  }
}

template <typename S>
void MorphogenFieldT<S>::CopyCell(int mother) {
  assert(cells_ < capacity_ && mother >= 0 && mother < cells_);
  const int cell = cells_++;
  if (morphogens_ == 0) return;  // No history to copy.
  for (int s = 0; s < kHistory; ++s) {
    std::copy_n(slot(s, mother), morphogens_, slot(s, cell));
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
    for (int k = i + 1; k < n; ++k, ++p) {
      kernel_[i * capacity_ + k] = kernel_[k * capacity_ + i] =
          static_cast<S>(pair_kernel_[p]);
      delay_[i * capacity_ + k] = delay_[k * capacity_ + i] =
          static_cast<uint8_t>(pair_delay_[p]);
    }
  }
}

template <typename S>
void MorphogenFieldT<S>::Record(int step, const GrnBatchT<S>& grn) {
  const std::vector<int>& nodes = grn.network().morphogen_nodes();
  for (int m = 0; m < morphogens_; ++m) {
    const S* level = grn.level_row(nodes[keep_[m]]);
    for (int cell = 0; cell < cells_; ++cell) {
      slot(step, cell)[m] = level[cell];
    }
  }
}

namespace {

// M_j(i) for every cell i: sums over source cells k in increasing order.
// kM > 0 fixes the morphogen count at compile time (sums in registers,
// vectorised); kM == 0 handles any count.
template <int kM, typename S>
void ApplyKernel(int step, int n, int m_count, int capacity, const S* kernel,
                 const uint8_t* delay, const S* history, S* out) {
  constexpr int kHistory = MorphogenFieldT<S>::kHistory;
  if constexpr (kM > 0) m_count = kM;
  // Offset in a cell's ring of the values entering step - d, for every
  // delay d: one table per step instead of index arithmetic per pair.
  uint32_t offset[kHistory];
  for (int d = 0; d < kHistory; ++d) {
    offset[d] = static_cast<uint32_t>(((step - d) & (kHistory - 1)) * m_count);
  }
  const size_t ring = static_cast<size_t>(kHistory) * m_count;
  int i = 0;
  if constexpr (kM > 0) {
    // Four receiving cells at once: four independent chains of additions
    // (the adds' latency, not their number, bounds one chain), each sum
    // still taken over k in increasing order.
    constexpr int kBlock = 4;
    for (; i + kBlock <= n; i += kBlock) {
      S sum[kBlock][kM] = {};
      const S* kernel_row[kBlock];
      const uint8_t* delay_row[kBlock];
      for (int r = 0; r < kBlock; ++r) {
        kernel_row[r] = &kernel[static_cast<size_t>(i + r) * capacity];
        delay_row[r] = &delay[static_cast<size_t>(i + r) * capacity];
      }
      const S* ring_k = history;
      for (int k = 0; k < n; ++k, ring_k += ring) {
        for (int r = 0; r < kBlock; ++r) {
          const S w = kernel_row[r][k];
          const S* h = ring_k + offset[delay_row[r][k]];
          for (int m = 0; m < kM; ++m) sum[r][m] += w * h[m];
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
    const uint8_t* delay_row = &delay[static_cast<size_t>(i) * capacity];
    const S* ring_k = history;
    for (int k = 0; k < n; ++k, ring_k += ring) {
      const S w = kernel_row[k];
      const S* h = ring_k + offset[delay_row[k]];
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
  S* sum = sum_.data();
  const S* kernel = kernel_.data();
  const uint8_t* delay = delay_.data();
  const S* history = history_.data();
  switch (m_count) {
#define ANIMAT_APPLY_CASE(M)                                               \
  case M:                                                                  \
    ApplyKernel<M, S>(step, n, m_count, capacity_, kernel, delay, history, \
                      sum);                                                \
    break;
    ANIMAT_APPLY_CASE(1)
    ANIMAT_APPLY_CASE(2)
    ANIMAT_APPLY_CASE(3)
    ANIMAT_APPLY_CASE(4)
    ANIMAT_APPLY_CASE(5)
    ANIMAT_APPLY_CASE(6)
    ANIMAT_APPLY_CASE(7)
    ANIMAT_APPLY_CASE(8)
#undef ANIMAT_APPLY_CASE
    default:
      ApplyKernel<0>(step, n, m_count, capacity_, kernel, delay, history, sum);
      break;
  }
  for (int m = 0; m < m_count; ++m) {
    S* signal = grn->signal_row(keep_[m]);
    for (int i = 0; i < n; ++i) {
      // NaN passes through (never clamped to a number).
      const S v = sum[static_cast<size_t>(i) * m_count + m];
      signal[i] = v > S{1} ? S{1} : v;
    }
  }
}

template class MorphogenFieldT<double>;
template class MorphogenFieldT<float>;

}  // namespace animat
