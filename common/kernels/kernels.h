// The model's hot loops over cells, compiled once per instruction-set path
// (isa.h) and run on the path in use. Every path gives the same bits,
// except the sign and payload of a NaN: which NaN x + y or x * y returns
// when both are NaN depends on the order of the operands, and compilers
// swap them freely. A NaN anywhere is a numerical failure of the
// evaluation (docs/model.md), so no NaN's bits reach a result.
//
// The arguments are plain arrays owned by the caller; a kernel keeps no
// state, allocates nothing and never fails. Thread-safe for distinct
// outputs.
#ifndef ANIMAT_COMMON_KERNELS_KERNELS_H_
#define ANIMAT_COMMON_KERNELS_KERNELS_H_

#include <cstddef>

#include "common/base/vec2.h"
#include "common/kernels/isa.h"

namespace animat::kernels {

// One synchronous network update of `cells` cells (docs/model.md §3):
// first, for each source row r in order and each of its weights k in
// order, activation[row_target[k]][c] += row_weight[k] * source[r][c];
// then, for each target t, with a = activation[target_activation[t]][c]
// and L = level[t][c]:
//   L <- clamp(L + (tanh(a * 0.5) - L) * dt, 0, 1)
// (TanhF or Tanh of common/base/fast_math.h; a NaN level stays NaN).
// Activation rows are `capacity` apart and hold the starting sums on
// entry. No output row may overlap an input row.
template <typename S>
struct GrnStepArgs {
  int cells = 0;
  int capacity = 0;
  int sources = 0;
  const S* const* source = nullptr;  // [sources] rows of cells values.
  const int* row_begin = nullptr;    // [sources + 1], into the two below.
  const int* row_target = nullptr;   // Activation row of each weight.
  const S* row_weight = nullptr;
  S* activation = nullptr;
  int targets = 0;
  const int* target_activation = nullptr;  // [targets]
  S* const* level = nullptr;               // [targets] rows of cells values.
  S dt = 0;
};
void GrnStep(const GrnStepArgs<float>& args);
void GrnStep(const GrnStepArgs<double>& args);
// The same on a given path (for tests and benchmarks). Precondition:
// IsaSupported(isa).
void GrnStep(Isa isa, const GrnStepArgs<float>& args);
void GrnStep(Isa isa, const GrnStepArgs<double>& args);

// The signals' kernel and delay of each cell pair from its distance d
// (docs/model.md §5): kernel[p] = Exp(-d / kernel_length) and
// delay[p] = min(max_delay, floor(d / delay_length + 0.5)).
struct PairKernelArgs {
  size_t pairs = 0;
  const double* distance = nullptr;
  double kernel_length = 1.0;
  double delay_length = 1.0;
  double max_delay = 0.0;
  double* kernel = nullptr;
  double* delay = nullptr;
};
void PairKernels(const PairKernelArgs& args);
void PairKernels(Isa isa, const PairKernelArgs& args);

// One row of a pair list's rebuild (common/geometry/contact_pairs.h): the
// cells j in [first, last), in increasing order, that lie within reach of
// cell i at (xi, yi). With dx = x[j] - xi, dy = y[j] - yi and
// d2 = dx * dx + dy * dy, j is kept when !(d2 > bound2[j - first]) (so a
// NaN distance is kept) and bound2[j - first] >= 0 (a negative bound
// excludes the pair whatever its distance). Writes the kept j to out and
// returns their count; `out` must have room for last - first + 8 values
// (the vector paths store whole vectors past the count).
struct NearPairsArgs {
  int first = 0;
  int last = 0;
  const double* x = nullptr;  // [last] cell coordinates.
  const double* y = nullptr;
  double xi = 0.0;
  double yi = 0.0;
  const double* bound2 = nullptr;  // [last - first]
  int* out = nullptr;
};
int NearPairs(Isa isa, const NearPairsArgs& args);

// Whether a pair list built at `built` still serves at `position`
// (common/geometry/contact_pairs.h): for every one of the `points` points,
// both coordinates of magnitude below `bound`, and
// dx * dx + dy * dy <= limit2 with (dx, dy) = position - built. False when
// any coordinate is NaN.
struct WithinMoveArgs {
  size_t points = 0;
  const Vec2* position = nullptr;
  const Vec2* built = nullptr;
  double bound = 0.0;
  double limit2 = 0.0;
};
bool WithinMove(Isa isa, const WithinMoveArgs& args);

// Velocity Verlet's predictor over `points` points
// (common/physics/soft_body.cc), with Vec2's operators:
// stage_x = x + v h + a half_h2 (left to right; half_h2 = h² / 2) and
// stage_v = v + a h. Outputs may not overlap inputs.
struct VerletPredictArgs {
  size_t points = 0;
  const Vec2* x = nullptr;
  const Vec2* v = nullptr;
  const Vec2* a = nullptr;
  Vec2* stage_x = nullptr;
  Vec2* stage_v = nullptr;
  double h = 0.0;
  double half_h2 = 0.0;
};
void VerletPredict(Isa isa, const VerletPredictArgs& args);

// Its corrector: x = stage_x and v = v + (a0 + a1) half_h. x may not
// overlap the inputs.
struct VerletCorrectArgs {
  size_t points = 0;
  const Vec2* stage_x = nullptr;
  const Vec2* a0 = nullptr;
  const Vec2* a1 = nullptr;
  Vec2* x = nullptr;
  Vec2* v = nullptr;
  double half_h = 0.0;
};
void VerletCorrect(Isa isa, const VerletCorrectArgs& args);

}  // namespace animat::kernels

#endif  // ANIMAT_COMMON_KERNELS_KERNELS_H_
