#include "analysis/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/base/rng.h"

namespace animat::analysis {
namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

std::vector<double> Cosine(int n, double frequency, double amplitude,
                           double phase, double mean) {
  std::vector<double> s(n);
  for (int k = 0; k < n; ++k) {
    s[k] = mean + amplitude * std::cos(kTwoPi * frequency * k - phase);
  }
  return s;
}

// A prime length: the signals are padded to a power of two for the
// coarse spectrum, and the peak is refined from there.
TEST(SpectrumTest, FindsThePeriodOfASignalOfPrimeLength) {
  std::vector<double> s = Cosine(2003, 1 / 37.3, 0.2, 0.5, 0.3);
  const std::vector<double> weak = Cosine(2003, 1 / 11.9, 0.05, 0, 0);
  for (size_t k = 0; k < s.size(); ++k) s[k] += weak[k];
  const std::optional<DominantFrequency> d =
      FindDominantFrequency({s, weak}, 2.0 / 2003);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(1 / d->frequency, 37.3, 37.3 * 1e-4);
}

TEST(SpectrumTest, ComponentOfACosineIsItsAmplitudeAndPhase) {
  const std::vector<double> s = Cosine(3000, 1 / 87.3, 0.4, 1.1, 0.25);
  const Component c = ComponentAt(s, 1 / 87.3);
  EXPECT_NEAR(c.amplitude, 0.4, 1e-4);
  EXPECT_NEAR(c.phase, 1.1, 1e-4);
  // Phases wrap into (−π, π].
  const Component wrapped = ComponentAt(Cosine(3000, 0.05, 1, -3, 0), 0.05);
  EXPECT_NEAR(wrapped.phase, -3, 1e-4);
}

TEST(SpectrumTest, FindsTheDominantPeriodAmongHarmonicsAndNoise) {
  RandomStream random(9, 0, StreamPurpose::kNullFitness);
  std::vector<std::vector<double>> signals;
  for (int cell = 0; cell < 5; ++cell) {
    std::vector<double> s = Cosine(2500, 1 / 61.7, 0.3, cell * 0.7, 0.1);
    const std::vector<double> harmonic =
        Cosine(2500, 2 / 61.7, 0.1, cell * 0.3, 0);
    for (size_t k = 0; k < s.size(); ++k) {
      s[k] += harmonic[k] + random.Uniform(-0.05, 0.05);
    }
    signals.push_back(s);
  }
  const std::optional<DominantFrequency> d =
      FindDominantFrequency(signals, 2.0 / 2500);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(1 / d->frequency, 61.7, 61.7 * 1e-4);
  // Variance: 0.3²/2 + 0.1²/2 + 0.1²/12 per signal; the main component
  // explains 0.045 of 0.05583.
  EXPECT_NEAR(d->periodic_fraction, 0.045 / (0.045 + 0.005 + 0.01 / 12), 0.01);
}

TEST(SpectrumTest, ASlowDriftIsNotAPeriod) {
  // A drift of a quarter cycle in the signal is far stronger than the
  // oscillation, but a period must fit at least twice.
  std::vector<double> s = Cosine(2000, 1 / 8000.0, 1, 0, 0);
  const std::vector<double> fast = Cosine(2000, 1 / 50.0, 0.3, 0, 0);
  for (size_t k = 0; k < s.size(); ++k) s[k] += fast[k];
  const std::optional<DominantFrequency> d =
      FindDominantFrequency({s}, 2.0 / 2000);
  ASSERT_TRUE(d.has_value());
  EXPECT_NEAR(1 / d->frequency, 50, 0.05);
}

TEST(SpectrumTest, ConstantSignalsHaveNoPeriod) {
  EXPECT_FALSE(
      FindDominantFrequency(
          {std::vector<double>(100, 0.3), std::vector<double>(100, -0.2)}, 0.02)
          .has_value());
  EXPECT_FALSE(FindDominantFrequency({{1, 2, 3}}, 0.02).has_value());
  EXPECT_FALSE(FindDominantFrequency({}, 0.02).has_value());
}

TEST(SpectrumTest, NoiseIsMostlyNotPeriodic) {
  RandomStream random(11, 0, StreamPurpose::kNullFitness);
  std::vector<std::vector<double>> signals(4, std::vector<double>(2000));
  for (auto& s : signals) {
    for (double& x : s) x = random.Uniform(-1, 1);
  }
  const std::optional<DominantFrequency> d =
      FindDominantFrequency(signals, 0.001);
  ASSERT_TRUE(d.has_value());
  EXPECT_LT(d->periodic_fraction, 0.05);
}

TEST(SpectrumTest, WrapAngleLandsInMinusPiToPi) {
  EXPECT_DOUBLE_EQ(WrapAngle(0.5), 0.5);
  EXPECT_NEAR(WrapAngle(kTwoPi + 0.5), 0.5, 1e-15);
  EXPECT_NEAR(WrapAngle(-kTwoPi - 0.5), -0.5, 1e-15);
  EXPECT_DOUBLE_EQ(WrapAngle(std::numbers::pi), std::numbers::pi);
  EXPECT_DOUBLE_EQ(WrapAngle(-std::numbers::pi), std::numbers::pi);
}

}  // namespace
}  // namespace animat::analysis
