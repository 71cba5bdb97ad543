// The network update's two kernels (common/grn/grn_batch.cc), written as
// there and as Eigen array expressions, on the reference workload's sizes:
// 32 cells, a weight applied to a row of activations, and the level update
// L <- clamp(L + (tanh(A / 2) - L) * dt, 0, 1). Each benchmark checks that
// both forms give the same bits before it times them (exits 1 if not).
//
//   build/bin/animat-eigen-bench
//
// docs/benchmarks.md ("Development's pair list, and Eigen measured") gives
// the results and why the hand-written loops stay.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <bit>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "common/base/fast_math.h"

namespace animat {
namespace {

constexpr int kCells = 32;
constexpr int kRows = 20;  // Activation rows updated per pass.

inline double TanhOf(double x) { return Tanh(x); }
inline float TanhOf(float x) { return TanhF(x); }

template <typename S>
using ArrayMap = Eigen::Map<Eigen::Array<S, Eigen::Dynamic, 1>>;
template <typename S>
using ConstArrayMap = Eigen::Map<const Eigen::Array<S, Eigen::Dynamic, 1>>;

// Reproducible inputs in the ranges the network sees.
template <typename S>
std::vector<S> Values(int count, S lo, S hi, unsigned seed) {
  std::vector<S> v(count);
  unsigned x = seed;
  for (S& value : v) {
    x = x * 1664525u + 1013904223u;
    value = lo + (hi - lo) * static_cast<S>(x >> 8) / static_cast<S>(1u << 24);
  }
  return v;
}

template <typename S>
void AccumulateHand(S* acc, const S* weight, const S* value, int n) {
  for (int r = 0; r < kRows; ++r) {
    S* row = acc + r * kCells;
    const S w = weight[r];
    for (int c = 0; c < n; ++c) row[c] += w * value[c];
  }
}

template <typename S>
void AccumulateEigen(S* acc, const S* weight, const S* value, int n) {
  for (int r = 0; r < kRows; ++r) {
    ArrayMap<S>(acc + r * kCells, n) += weight[r] * ConstArrayMap<S>(value, n);
  }
}

template <typename S>
void UpdateHand(S* level, const S* a, S dt, int n) {
  for (int r = 0; r < kRows; ++r) {
    S* l = level + r * kCells;
    const S* ar = a + r * kCells;
    for (int c = 0; c < n; ++c) {
      const S x = l[c] + (TanhOf(ar[c] * S{0.5}) - l[c]) * dt;
      l[c] = x < S{0} ? S{0} : (x > S{1} ? S{1} : x);
    }
  }
}

template <typename S>
void UpdateEigen(S* level, const S* a, S dt, int n) {
  for (int r = 0; r < kRows; ++r) {
    ArrayMap<S> l(level + r * kCells, n);
    const ConstArrayMap<S> ar(a + r * kCells, n);
    l = (l + ((ar * S{0.5}).unaryExpr([](S v) { return TanhOf(v); }) - l) * dt)
            .unaryExpr(
                [](S x) { return x < S{0} ? S{0} : (x > S{1} ? S{1} : x); });
  }
}

template <typename S>
void CheckSameBits(const std::vector<S>& a, const std::vector<S>& b,
                   const char* what) {
  if (std::memcmp(a.data(), b.data(), a.size() * sizeof(S)) != 0) {
    std::fprintf(stderr, "%s: Eigen and hand-written forms differ\n", what);
    std::exit(1);
  }
}

// state.range(0): 0 hand-written, 1 Eigen.
template <typename S>
void BM_Accumulate(benchmark::State& state) {
  const std::vector<S> weight = Values<S>(kRows, S{-5}, S{5}, 1);
  const std::vector<S> value = Values<S>(kCells, S{0}, S{1}, 2);
  std::vector<S> hand = Values<S>(kRows * kCells, S{-3}, S{3}, 3);
  std::vector<S> eigen = hand;
  AccumulateHand(hand.data(), weight.data(), value.data(), kCells);
  AccumulateEigen(eigen.data(), weight.data(), value.data(), kCells);
  CheckSameBits(hand, eigen, "accumulate");
  std::vector<S>& acc = state.range(0) == 0 ? hand : eigen;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      AccumulateHand(acc.data(), weight.data(), value.data(), kCells);
    } else {
      AccumulateEigen(acc.data(), weight.data(), value.data(), kCells);
    }
    benchmark::DoNotOptimize(acc.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK_TEMPLATE(BM_Accumulate, double)->DenseRange(0, 1);
BENCHMARK_TEMPLATE(BM_Accumulate, float)->DenseRange(0, 1);

template <typename S>
void BM_LevelUpdate(benchmark::State& state) {
  const std::vector<S> a = Values<S>(kRows * kCells, S{-12}, S{12}, 4);
  std::vector<S> hand = Values<S>(kRows * kCells, S{0}, S{1}, 5);
  std::vector<S> eigen = hand;
  const S dt = S{0.05};
  UpdateHand(hand.data(), a.data(), dt, kCells);
  UpdateEigen(eigen.data(), a.data(), dt, kCells);
  CheckSameBits(hand, eigen, "level update");
  std::vector<S>& level = state.range(0) == 0 ? hand : eigen;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      UpdateHand(level.data(), a.data(), dt, kCells);
    } else {
      UpdateEigen(level.data(), a.data(), dt, kCells);
    }
    benchmark::DoNotOptimize(level.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK_TEMPLATE(BM_LevelUpdate, double)->DenseRange(0, 1);
BENCHMARK_TEMPLATE(BM_LevelUpdate, float)->DenseRange(0, 1);

}  // namespace
}  // namespace animat

// main: bench/benchmark_main.cc, which checks the command line first.
