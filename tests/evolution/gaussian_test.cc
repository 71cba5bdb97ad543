// The written-out logarithm and Box-Muller normals behind the coordinate
// mutation (master/evolution/gaussian.h).
#include "master/evolution/gaussian.h"

#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "common/base/rng.h"

namespace animat {
namespace {

// Distance in ulps between two finite doubles of the same sign.
int64_t UlpDistance(double a, double b) {
  if (a == b) return 0;
  const double ulp = std::nextafter(std::fabs(b), 1e300) - std::fabs(b);
  return static_cast<int64_t>(std::llround(std::fabs(a - b) / ulp));
}

TEST(GaussianTest, LogPositiveAgreesWithLibmWithinOneUlp) {
  EXPECT_EQ(LogPositive(1.0), 0.0);
  EXPECT_EQ(LogPositive(2.0), std::log(2.0));
  RandomStream stream(1, 0, StreamPurpose::kMutation);
  int64_t worst = 0;
  for (int i = 0; i < 40000; ++i) {
    // The Box-Muller inputs, (0, 1], and values around 1 and far from it.
    double x = 1.0 - stream.NextDouble();
    if (i % 4 == 1) x = 1.0 + (stream.NextDouble() - 0.5) * 1e-6;
    if (i % 4 == 2) x = std::ldexp(0.5 + stream.NextDouble(), -1000 + i % 2000);
    if (i % 4 == 3) x = 0x1.0p-53 * (1 + static_cast<double>(i));
    const int64_t ulps = UlpDistance(LogPositive(x), std::log(x));
    worst = std::max(worst, ulps);
    ASSERT_LE(ulps, 1) << x;
  }
  EXPECT_LE(worst, 1);
}

TEST(GaussianTest, StandardNormalPairHasTheMomentsOfANormal) {
  RandomStream stream(2, 0, StreamPurpose::kMutation);
  const int pairs = 25000;
  double sum[2] = {0, 0}, sum2[2] = {0, 0}, sum4[2] = {0, 0}, cross = 0;
  double largest = 0;
  for (int i = 0; i < pairs; ++i) {
    double z[2];
    StandardNormalPair(stream, &z[0], &z[1]);
    for (int k = 0; k < 2; ++k) {
      sum[k] += z[k];
      sum2[k] += z[k] * z[k];
      sum4[k] += z[k] * z[k] * z[k] * z[k];
      largest = std::max(largest, std::fabs(z[k]));
    }
    cross += z[0] * z[1];
  }
  EXPECT_EQ(stream.draws(), 2u * pairs);
  const double n = pairs;
  for (int k = 0; k < 2; ++k) {
    EXPECT_LT(std::fabs(sum[k] / n), 5.0 / std::sqrt(n));
    // Var(z^2) = 2, Var(z^4) = 96.
    EXPECT_LT(std::fabs(sum2[k] / n - 1.0), 5.0 * std::sqrt(2.0 / n));
    EXPECT_LT(std::fabs(sum4[k] / n - 3.0), 5.0 * std::sqrt(96.0 / n));
  }
  EXPECT_LT(std::fabs(cross / n), 5.0 / std::sqrt(n));
  EXPECT_LT(largest, 8.6);
}

}  // namespace
}  // namespace animat
