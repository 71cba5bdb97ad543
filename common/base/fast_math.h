// exp and tanh in plain IEEE double arithmetic.
//
// The model's results must be bit-identical on every machine running the
// same build (docs/model.md, "Determinism"). libm's exp and tanh differ
// between library versions, and scalar libm tanh was 60% of a naive
// simulation step. These versions use only +, -, *, / and bit operations,
// so they give the same bits everywhere, in scalar code and when the
// compiler vectorises the array forms.
//
// Accuracy (checked against long-double libm in fast_math_test): Exp
// within 2 ulp (measured 1.2); Tanh within 4 ulp for |x| >= 2^-20
// (measured 3.4) and within 2e-16 absolutely for all x (measured 1.7e-16),
// non-decreasing up to 2 ulp; SinCos within 1 ulp of 1. For the model a
// few ulp are far below every other error (the network integrates tanh with
// a step of 0.05). NaN in gives NaN out. Pure and thread-safe.
#ifndef ANIMAT_COMMON_BASE_FAST_MATH_H_
#define ANIMAT_COMMON_BASE_FAST_MATH_H_

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

// Each build of the vector kernels (common/kernels) compiles these inline
// functions for its own instruction set. The inline namespace gives each
// build its own symbols, so the linker never merges, say, an AVX-512 copy
// into code that runs on every machine. Only those builds define it.
#ifndef ANIMAT_ISA_NAMESPACE
#define ANIMAT_ISA_NAMESPACE isa_baseline
#endif

namespace animat {
inline namespace ANIMAT_ISA_NAMESPACE {
namespace fast_math_internal {

// The compiler's built-ins, not std::bit_cast, std::fabs and
// std::copysign: those are functions that an unoptimised build emits out
// of line, outside this namespace, where the linker could merge a copy
// compiled for a wide path into code that runs everywhere.
inline double FabsOf(double x) { return __builtin_fabs(x); }
inline float FabsOf(float x) { return __builtin_fabsf(x); }
inline double CopySignOf(double x, double s) {
  return __builtin_copysign(x, s);
}
inline float CopySignOf(float x, float s) { return __builtin_copysignf(x, s); }

constexpr double kLog2e = 1.44269504088896338700e+00;
// ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (fdlibm).
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;
// Adding this rounds a double of magnitude < 2^51 to an integer held in
// the low mantissa bits.
constexpr double kShifter = 0x1.8p52;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// expm1(r) for |r| <= ln2/2 by its Taylor series to degree 13 (truncation
// error below 4e-18 relative).
inline double Expm1Reduced(double r) {
  constexpr double c13 = 1.0 / 6227020800.0;
  constexpr double c12 = 1.0 / 479001600.0;
  constexpr double c11 = 1.0 / 39916800.0;
  constexpr double c10 = 1.0 / 3628800.0;
  constexpr double c9 = 1.0 / 362880.0;
  constexpr double c8 = 1.0 / 40320.0;
  constexpr double c7 = 1.0 / 5040.0;
  constexpr double c6 = 1.0 / 720.0;
  constexpr double c5 = 1.0 / 120.0;
  constexpr double c4 = 1.0 / 24.0;
  constexpr double c3 = 1.0 / 6.0;
  constexpr double c2 = 0.5;
  double p = c13;
  p = c12 + r * p;
  p = c11 + r * p;
  p = c10 + r * p;
  p = c9 + r * p;
  p = c8 + r * p;
  p = c7 + r * p;
  p = c6 + r * p;
  p = c5 + r * p;
  p = c4 + r * p;
  p = c3 + r * p;
  p = c2 + r * p;
  p = 1.0 + r * p;
  return r * p;
}

// Splits x (|x| < 709) as k*ln2 + r; returns r and sets *scale = 2^k.
inline double Reduce(double x, double* scale) {
  const double t = x * kLog2e + kShifter;
  const double k = t - kShifter;
  const uint64_t bits = (__builtin_bit_cast(uint64_t, t) + 1023u) << 52;
  *scale = __builtin_bit_cast(double, bits);
  return (x - k * kLn2Hi) - k * kLn2Lo;
}

}  // namespace fast_math_internal

// e^x on [-708, 709]; 0 below (no subnormal results), +inf above, NaN
// for NaN.
inline double Exp(double x) {
  using namespace fast_math_internal;
  // Branch-free clamp (see Tanh) so array loops vectorise: the sign bit
  // decides which bound applies.
  const uint64_t bits = __builtin_bit_cast(uint64_t, x);
  const uint64_t magnitude = bits & ~(uint64_t{1} << 63);
  const uint64_t bound = (bits >> 63) ? __builtin_bit_cast(uint64_t, 708.0)
                                      : __builtin_bit_cast(uint64_t, 709.0);
  const bool outside = magnitude > bound;  // Also true for NaN.
  const double clamped = __builtin_bit_cast(
      double, outside ? (bits & (uint64_t{1} << 63)) | bound : bits);
  double scale;
  const double r = Reduce(clamped, &scale);
  const double y = (1.0 + Expm1Reduced(r)) * scale;
  // Outside the range: 0 below, +inf above, x itself when NaN. Selected
  // with masks so y is always computed and the loop has no branch.
  const bool is_nan = magnitude > __builtin_bit_cast(uint64_t, kInfinity);
  const uint64_t beyond =
      is_nan ? bits
             : ((bits >> 63) ? uint64_t{0}
                             : __builtin_bit_cast(uint64_t, kInfinity));
  const uint64_t mask = uint64_t{0} - static_cast<uint64_t>(outside);
  return __builtin_bit_cast(
      double, (__builtin_bit_cast(uint64_t, y) & ~mask) | (beyond & mask));
}

// Hyperbolic tangent: odd (bitwise), exactly +-1 for |x| >= 19.1,
// non-decreasing up to 2 ulp. Non-finite x gives NaN.
inline double Tanh(double x) {
  using namespace fast_math_internal;
  // Clamp |x| to 20 (tanh(20) rounds to 1) with an integer minimum: for
  // non-negative doubles the bit patterns order like the values, and this
  // form keeps the loop free of branches so it vectorises.
  const uint64_t bits = __builtin_bit_cast(uint64_t, FabsOf(x));
  constexpr uint64_t kTwenty = __builtin_bit_cast(uint64_t, 20.0);
  const double a = __builtin_bit_cast(double, bits < kTwenty ? bits : kTwenty);
  double scale;
  const double r = Reduce(2.0 * a, &scale);
  // expm1(2a) = 2^k * expm1(r) + (2^k - 1).
  const double em1 = scale * Expm1Reduced(r) + (scale - 1.0);
  // x - x is 0 for finite x and NaN otherwise.
  return CopySignOf(em1 / (em1 + 2.0), x) * (1.0 + (x - x));
}

// Single-precision tanh by the same method (expm1 to degree 7 on
// |r| <= ln2/2): within 4 ulp of the correctly rounded float result, odd,
// exactly +-1 for |x| >= 9.1; non-finite x gives NaN. Four lanes per SSE
// vector, so it costs about a third of Tanh per value.
inline float TanhF(float x) {
  using namespace fast_math_internal;
  constexpr float kLog2eF = 1.44269504f;
  // ln 2 split so that k * kLn2HiF is exact for |k| < 2^9.
  constexpr float kLn2HiF = 0.693145751953125f;
  constexpr float kLn2LoF = 1.42860677e-06f;
  constexpr float kShifterF = 0x1.8p23f;
  const uint32_t bits = __builtin_bit_cast(uint32_t, FabsOf(x));
  constexpr uint32_t kNine = __builtin_bit_cast(uint32_t, 9.5f);
  const float a = __builtin_bit_cast(float, bits < kNine ? bits : kNine);
  const float u = 2.0f * a;
  const float t = u * kLog2eF + kShifterF;
  const float k = t - kShifterF;
  const float scale =
      __builtin_bit_cast(float, (__builtin_bit_cast(uint32_t, t) + 127u) << 23);
  const float r = (u - k * kLn2HiF) - k * kLn2LoF;
  float p = 1.0f / 5040.0f;
  p = 1.0f / 720.0f + r * p;
  p = 1.0f / 120.0f + r * p;
  p = 1.0f / 24.0f + r * p;
  p = 1.0f / 6.0f + r * p;
  p = 0.5f + r * p;
  p = 1.0f + r * p;
  const float em1 = scale * (r * p) + (scale - 1.0f);
  return CopySignOf(em1 / (em1 + 2.0f), x) * (1.0f + (x - x));
}

// sin(x) and cos(x) for |x| < 2^20 (accuracy degrades beyond; arguments
// are cell orientations, a few hundred radians at most).
inline void SinCos(double x, double* sin_out, double* cos_out) {
  using namespace fast_math_internal;
  // pi/2 in three parts of 33, 33 and 53 bits (fdlibm): q * part is exact
  // for |q| < 2^20.
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kPio2_1 = 1.57079632673412561417e+00;
  constexpr double kPio2_2 = 6.07710050630396597660e-11;
  constexpr double kPio2_2t = 2.02226624879595063154e-21;
  const double t = x * kTwoOverPi + kShifter;
  const double q = t - kShifter;
  const uint64_t quadrant = __builtin_bit_cast(uint64_t, t) & 3u;
  const double r = ((x - q * kPio2_1) - q * kPio2_2) - q * kPio2_2t;
  const double r2 = r * r;
  // Taylor series on |r| <= pi/4: sin to degree 17, cos to degree 18
  // (truncation below 1e-19).
  double s = -1.0 / 355687428096000.0;  // -1/17!
  s = 1.0 / 1307674368000.0 + r2 * s;   //  1/15!
  s = -1.0 / 6227020800.0 + r2 * s;     // -1/13!
  s = 1.0 / 39916800.0 + r2 * s;        //  1/11!
  s = -1.0 / 362880.0 + r2 * s;         // -1/9!
  s = 1.0 / 5040.0 + r2 * s;            //  1/7!
  s = -1.0 / 120.0 + r2 * s;            // -1/5!
  s = 1.0 / 6.0 + r2 * s;               //  1/3!
  const double sin_r = r - r * r2 * s;
  double c = 1.0 / 6402373705728000.0;   //  1/18!
  c = -1.0 / 20922789888000.0 + r2 * c;  // -1/16!
  c = 1.0 / 87178291200.0 + r2 * c;      //  1/14!
  c = -1.0 / 479001600.0 + r2 * c;       // -1/12!
  c = 1.0 / 3628800.0 + r2 * c;          //  1/10!
  c = -1.0 / 40320.0 + r2 * c;           // -1/8!
  c = 1.0 / 720.0 + r2 * c;              //  1/6!
  c = -1.0 / 24.0 + r2 * c;              // -1/4!
  c = 0.5 + r2 * c;                      //  1/2! (sign folded)
  const double cos_r = 1.0 - r2 * c;
  switch (quadrant) {
    case 0:
      *sin_out = sin_r;
      *cos_out = cos_r;
      break;
    case 1:
      *sin_out = cos_r;
      *cos_out = -sin_r;
      break;
    case 2:
      *sin_out = -sin_r;
      *cos_out = -cos_r;
      break;
    default:
      *sin_out = -cos_r;
      *cos_out = sin_r;
      break;
  }
}

}  // namespace ANIMAT_ISA_NAMESPACE

// In-place array forms (the loop vectorises; results equal the scalar
// forms bit for bit).
void ExpInPlace(double* values, size_t n);
void TanhInPlace(double* values, size_t n);
void TanhInPlace(float* values, size_t n);

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_FAST_MATH_H_
