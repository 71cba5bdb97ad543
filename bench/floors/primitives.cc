#include "bench/floors/primitives.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "common/kernels/isa.h"
#include "common/kernels/kernels.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#endif

namespace animat::floors {
namespace {

using Clock = std::chrono::steady_clock;

// Best of `runs` timings of fn(), in nanoseconds per `lanes` values.
template <typename Fn>
double BestNsPerLane(Fn fn, double lanes, int runs = 7) {
  double best = 1e300;
  for (int r = 0; r < runs; ++r) {
    const auto start = Clock::now();
    fn();
    const double ns =
        std::chrono::duration<double, std::nano>(Clock::now() - start).count();
    best = std::min(best, ns / lanes);
  }
  return best;
}

// Register-resident chains of one operation on vectors of W lanes of T:
// kChains independent chains hide the latency, so the loop runs at the
// pipes' throughput.
constexpr int kChains = 12;
constexpr int kRounds = 20000;

#define ANIMAT_CHAIN_FN(name, T, bytes, op, target_attr)                      \
  target_attr double name(T seed) {                                           \
    typedef T V __attribute__((vector_size(bytes)));                          \
    V acc[kChains];                                                           \
    for (int c = 0; c < kChains; ++c) acc[c] = V{} + (seed + T(c) * T(1e-3)); \
    const V k = V{} + T(1.0000001);                                           \
    for (int r = 0; r < kRounds; ++r) {                                       \
      for (int c = 0; c < kChains; ++c) acc[c] = acc[c] op k;                 \
    }                                                                         \
    T sum = 0;                                                                \
    for (int c = 0; c < kChains; ++c) sum += acc[c][0];                       \
    return static_cast<double>(sum);                                          \
  }

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define ANIMAT_T512                                \
  __attribute__((                                  \
      target("avx512f,avx512bw,avx512dq,avx512vl," \
             "prefer-vector-width=512")))
#define ANIMAT_T256 __attribute__((target("avx2")))
#else
#define ANIMAT_T512
#define ANIMAT_T256
#endif
#define ANIMAT_T128

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
ANIMAT_CHAIN_FN(AddD512, double, 64, +, ANIMAT_T512)
ANIMAT_CHAIN_FN(MulD512, double, 64, *, ANIMAT_T512)
ANIMAT_CHAIN_FN(AddF512, float, 64, +, ANIMAT_T512)
ANIMAT_CHAIN_FN(MulF512, float, 64, *, ANIMAT_T512)
ANIMAT_CHAIN_FN(AddD256, double, 32, +, ANIMAT_T256)
ANIMAT_CHAIN_FN(MulD256, double, 32, *, ANIMAT_T256)
ANIMAT_CHAIN_FN(AddF256, float, 32, +, ANIMAT_T256)
ANIMAT_CHAIN_FN(MulF256, float, 32, *, ANIMAT_T256)
#endif
ANIMAT_CHAIN_FN(AddD128, double, 16, +, ANIMAT_T128)
ANIMAT_CHAIN_FN(MulD128, double, 16, *, ANIMAT_T128)
ANIMAT_CHAIN_FN(AddF128, float, 16, +, ANIMAT_T128)
ANIMAT_CHAIN_FN(MulF128, float, 16, *, ANIMAT_T128)

#undef ANIMAT_CHAIN_FN

// Element-wise division of an array in L1, vectorised at the attribute's
// width.
#define ANIMAT_DIV_FN(name, T, target_attr)                           \
  target_attr void name(const T* __restrict a, const T* __restrict b, \
                        T* __restrict out, int n) {                   \
    for (int i = 0; i < n; ++i) out[i] = a[i] / b[i];                 \
  }
ANIMAT_DIV_FN(DivD512, double, ANIMAT_T512)
ANIMAT_DIV_FN(DivF512, float, ANIMAT_T512)
ANIMAT_DIV_FN(DivD256, double, ANIMAT_T256)
ANIMAT_DIV_FN(DivF256, float, ANIMAT_T256)
ANIMAT_DIV_FN(DivD128, double, ANIMAT_T128)
ANIMAT_DIV_FN(DivF128, float, ANIMAT_T128)
#undef ANIMAT_DIV_FN

// Square roots of an array in L1 (intrinsics: the compiler does not
// vectorise std::sqrt while it may set errno). `b` is unused.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
ANIMAT_T512 void SqrtD512(const double* a, const double*, double* out, int n) {
  for (int i = 0; i + 8 <= n; i += 8) {
    _mm512_storeu_pd(out + i,
                     _mm512_maskz_sqrt_pd(0xFF, _mm512_loadu_pd(a + i)));
  }
}
ANIMAT_T256 void SqrtD256(const double* a, const double*, double* out, int n) {
  for (int i = 0; i + 4 <= n; i += 4) {
    _mm256_storeu_pd(out + i, _mm256_sqrt_pd(_mm256_loadu_pd(a + i)));
  }
}
void SqrtD128(const double* a, const double*, double* out, int n) {
  for (int i = 0; i + 2 <= n; i += 2) {
    _mm_storeu_pd(out + i, _mm_sqrt_pd(_mm_loadu_pd(a + i)));
  }
}
#else
void SqrtD128(const double* a, const double*, double* out, int n) {
  for (int i = 0; i < n; ++i) out[i] = std::sqrt(a[i]);
}
#endif

template <typename T, typename Fn>
double ArrayCost(Fn fn) {
  constexpr int kN = 1024;
  constexpr int kRepeat = 200;
  std::vector<T> a(kN), b(kN), out(kN);
  for (int i = 0; i < kN; ++i) {
    a[i] = static_cast<T>(1.5 + 0.001 * i);
    b[i] = static_cast<T>(0.7 + 0.0003 * i);
  }
  return BestNsPerLane(
      [&] {
        for (int r = 0; r < kRepeat; ++r) {
          fn(a.data(), b.data(), out.data(), kN);
          __asm__ volatile("" : : "r"(out.data()) : "memory");
        }
      },
      double{kN} * kRepeat);
}

template <typename Fn>
double ChainCost(Fn fn, int lanes) {
  volatile double sink = 0;
  return BestNsPerLane([&] { sink = sink + fn(1.0); },
                       double{kRounds} * kChains * lanes);
}

double LevelUpdateCost() {
  // Level updates only: no weights, 64 targets of 32 cells.
  constexpr int kTargets = 64, kCells = 32, kRepeat = 500;
  std::vector<float> activation(kTargets * kCells), levels(kTargets * kCells);
  for (size_t i = 0; i < activation.size(); ++i) {
    activation[i] = static_cast<float>(-3.0 + 6.0 * (i % 97) / 97.0);
    levels[i] = 0.5f;
  }
  std::vector<int> target_activation(kTargets);
  std::vector<float*> level_rows(kTargets);
  for (int t = 0; t < kTargets; ++t) {
    target_activation[t] = t;
    level_rows[t] = &levels[static_cast<size_t>(t) * kCells];
  }
  const int row_begin[] = {0};
  kernels::GrnStepArgs<float> args;
  args.cells = kCells;
  args.capacity = kCells;
  args.sources = 0;
  args.row_begin = row_begin;
  args.activation = activation.data();
  args.targets = kTargets;
  args.target_activation = target_activation.data();
  args.level = level_rows.data();
  args.dt = 0.05f;
  return BestNsPerLane(
      [&] {
        for (int r = 0; r < kRepeat; ++r) kernels::GrnStep(args);
      },
      double{kTargets} * kCells * kRepeat);
}

double PairKernelCost() {
  constexpr int kPairs = 496, kRepeat = 500;  // 32 cells.
  std::vector<double> distance(kPairs), kernel(kPairs), delay(kPairs);
  for (int p = 0; p < kPairs; ++p) distance[p] = 0.5 + 0.02 * p;
  kernels::PairKernelArgs args;
  args.pairs = kPairs;
  args.distance = distance.data();
  args.kernel_length = 3.0;
  args.delay_length = 0.25;
  args.max_delay = 127.0;
  args.kernel = kernel.data();
  args.delay = delay.data();
  return BestNsPerLane(
      [&] {
        for (int r = 0; r < kRepeat; ++r) kernels::PairKernels(args);
      },
      double{kPairs} * kRepeat);
}

}  // namespace

PrimitiveCosts MeasurePrimitives() {
  PrimitiveCosts c;
  const Isa widest = SupportedIsas().back();
  c.path = IsaName(widest);
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  if (widest == Isa::kAvx512) {
    c.double_lanes = 8;
    c.float_lanes = 16;
    c.add_double = ChainCost(AddD512, 8);
    c.mul_double = ChainCost(MulD512, 8);
    c.add_float = ChainCost(AddF512, 16);
    c.mul_float = ChainCost(MulF512, 16);
    c.div_double = ArrayCost<double>(DivD512);
    c.sqrt_double = ArrayCost<double>(SqrtD512);
    c.div_float = ArrayCost<float>(DivF512);
  } else if (widest == Isa::kAvx2) {
    c.double_lanes = 4;
    c.float_lanes = 8;
    c.add_double = ChainCost(AddD256, 4);
    c.mul_double = ChainCost(MulD256, 4);
    c.add_float = ChainCost(AddF256, 8);
    c.mul_float = ChainCost(MulF256, 8);
    c.div_double = ArrayCost<double>(DivD256);
    c.sqrt_double = ArrayCost<double>(SqrtD256);
    c.div_float = ArrayCost<float>(DivF256);
  } else
#endif
  {
    c.double_lanes = 2;
    c.float_lanes = 4;
    c.add_double = ChainCost(AddD128, 2);
    c.mul_double = ChainCost(MulD128, 2);
    c.add_float = ChainCost(AddF128, 4);
    c.mul_float = ChainCost(MulF128, 4);
    c.div_double = ArrayCost<double>(DivD128);
    c.sqrt_double = ArrayCost<double>(SqrtD128);
    c.div_float = ArrayCost<float>(DivF128);
  }
  c.level_update_float = LevelUpdateCost();
  c.pair_kernel_double = PairKernelCost();
  return c;
}

}  // namespace animat::floors
