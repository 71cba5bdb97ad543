// The network dynamics of every cell of an embryo, advanced together
// (docs/model.md §3).
//
// State is stored node-major with the cells of one node contiguous, so one
// weight updates all cells in a vector loop (common/kernels, on the
// instruction-set path in use); results do not depend on the path. The scalar
// type S (double or float) is the arithmetic of levels, weights, signals and
// tanh (GrnParams::precision); values cross the interface as double. The batch
// keeps a reference to its Network, which must outlive it. Not thread-safe; one
// batch per evaluation.
#ifndef ANIMAT_COMMON_GRN_GRN_BATCH_H_
#define ANIMAT_COMMON_GRN_GRN_BATCH_H_

#include <array>
#include <span>
#include <vector>

#include "common/genome/genome.h"
#include "common/grn/grn_params.h"
#include "common/grn/network.h"

namespace animat {

template <typename S>
class GrnBatchT {
 public:
  using Scalar = S;

  // Holds up to `capacity` cells (> 0).
  GrnBatchT(const Network& network, const GrnParams& params, int capacity);

  int cells() const { return cells_; }
  int capacity() const { return capacity_; }
  const Network& network() const { return *network_; }

  // Adds a cell with every level, input and signal 0; returns its index.
  // Precondition: cells() < capacity().
  int AddCell();
  // Adds a copy of `mother` (levels, inputs, signals); returns its index.
  int CopyCell(int mother);

  // Sets the cell's input channel values (MATERNAL_0..2, UNIFORM,
  // CHEMICAL). Input nodes hold the value of their channel as their level.
  void SetInputs(int cell, const std::array<double, kInputChannels>& values);
  // Sets the CHEMICAL channel of every cell: values[c] for cell c <
  // cells() (values.size() >= cells()). Unlike SetInputs it keeps
  // FreezeInputs' precomputation, which leaves CHEMICAL out, so the
  // chemical can change every motion step (docs/model.md §10.2).
  void SetChemical(std::span<const double> values);
  // Morphogen signals M, one row of capacity() per morphogen (cells
  // contiguous): set them before Step().
  S* signal_row(int morphogen) {
    return &signals_[static_cast<size_t>(morphogen) * capacity_];
  }
  const S* signal_row(int morphogen) const {
    return &signals_[static_cast<size_t>(morphogen) * capacity_];
  }
  // Sets every cell's signals to its own levels, min(1, L) (a cell alone:
  // K(0) = 1, no delay).
  void SetOwnSignals();

  // Precomputes the contribution of the input nodes other than CHEMICAL to
  // every activation; until the next AddCell, CopyCell or SetInputs, Step()
  // reuses it (CHEMICAL nodes are read at every Step). Results are
  // bit-identical with and without freezing.
  void FreezeInputs();

  // From now on Step() updates only the nodes marked in `needed` (indexed
  // by node; see Network::NodesReaching): the others keep their levels. A
  // needed node's inputs all come from needed nodes, so its trajectory is
  // bit-identical to an unrestricted run. An empty vector lifts the
  // restriction.
  void Restrict(const std::vector<bool>& needed);

  // One synchronous update of every cell:
  //   L <- clamp(L + (tanh(A / 2) - L) * dt, 0, 1).
  // A NaN level stays NaN (never clamped to a number).
  void Step();

  double level(int cell, int node) const {
    return levels_[static_cast<size_t>(node) * capacity_ + cell];
  }
  // Levels of one node for all cells (cells contiguous).
  const S* level_row(int node) const {
    return &levels_[static_cast<size_t>(node) * capacity_];
  }
  // The channel's value: the maximum level of its output nodes, 0 if none.
  double Output(int cell, OutputChannel channel) const;
  // The channel's value for every cell: out[c] = Output(c, channel), for
  // c < cells().
  void OutputAll(OutputChannel channel, double* out) const;
  // Sets every output node of the channel to 0 in this cell.
  void ResetOutput(int cell, OutputChannel channel);

 private:
  // activation += the weighted rows of active sources [first, last).
  void AccumulateSources(int first, int last);
  // The values of active source `active` (a level or signal row).
  const S* SourceRow(int active) const;

  const Network* network_;
  S dt_;
  int capacity_;
  int cells_ = 0;
  bool frozen_ = false;
  std::vector<S> levels_;         // node-major, capacity per node
  std::vector<S> signals_;        // morphogen-major
  std::vector<S> activation_;     // target-major
  std::vector<S> input_partial_;  // target-major, when frozen
  // What Step() computes: indices into network().targets(), and the
  // network's sparse rows restricted to active sources and targets, with
  // the weights in S (row r of source active_sources_[r] spans
  // [row_begin_[r], row_begin_[r + 1]) of row_target_ and row_weight_).
  std::vector<int> active_targets_;
  std::vector<int> active_sources_;
  // Leading input sources among them that are not CHEMICAL (frozen).
  int active_static_sources_ = 0;
  std::vector<int> row_begin_;
  std::vector<int> row_target_;
  std::vector<S> row_weight_;
  // Step()'s scratch: the rows its kernel reads and writes.
  std::vector<const S*> source_row_;
  std::vector<S*> target_level_;
};

using GrnBatch = GrnBatchT<double>;
using GrnBatchF = GrnBatchT<float>;

extern template class GrnBatchT<double>;
extern template class GrnBatchT<float>;

}  // namespace animat

#endif  // ANIMAT_COMMON_GRN_GRN_BATCH_H_
