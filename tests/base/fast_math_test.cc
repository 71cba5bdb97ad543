#include "common/base/fast_math.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iomanip>
#include <iterator>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace animat {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

uint64_t Bits(double x) { return std::bit_cast<uint64_t>(x); }

// "0x1.8p+1 (3)": the exact bits and a decimal that round-trips.
std::string Show(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%a (%.17g)", x, x);
  return buffer;
}

// The references are libm's long double functions (64-bit significand):
// their own error is far below a double ulp, so the measured error is that
// of the function under test (libm's double tanh alone is off by up to 2
// ulp on glibc).
long double ExactExp(double x) { return std::exp(static_cast<long double>(x)); }
long double ExactTanh(double x) {
  return std::tanh(static_cast<long double>(x));
}

// |got - exact| in units of the last place of a double of exact's
// magnitude. Precondition: exact is finite, non-zero and in the normal
// range of double.
double UlpError(double got, long double exact) {
  const long double ulp = std::ldexp(1.0L, std::ilogb(exact) - 52);
  return static_cast<double>(std::fabs(got - exact) / ulp);
}

// The largest error seen over a sweep, with the input that produced it.
struct Worst {
  double error = 0.0;
  double x = 0.0;
  double got = 0.0;
  long double exact = 0.0L;
  long count = 0;

  void Add(double err, double x_in, double got_in, long double exact_in) {
    ++count;
    if (err > error) {
      error = err;
      x = x_in;
      got = got_in;
      exact = exact_in;
    }
  }
};

std::ostream& operator<<(std::ostream& os, const Worst& w) {
  return os << "worst error " << w.error << " at x = " << Show(w.x) << ": got "
            << Show(w.got) << ", exact " << std::setprecision(21) << w.exact
            << " (" << w.count << " points)";
}

// n + 1 points spread over [lo, hi], offset by an irrational fraction of a
// step so that the points have varied significands.
std::vector<double> Sweep(double lo, double hi, int n) {
  std::vector<double> xs;
  xs.reserve(static_cast<size_t>(n) + 1);
  const double step = (hi - lo) / n;
  for (int i = 0; i <= n; ++i) {
    const double x = lo + (i + 0.38196601125) * step;
    if (x <= hi) xs.push_back(x);
  }
  xs.push_back(lo);
  xs.push_back(hi);
  return xs;
}

// Positive values 2^-1074 .. 2^0 on a logarithmic grid (16 per binade),
// and their negatives.
std::vector<double> TinyValues() {
  std::vector<double> xs;
  for (int e = -1074; e < 0; ++e) {
    for (int j = 0; j < 16; ++j) {
      const double x = std::ldexp(1.0 + j / 16.0 + j / 1024.0, e);
      if (x == 0.0) continue;
      xs.push_back(x);
      xs.push_back(-x);
    }
  }
  return xs;
}

Worst ExpError(const std::vector<double>& xs) {
  Worst worst;
  for (double x : xs) {
    const double got = Exp(x);
    const long double exact = ExactExp(x);
    worst.Add(UlpError(got, exact), x, got, exact);
  }
  return worst;
}

TEST(ExpTest, WithinTwoUlpOverWholeRange) {
  const Worst worst = ExpError(Sweep(-700.0, 700.0, 300000));
  EXPECT_LE(worst.error, 2.0) << worst;
}

TEST(ExpTest, WithinTwoUlpOverNetworkRange) {
  // [-40, 5] is where the model evaluates exp most (affinities, kernels).
  const Worst worst = ExpError(Sweep(-40.0, 5.0, 400000));
  EXPECT_LE(worst.error, 2.0) << worst;
}

TEST(ExpTest, WithinTwoUlpUpToTheEndsOfItsRange) {
  const Worst low = ExpError(Sweep(-708.0, -700.0, 20000));
  EXPECT_LE(low.error, 2.0) << low;
  const Worst high = ExpError(Sweep(700.0, 709.0, 20000));
  EXPECT_LE(high.error, 2.0) << high;
}

TEST(ExpTest, ExactAtZero) { EXPECT_EQ(Exp(0.0), 1.0); }

TEST(ExpTest, UnderflowsToZeroAndOverflowsToInfinity) {
  testing::FpTrapsOff traps_off;
  EXPECT_EQ(Bits(Exp(-800.0)), Bits(0.0));
  EXPECT_EQ(Exp(800.0), kInf);
  EXPECT_EQ(Bits(Exp(-kInf)), Bits(0.0));
  EXPECT_EQ(Exp(kInf), kInf);
  EXPECT_EQ(Exp(-708.5), 0.0);
  EXPECT_EQ(Exp(709.5), kInf);
}

TEST(ExpTest, NanGivesNan) {
  testing::FpTrapsOff traps_off;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(Exp(nan)));
  EXPECT_TRUE(std::isnan(Exp(-nan)));
}

TEST(TanhTest, WithinFourUlpAwayFromZero) {
  // Relative error for |x| >= 2^-20, over [-25, 25] and a logarithmic grid
  // of small values.
  std::vector<double> xs = Sweep(-25.0, 25.0, 400000);
  const std::vector<double> tiny = TinyValues();
  xs.insert(xs.end(), tiny.begin(), tiny.end());
  Worst worst;
  for (double x : xs) {
    if (std::fabs(x) < 0x1p-20) continue;
    const double got = Tanh(x);
    const long double exact = ExactTanh(x);
    worst.Add(UlpError(got, exact), x, got, exact);
  }
  EXPECT_LE(worst.error, 4.0) << worst;
}

TEST(TanhTest, WithinTwoEMinus16Absolutely) {
  std::vector<double> xs = Sweep(-25.0, 25.0, 400000);
  const std::vector<double> tiny = TinyValues();
  xs.insert(xs.end(), tiny.begin(), tiny.end());
  xs.push_back(0.0);
  Worst worst;
  for (double x : xs) {
    const double got = Tanh(x);
    const long double exact = ExactTanh(x);
    worst.Add(static_cast<double>(std::fabs(got - exact)), x, got, exact);
  }
  EXPECT_LE(worst.error, 2e-16) << worst;
}

TEST(TanhTest, IsOddBitwise) {
  std::vector<double> xs = Sweep(0.0, 25.0, 100000);
  const std::vector<double> tiny = TinyValues();
  xs.insert(xs.end(), tiny.begin(), tiny.end());
  xs.push_back(0.0);
  xs.push_back(1e300);
  for (double x : xs) {
    ASSERT_EQ(Bits(Tanh(-x)), Bits(-Tanh(x))) << "x = " << Show(x);
  }
}

// Reports the first pair x0 < x1 of `xs` (sorted) with Tanh(x1) more than
// two ulp below Tanh(x0): the documented contract is monotone up to 2 ulp
// (the last bits are rounding noise where the exact value sits near a
// rounding midpoint, e.g. between 1 - 2^-52 and 1 near x = 18.9).
::testing::AssertionResult NonDecreasingOver(const std::vector<double>& xs) {
  for (size_t i = 1; i < xs.size(); ++i) {
    const double y0 = Tanh(xs[i - 1]);
    const double y1 = Tanh(xs[i]);
    if (y1 < std::nextafter(std::nextafter(y0, -kInf), -kInf)) {
      return ::testing::AssertionFailure()
             << "Tanh(" << Show(xs[i - 1]) << ") = " << Show(y0) << " > Tanh("
             << Show(xs[i]) << ") = " << Show(y1);
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(TanhTest, IsMonotoneUpToTwoUlpOverFineSweep) {
  std::vector<double> xs = Sweep(-25.0, 25.0, 1000000);
  std::sort(xs.begin(), xs.end());  // Sweep appends its ends last.
  EXPECT_TRUE(NonDecreasingOver(xs));
}

TEST(TanhTest, IsMonotoneUpToTwoUlpOverConsecutiveDoubles) {
  // Runs of adjacent doubles around zero, the points where the argument
  // reduction changes its power of two (2|x| = (k + 1/2) ln 2), and the
  // approach to 1.
  for (double start : {-0x1p-20, 0.0, 0.17328679513998632, 0.5198603854199589,
                       0.8664339756999316, 1.0, 5.0, 18.5, 19.06148}) {
    std::vector<double> xs;
    double x = start;
    for (int i = 0; i < 4000; ++i) {
      xs.push_back(x);
      x = std::nextafter(x, kInf);
    }
    EXPECT_TRUE(NonDecreasingOver(xs)) << "run from " << Show(start);
  }
}

TEST(TanhTest, IsExactlyOneFromNineteenPointOne) {
  for (double x : Sweep(19.1, 40.0, 100000)) {
    ASSERT_EQ(Tanh(x), 1.0) << "x = " << Show(x);
    ASSERT_EQ(Tanh(-x), -1.0) << "x = " << Show(x);
  }
  EXPECT_EQ(Tanh(1e300), 1.0);
  EXPECT_EQ(Tanh(-std::numeric_limits<double>::max()), -1.0);
}

TEST(TanhTest, PreservesSignedZero) {
  EXPECT_EQ(Bits(Tanh(0.0)), Bits(0.0));
  EXPECT_EQ(Bits(Tanh(-0.0)), Bits(-0.0));
}

TEST(TanhTest, NanGivesNan) {
  testing::FpTrapsOff traps_off;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(Tanh(nan)));
  EXPECT_TRUE(std::isnan(Tanh(-nan)));
}

// 1001 values (not a multiple of any vector width) spread over the whole
// domain, with the special values among them.
std::vector<double> VariedValues(double scale) {
  std::vector<double> values;
  for (int i = 0; i < 1001; ++i) {
    const double u = std::fmod(i * 0.6180339887498949, 1.0);
    values.push_back(scale * (2.0 * u - 1.0));
  }
  const double specials[] = {0.0,
                             -0.0,
                             1e-310,
                             -1e-310,
                             1e-20,
                             -1e-20,
                             kInf,
                             -kInf,
                             1e300,
                             -1e300,
                             std::numeric_limits<double>::quiet_NaN()};
  for (size_t i = 0; i < std::size(specials); ++i) {
    values[97 * i + 3] = specials[i];
  }
  return values;
}

TEST(ExpInPlaceTest, MatchesScalarBitwise) {
  testing::FpTrapsOff traps_off;  // The values include NaN and infinities.
  std::vector<double> values = VariedValues(800.0);
  const std::vector<double> inputs = values;
  ExpInPlace(values.data(), values.size());
  for (size_t i = 0; i < inputs.size(); ++i) {
    ASSERT_EQ(Bits(values[i]), Bits(Exp(inputs[i])))
        << "index " << i << ", x = " << Show(inputs[i]);
  }
}

TEST(TanhInPlaceTest, MatchesScalarBitwise) {
  testing::FpTrapsOff traps_off;
  std::vector<double> values = VariedValues(30.0);
  const std::vector<double> inputs = values;
  TanhInPlace(values.data(), values.size());
  for (size_t i = 0; i < inputs.size(); ++i) {
    ASSERT_EQ(Bits(values[i]), Bits(Tanh(inputs[i])))
        << "index " << i << ", x = " << Show(inputs[i]);
  }
}

TEST(InPlaceTest, EmptyArrayIsFine) {
  ExpInPlace(nullptr, 0);
  TanhInPlace(static_cast<double*>(nullptr), 0);
  TanhInPlace(static_cast<float*>(nullptr), 0);
}

}  // namespace
}  // namespace animat
