#include "master/evolution/gaussian.h"

#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>

#include "common/base/fast_math.h"

namespace animat {
namespace {

// ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (fdlibm).
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kSqrt2 = 1.41421356237309504880;
constexpr double kTwoPi = 6.28318530717958647693;

}  // namespace

double LogPositive(double x) {
  assert(std::isnormal(x) && x > 0.0);
  // x = m * 2^k with m in [1, 2), then m in [sqrt(2)/2, sqrt(2)).
  const uint64_t bits = std::bit_cast<uint64_t>(x);
  int k = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  double m = std::bit_cast<double>((bits & ((uint64_t{1} << 52) - 1)) |
                                   (uint64_t{1023} << 52));
  if (m >= kSqrt2) {
    m *= 0.5;  // Exact.
    ++k;
  }
  // ln(1 + f) = 2 atanh(s) = 2s + s R(z), s = f / (2 + f), z = s^2,
  // R(z) = sum 2 z^j / (2j + 1); |s| <= 0.172, so z <= 0.0295 and the
  // series to j = 11 leaves a relative error below 1e-18.
  const double f = m - 1.0;  // Exact (Sterbenz).
  const double s = f / (2.0 + f);
  const double z = s * s;
  double r = 2.0 / 23.0;
  r = 2.0 / 21.0 + z * r;
  r = 2.0 / 19.0 + z * r;
  r = 2.0 / 17.0 + z * r;
  r = 2.0 / 15.0 + z * r;
  r = 2.0 / 13.0 + z * r;
  r = 2.0 / 11.0 + z * r;
  r = 2.0 / 9.0 + z * r;
  r = 2.0 / 7.0 + z * r;
  r = 2.0 / 5.0 + z * r;
  r = 2.0 / 3.0 + z * r;
  r *= z;
  // 2s = f - s f = f - hfsq + s hfsq, with hfsq = f^2 / 2 (fdlibm's form,
  // which keeps the result accurate near x = 1).
  const double hfsq = 0.5 * f * f;
  const double dk = static_cast<double>(k);
  return dk * kLn2Hi - ((hfsq - (s * (hfsq + r) + dk * kLn2Lo)) - f);
}

void StandardNormalPair(RandomStream& stream, double* z0, double* z1) {
  const double u1 = 1.0 - stream.NextDouble();  // (0, 1], exact.
  const double u2 = stream.NextDouble();
  const double radius = std::sqrt(-2.0 * LogPositive(u1));
  double sin_theta, cos_theta;
  SinCos(kTwoPi * u2, &sin_theta, &cos_theta);
  *z0 = radius * cos_theta;
  *z1 = radius * sin_theta;
}

}  // namespace animat
