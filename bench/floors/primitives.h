// What this machine's arithmetic costs at its widest instruction-set path
// (common/kernels/isa.h): nanoseconds per lane of each operation the model
// does, measured here, for the floors report (docs/benchmarks.md).
#ifndef ANIMAT_BENCH_FLOORS_PRIMITIVES_H_
#define ANIMAT_BENCH_FLOORS_PRIMITIVES_H_

#include <string>

namespace animat::floors {

// Nanoseconds per lane (one value), each the best of several timed runs.
struct PrimitiveCosts {
  std::string path;  // "avx512", "avx2" or "baseline": the vector width.
  int double_lanes = 1;
  int float_lanes = 1;
  // Independent additions or multiplications, operands in registers (the
  // two kinds run on separate pipes, so a mix of n of each costs about
  // n * add, not n * (add + mul)).
  double add_double = 0, mul_double = 0, add_float = 0, mul_float = 0;
  // Divisions and square roots of arrays in L1 (the divider bounds them).
  double div_double = 0, sqrt_double = 0, div_float = 0;
  // The model's own vector kernels on the widest path, per value: the
  // network's level update (TanhF and the clamp, float) and the signals'
  // pair kernel (Exp, a division, a floor; double).
  double level_update_float = 0;
  double pair_kernel_double = 0;
};

// Measures on the widest path this machine and build support; takes about a
// second.
PrimitiveCosts MeasurePrimitives();

}  // namespace animat::floors

#endif  // ANIMAT_BENCH_FLOORS_PRIMITIVES_H_
