#include "common/base/rng.h"

#include <array>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

namespace animat {
namespace {

using Block = std::array<uint32_t, 4>;

constexpr StreamPurpose kPurpose = StreamPurpose::kRandomGenome;
// A purpose number no enumerator has yet (the enum has a fixed underlying
// type, so any uint32_t is a valid value).
constexpr StreamPurpose kOtherPurpose = static_cast<StreamPurpose>(2);

std::vector<uint64_t> Draws(RandomStream stream, int n) {
  std::vector<uint64_t> out;
  for (int i = 0; i < n; ++i) out.push_back(stream.NextU64());
  return out;
}

// Known-answer vectors of Random123 (kat_vectors, philox4x32 10 rounds).
TEST(PhiloxTest, MatchesRandom123ZeroVector) {
  EXPECT_EQ(Philox4x32({0, 0, 0, 0}, {0, 0}),
            (Block{0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}));
}

TEST(PhiloxTest, MatchesRandom123AllOnesVector) {
  EXPECT_EQ(Philox4x32({0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
                       {0xffffffff, 0xffffffff}),
            (Block{0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}));
}

TEST(PhiloxTest, MatchesRandom123PiVector) {
  EXPECT_EQ(Philox4x32({0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
                       {0xa4093822, 0x299f31d0}),
            (Block{0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}));
}

// The counter layout is part of the determinism contract (stored runs
// replay only if it stays): draw n of (seed, individual, purpose) is the
// first 64 bits of the block for counter (n, purpose, individual lo, hi)
// and key (seed lo, hi).
TEST(RandomStreamTest, DrawNIsPhiloxBlockForCounterN) {
  const uint64_t seed = 0x0123456789abcdefull;
  const uint64_t individual = 0xfedcba9876543210ull;
  RandomStream stream(seed, individual, kPurpose);
  for (uint32_t n = 0; n < 5; ++n) {
    const Block out = Philox4x32({n, 1u, 0x76543210u, 0xfedcba98u},
                                 {0x89abcdefu, 0x01234567u});
    EXPECT_EQ(stream.NextU64(), (uint64_t{out[1]} << 32) | out[0])
        << "draw " << n;
  }
}

TEST(RandomStreamTest, SameKeyGivesSameSequence) {
  RandomStream a(42, 7, kPurpose);
  RandomStream b(42, 7, kPurpose);
  EXPECT_EQ(Draws(a, 100), Draws(b, 100));
}

TEST(RandomStreamTest, CopyContinuesTheSameSequence) {
  RandomStream a(42, 7, kPurpose);
  for (int i = 0; i < 10; ++i) (void)a.NextU64();
  RandomStream b = a;
  EXPECT_EQ(Draws(a, 20), Draws(b, 20));
  EXPECT_EQ(b.draws(), 10u);
}

TEST(RandomStreamTest, DifferentSeedGivesDifferentSequence) {
  const std::vector<uint64_t> base = Draws(RandomStream(42, 7, kPurpose), 16);
  EXPECT_NE(Draws(RandomStream(43, 7, kPurpose), 16), base);
  // Only the high half of the seed differs.
  EXPECT_NE(Draws(RandomStream(42 + (uint64_t{1} << 32), 7, kPurpose), 16),
            base);
}

TEST(RandomStreamTest, DifferentIndividualGivesDifferentSequence) {
  const std::vector<uint64_t> base = Draws(RandomStream(42, 7, kPurpose), 16);
  EXPECT_NE(Draws(RandomStream(42, 8, kPurpose), 16), base);
  // Only the high half of the individual differs.
  EXPECT_NE(Draws(RandomStream(42, 7 + (uint64_t{1} << 32), kPurpose), 16),
            base);
}

TEST(RandomStreamTest, DifferentPurposeGivesDifferentSequence) {
  EXPECT_NE(Draws(RandomStream(42, 7, kOtherPurpose), 16),
            Draws(RandomStream(42, 7, kPurpose), 16));
}

TEST(RandomStreamTest, DrawsWithinOneStreamDiffer) {
  const std::vector<uint64_t> draws = Draws(RandomStream(1, 2, kPurpose), 64);
  for (size_t i = 0; i < draws.size(); ++i) {
    for (size_t j = i + 1; j < draws.size(); ++j) {
      EXPECT_NE(draws[i], draws[j]) << i << " " << j;
    }
  }
}

TEST(RandomStreamTest, NextDoubleIsInUnitIntervalWithMeanOneHalf) {
  RandomStream stream(5, 0, kPurpose);
  constexpr int kN = 20000;
  double sum = 0.0;
  double lowest = 1.0;
  double highest = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double u = stream.NextDouble();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    lowest = u < lowest ? u : lowest;
    highest = u > highest ? u : highest;
  }
  // Standard error of the mean is 0.29 / sqrt(kN) = 2e-3.
  EXPECT_NEAR(sum / kN, 0.5, 1e-2);
  EXPECT_LT(lowest, 1e-3);
  EXPECT_GT(highest, 1.0 - 1e-3);
}

TEST(RandomStreamTest, UniformIsInHalfOpenRange) {
  RandomStream stream(6, 0, kPurpose);
  double sum = 0.0;
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    const double u = stream.Uniform(-3.0, 5.0);
    ASSERT_GE(u, -3.0);
    ASSERT_LT(u, 5.0);
    sum += u;
  }
  EXPECT_NEAR(sum / kN, 1.0, 0.1);
}

TEST(RandomStreamTest, UniformOfEmptyRangeIsItsBound) {
  RandomStream stream(6, 0, kPurpose);
  EXPECT_EQ(stream.Uniform(2.5, 2.5), 2.5);
}

TEST(RandomStreamTest, BelowStaysInRange) {
  RandomStream stream(7, 0, kPurpose);
  for (uint64_t n : {uint64_t{1}, uint64_t{2}, uint64_t{3}, uint64_t{7},
                     uint64_t{1000}, (uint64_t{1} << 63) + 1, UINT64_MAX}) {
    for (int i = 0; i < 1000; ++i) {
      ASSERT_LT(stream.Below(n), n) << "n = " << n;
    }
  }
}

TEST(RandomStreamTest, BelowOneIsAlwaysZero) {
  RandomStream stream(7, 1, kPurpose);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(stream.Below(1), 0u);
}

// Pearson's chi-square over the n bins. The stream is fixed, so the
// statistic is one deterministic number; the bounds are about 5 standard
// deviations above the mean (n - 1) so that a correct generator passes by a
// wide margin and a biased one fails.
double ChiSquare(RandomStream& stream, uint64_t n, int draws) {
  std::vector<int> counts(n, 0);
  for (int i = 0; i < draws; ++i) ++counts[stream.Below(n)];
  const double expected = static_cast<double>(draws) / static_cast<double>(n);
  double chi2 = 0.0;
  for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
  return chi2;
}

TEST(RandomStreamTest, BelowIsRoughlyUniform) {
  RandomStream stream(8, 0, kPurpose);
  EXPECT_LT(ChiSquare(stream, 10, 20000), 9.0 + 5.0 * 4.3);
  EXPECT_LT(ChiSquare(stream, 7, 14000), 6.0 + 5.0 * 3.5);
  EXPECT_LT(ChiSquare(stream, 1000, 30000), 999.0 + 5.0 * 44.7);
}

TEST(RandomStreamTest, BelowHasNoModuloBias) {
  // For n near 2/3 of 2^64, a plain NextU64() % n lands in the lower half
  // of [0, n) two times in three; an unbiased draw does so half the time.
  RandomStream stream(9, 0, kPurpose);
  const uint64_t n = 0xAAAAAAAAAAAAAAABull;
  constexpr int kN = 10000;
  int low = 0;
  for (int i = 0; i < kN; ++i) low += stream.Below(n) < n / 2;
  EXPECT_NEAR(static_cast<double>(low) / kN, 0.5, 0.02);
}

TEST(RandomStreamTest, DrawsCountsEverySixtyFourBitDraw) {
  RandomStream stream(10, 0, kPurpose);
  EXPECT_EQ(stream.draws(), 0u);
  (void)stream.NextU64();
  EXPECT_EQ(stream.draws(), 1u);
  (void)stream.NextDouble();
  EXPECT_EQ(stream.draws(), 2u);
  (void)stream.Uniform(0.0, 1.0);
  EXPECT_EQ(stream.draws(), 3u);
  (void)stream.NextBool();
  EXPECT_EQ(stream.draws(), 4u);
  (void)stream.Below(8);  // A power of two never rejects.
  EXPECT_EQ(stream.draws(), 5u);
}

TEST(RandomStreamTest, DrawsCountsRejectedDrawsOfBelow) {
  // About half of the 64-bit draws are rejected for n = 2^63 + 1.
  RandomStream stream(11, 0, kPurpose);
  constexpr int kN = 1000;
  for (int i = 0; i < kN; ++i) (void)stream.Below((uint64_t{1} << 63) + 1);
  EXPECT_GT(stream.draws(), uint64_t{kN} * 3 / 2);
  EXPECT_LT(stream.draws(), uint64_t{kN} * 5 / 2);
}

TEST(RandomStreamTest, NextBoolGivesBothValuesEvenly) {
  RandomStream stream(12, 0, kPurpose);
  constexpr int kN = 10000;
  int heads = 0;
  for (int i = 0; i < kN; ++i) heads += stream.NextBool();
  EXPECT_NEAR(static_cast<double>(heads) / kN, 0.5, 0.02);
}

}  // namespace
}  // namespace animat
