// Maternal and endogenous morphogens (docs/model.md §5).
//
// MorphogenField keeps, for every cell, the recent history of its
// morphogen-making nodes' levels, and turns it into the signal M each cell
// sees through the distance kernel K(d) = exp(-d / kernel_length) and the
// delay tau(d) = min(max_delay, floor(d / delay_length + 0.5)) steps. The
// scalar S (double or float) is that of the network batch it serves;
// distances, kernels and delays are computed in double. Not thread-safe;
// one field per evaluation.
#ifndef ANIMAT_COMMON_DEVELOPMENT_SIGNALS_H_
#define ANIMAT_COMMON_DEVELOPMENT_SIGNALS_H_

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/base/vec2.h"
#include "common/development/development_params.h"
#include "common/genome/genome.h"
#include "common/grn/grn_batch.h"

namespace animat {

// The three maternal sources: distance maternal_distance from the origin at
// angles 90 + 120 k degrees.
std::array<Vec2, 3> MaternalSources(const SignalParams& params);

// Input channel values at a position: exp(-|p - s_k| / maternal_length)
// for the three maternal channels, then UNIFORM = 1, then CHEMICAL = 0
// (only guidance's sensing sets it, during motion: model §10.2).
std::array<double, kInputChannels> InputValuesAt(
    Vec2 p, const std::array<Vec2, 3>& sources, const SignalParams& params);

template <typename S>
class MorphogenFieldT {
 public:
  // History length in steps (a power of two above the longest delay).
  static constexpr int kHistory = 128;

  // `morphogens`: the network's morphogen-making nodes; `capacity`: most
  // cells.
  MorphogenFieldT(int morphogens, int capacity, const SignalParams& params);

  int cells() const { return cells_; }
  // Morphogens computed (all of the network's until Restrict).
  int morphogens() const { return morphogens_; }

  // Adds a cell whose history is all 0 / a copy of the mother's.
  void AddCell();
  void CopyCell(int mother);

  // Recomputes kernels and delays from the cells' positions (one per
  // cell, in cell order). K(0) = 1 and delay 0 for a cell and itself.
  void SetGeometry(std::span<const Vec2> positions);

  // Stores every cell's morphogen-node levels in `grn` as its values
  // entering step `step`.
  void Record(int step, const GrnBatchT<S>& grn);

  // Writes M_j(i) = min(1, sum over cells k, in index order, of
  // K(d_ik) * L_j(k, step - tau(d_ik))) into grn's signal rows; history
  // before step 0 reads 0.
  void Apply(int step, GrnBatchT<S>* grn) const;

  // From now on only the listed morphogens (indices into the network's
  // morphogen_nodes(), increasing) are recorded and applied; the others'
  // signals keep their last values. The kept histories carry over.
  void Restrict(const std::vector<int>& keep);

  // From now on `morphogen` (an index into the network's morphogen_nodes(),
  // in [0, morphogen_count())) is neither recorded nor applied, and its signal
  // in `grn` reads 0 in every cell: a knock-out (docs/analysis.md), not part of
  // the model. The other morphogens' signals keep every bit.
  void Silence(int morphogen, GrnBatchT<S>* grn);

  // The morphogens computed, as indices into the network's
  // morphogen_nodes(), increasing.
  const std::vector<int>& kept() const { return keep_; }

  double kernel(int i, int k) const { return kernel_[i * capacity_ + k]; }
  int delay(int i, int k) const { return delay_[i * capacity_ + k]; }

 private:
  // Each cell's ring holds every value twice, at slot s and s + kHistory
  // (s = step mod kHistory), so that the values entering step - d, for
  // any delay d in [0, kHistory), sit at slot (step mod kHistory) +
  // kHistory - d without a wrap: one offset per cell pair, fixed with the
  // geometry, and one per step.
  static constexpr int kRing = 2 * kHistory;

  // Slot `s` in [0, kRing) of the cell's ring. Slots are the outer index,
  // so one step's values of all cells lie together. Precondition:
  // morphogens_ > 0.
  S* ring_slot(int s, int cell) {
    return &history_[(static_cast<size_t>(s) * capacity_ + cell) * stride_];
  }
  // The cell's values entering `step` (any integer), first copy.
  S* slot(int step, int cell) { return ring_slot(step & (kHistory - 1), cell); }

  // Values of one slot (all cells): the distance between a slot and the
  // next, and between a value's two copies (kHistory slots apart).
  size_t slot_size() const { return static_cast<size_t>(capacity_) * stride_; }
  // source_offset_ of a pair with this delay (less its source's k * stride_).
  uint32_t OffsetOf(int delay) const {
    return static_cast<uint32_t>((kHistory - delay) * slot_size());
  }
  // source_offset_ of every pair, from delay_ and the morphogen count.
  void UpdateOffsets();

  // Values per cell and slot: morphogens rounded up to a multiple of 4,
  // so that the sums run in whole vectors; the padding stays 0.
  static int Stride(int morphogens) { return (morphogens + 3) / 4 * 4; }

  int morphogens_;
  int stride_;
  int capacity_;
  int cells_ = 0;
  SignalParams params_;
  std::vector<int> keep_;       // Network morphogen index of each kept one.
  std::vector<S> kernel_;       // capacity x capacity
  std::vector<uint8_t> delay_;  // capacity x capacity
  std::vector<S> history_;      // [kRing slots][capacity][stride_]
  // Where cell i finds cell k's values (i, k < capacity; symmetric): cell
  // k's values of ring slot kHistory - delay(i, k) are at history_ index
  // source_offset_[i][k] + k * stride_, and those entering step s
  // (s mod kHistory) * capacity * stride_ further on.
  std::vector<uint32_t> source_offset_;
  mutable std::vector<S> sum_;  // scratch, [cell][stride_]
  // Scratch for SetGeometry, one entry per pair i < k.
  std::vector<double> pair_distance_, pair_kernel_, pair_delay_;
};

using MorphogenField = MorphogenFieldT<double>;

extern template class MorphogenFieldT<double>;
extern template class MorphogenFieldT<float>;

}  // namespace animat

#endif  // ANIMAT_COMMON_DEVELOPMENT_SIGNALS_H_
