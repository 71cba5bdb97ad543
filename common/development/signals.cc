#include "common/development/signals.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "common/base/fast_math.h"

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
  std::array<double, kInputChannels> values;
  for (int k = 0; k < 3; ++k) {
    values[k] = Exp(-Length(p - sources[k]) / params.maternal_length);
  }
  values[static_cast<int>(InputChannel::kUniform)] = 1.0;
  return values;
}

MorphogenField::MorphogenField(int morphogens, int capacity,
                               const SignalParams& params)
    : morphogens_(morphogens), capacity_(capacity), params_(params) {
  const size_t cap = static_cast<size_t>(capacity);
  kernel_.assign(cap * cap, 0.0);
  delay_.assign(cap * cap, 0);
  history_.assign(kHistory * cap * morphogens, 0.0);
  sum_.assign(morphogens, 0.0);
}

void MorphogenField::AddCell() {
  assert(cells_ < capacity_);
  const int cell = cells_++;
  for (int s = 0; s < kHistory; ++s) {
    std::fill_n(slot(s, cell), morphogens_, 0.0);
  }
}

void MorphogenField::CopyCell(int mother) {
  assert(cells_ < capacity_ && mother >= 0 && mother < cells_);
  const int cell = cells_++;
  for (int s = 0; s < kHistory; ++s) {
    std::copy_n(slot(s, mother), morphogens_, slot(s, cell));
  }
}

void MorphogenField::SetGeometry(std::span<const Vec2> positions) {
  assert(static_cast<int>(positions.size()) == cells_);
  const int n = cells_;
  for (int i = 0; i < n; ++i) {
    kernel_[i * capacity_ + i] = 1.0;
    delay_[i * capacity_ + i] = 0;
    for (int k = i + 1; k < n; ++k) {
      const double d = Length(positions[k] - positions[i]);
      const double kernel = Exp(-d / params_.kernel_length);
      const double steps = std::floor(d / params_.delay_length + 0.5);
      const int delay = steps < params_.max_delay
                            ? static_cast<int>(steps)
                            : params_.max_delay;
      kernel_[i * capacity_ + k] = kernel_[k * capacity_ + i] = kernel;
      delay_[i * capacity_ + k] = delay_[k * capacity_ + i] =
          static_cast<uint8_t>(delay);
    }
  }
}

void MorphogenField::Record(int step, const GrnBatch& grn) {
  const std::vector<int>& nodes = grn.network().morphogen_nodes();
  assert(static_cast<int>(nodes.size()) == morphogens_);
  for (int m = 0; m < morphogens_; ++m) {
    const double* level = grn.level_row(nodes[m]);
    for (int cell = 0; cell < cells_; ++cell) {
      slot(step, cell)[m] = level[cell];
    }
  }
}

void MorphogenField::Apply(int step, GrnBatch* grn) const {
  const int n = cells_;
  const int m_count = morphogens_;
  double* sum = sum_.data();
  for (int i = 0; i < n; ++i) {
    std::fill_n(sum, m_count, 0.0);
    for (int k = 0; k < n; ++k) {
      const double w = kernel_[i * capacity_ + k];
      const size_t s = static_cast<size_t>(step - delay_[i * capacity_ + k]) &
                       (kHistory - 1);
      const double* h = &history_[(s * capacity_ + k) * m_count];
      for (int m = 0; m < m_count; ++m) sum[m] += w * h[m];
    }
    for (int m = 0; m < m_count; ++m) {
      // NaN passes through (never clamped to a number).
      grn->signal_row(m)[i] = sum[m] > 1.0 ? 1.0 : sum[m];
    }
  }
}

}  // namespace animat
