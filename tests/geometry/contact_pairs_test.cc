// Tests of the mechanics' pair list (common/geometry/contact_pairs.h):
// every pair it leaves out fails the mechanics' exact range test, whatever
// the cells did since the list was built, and it is rebuilt only when it
// must be.
#include "common/geometry/contact_pairs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "common/base/rng.h"
#include "common/base/vec2.h"
#include "tests/test_util.h"

namespace animat {
namespace {

constexpr double kRange = 1.2;
constexpr double kSkin = 0.5;

bool Listed(const ContactPairs& pairs, int i, int j) {
  for (int k : pairs.Partners(i)) {
    if (k == j) return true;
  }
  return false;
}

// The mechanics' exact test (development.cc): the pair interacts while
// d < range * s.
bool InRange(Vec2 a, Vec2 b, double ra, double rb) {
  const Vec2 delta = b - a;
  return std::sqrt(delta.x * delta.x + delta.y * delta.y) < kRange * (ra + rb);
}

// Fails the test with the pair when a pair in range is not listed, or a
// partner list is not increasing above its cell.
void ExpectEveryPairInRangeListed(const ContactPairs& pairs,
                                  const std::vector<Vec2>& x,
                                  const std::vector<double>& r) {
  const int n = static_cast<int>(x.size());
  for (int i = 0; i < n; ++i) {
    int previous = i;
    for (int j : pairs.Partners(i)) {
      EXPECT_GT(j, previous) << "cell " << i;
      previous = j;
    }
    for (int j = i + 1; j < n; ++j) {
      if (InRange(x[i], x[j], r[i], r[j])) {
        EXPECT_TRUE(Listed(pairs, i, j)) << "pair " << i << ", " << j;
      }
    }
  }
}

TEST(ContactPairsTest, ListsNearPairsInOrderAndLeavesOutFarOnes) {
  // Unit cells on a line, 2 radii apart: neighbours touch (d = s), cells
  // two apart are 4 radii apart, beyond 1.2 * 2 + skin.
  std::vector<Vec2> x;
  for (int i = 0; i < 5; ++i) x.push_back({2.0 * i, 0.0});
  const std::vector<double> r(5, 1.0);
  ContactPairs pairs(kSkin);
  pairs.Update(x, r, kRange);
  for (int i = 0; i < 4; ++i) {
    ASSERT_EQ(pairs.Partners(i).size(), 1u) << "cell " << i;
    EXPECT_EQ(pairs.Partners(i)[0], i + 1);
  }
  EXPECT_TRUE(pairs.Partners(4).empty());
  EXPECT_EQ(pairs.builds(), 1);
}

TEST(ContactPairsTest, ExcludedPairsAreNeverListedAndTheOthersAre) {
  // Five unit cells close together: every pair within reach.
  const std::vector<Vec2> x = {
      {0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}, {0.5, 0.5}};
  const std::vector<double> r(5, 1.0);
  ContactPairs pairs(kSkin);
  // Either order, repeated, and a pair of a cell with itself (ignored).
  const std::vector<IndexEdge> excluded = {
      {3, 1}, {0, 4}, {1, 3}, {2, 2}, {0, 1}};
  pairs.Exclude(excluded);
  pairs.Update(x, r, kRange);
  for (int i = 0; i < 5; ++i) {
    for (int j = i + 1; j < 5; ++j) {
      const bool skip =
          (i == 0 && j == 1) || (i == 0 && j == 4) || (i == 1 && j == 3);
      EXPECT_EQ(Listed(pairs, i, j), !skip) << i << ", " << j;
    }
  }
  // A new exclusion rebuilds the list at the next Update, at the same
  // positions.
  pairs.Exclude(std::vector<IndexEdge>{{2, 4}});
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.builds(), 2);
  EXPECT_TRUE(Listed(pairs, 0, 1));
  EXPECT_FALSE(Listed(pairs, 2, 4));
  // Exclusions of cells beyond the last leave the others alone.
  pairs.Exclude(std::vector<IndexEdge>{{7, 9}});
  pairs.Update(x, r, kRange);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(pairs.Partners(i).size(), 4u - i);
}

TEST(ContactPairsTest, SkinKeepsPairsJustBeyondTheRange) {
  // 2.4 + 0.4 apart: out of range now, within range plus skin.
  const std::vector<Vec2> x = {{0.0, 0.0}, {2.8, 0.0}};
  const std::vector<double> r = {1.0, 1.0};
  ContactPairs pairs(kSkin);
  pairs.Update(x, r, kRange);
  EXPECT_TRUE(Listed(pairs, 0, 1));
}

TEST(ContactPairsTest, SmallMovesKeepTheListLargeMovesRebuildIt) {
  std::vector<Vec2> x = {{0.0, 0.0}, {2.0, 0.0}, {10.0, 0.0}};
  const std::vector<double> r = {1.0, 1.0, 1.0};
  ContactPairs pairs(kSkin);
  pairs.Update(x, r, kRange);
  x[2].x -= 0.2;  // Less than 0.45 skin.
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.builds(), 1);
  x[2].x = 3.5;  // Far: must be seen.
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.builds(), 2);
  EXPECT_TRUE(Listed(pairs, 1, 2));
}

TEST(ContactPairsTest, OtherRadiiAtTheNextRebuildAreHeeded) {
  // 3.2 apart: beyond 1.2 · 2 + skin = 2.9 with unit radii, within it with
  // radii 1.2 (1.2 · 2.4 + 0.5 = 3.38).
  std::vector<Vec2> x = {{0.0, 0.0}, {3.2, 0.0}};
  std::vector<double> r = {1.0, 1.0};
  ContactPairs pairs(kSkin);
  pairs.Update(x, r, kRange);
  EXPECT_FALSE(Listed(pairs, 0, 1));
  r = {1.2, 1.2};
  x[1].x += 1.0;  // A rebuild...
  pairs.Update(x, r, kRange);
  x[1].x -= 1.0;  // ...and another, with the new radii.
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.builds(), 3);
  EXPECT_TRUE(Listed(pairs, 0, 1));
}

TEST(ContactPairsTest, MovesCountOnlyOtherPositionsOrRanges) {
  std::vector<Vec2> x = {{0.0, 0.0}, {2.0, 0.0}};
  const std::vector<double> r = {1.0, 1.0};
  ContactPairs pairs(kSkin);
  EXPECT_EQ(pairs.moves(), 0);
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.moves(), 1);
  pairs.Update(x, r, kRange);  // The same bits: no move.
  EXPECT_EQ(pairs.moves(), 1);
  const std::vector<Vec2> before = x;
  x[1].x += 0.01;  // Within the skin: a move, no rebuild.
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.moves(), 2);
  EXPECT_EQ(pairs.builds(), 1);
  pairs.Update(before, r, kRange);  // Back: a move again.
  EXPECT_EQ(pairs.moves(), 3);
  pairs.Update(before, r, 2.0);  // Another range.
  EXPECT_EQ(pairs.moves(), 4);
}

TEST(ContactPairsTest, AnotherRangeRebuildsTheList) {
  // 4.5 apart, radii 1: beyond 1.2 · 2 + skin = 2.9, within 2.5 · 2 = 5.
  const std::vector<Vec2> x = {{0.0, 0.0}, {4.5, 0.0}};
  const std::vector<double> r = {1.0, 1.0};
  ContactPairs pairs(kSkin);
  pairs.Update(x, r, kRange);
  EXPECT_FALSE(Listed(pairs, 0, 1));
  pairs.Update(x, r, 2.5);  // The same positions, a wider range.
  EXPECT_EQ(pairs.builds(), 2);
  EXPECT_TRUE(Listed(pairs, 0, 1));
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.builds(), 3);
  EXPECT_FALSE(Listed(pairs, 0, 1));
}

TEST(ContactPairsTest, NewCellRebuildsTheList) {
  std::vector<Vec2> x = {{0.0, 0.0}, {2.0, 0.0}};
  std::vector<double> r = {1.0, 1.0};
  ContactPairs pairs(kSkin);
  pairs.Update(x, r, kRange);
  x.push_back({1.0, 1.0});
  r.push_back(1.0);
  pairs.Update(x, r, kRange);
  EXPECT_EQ(pairs.builds(), 2);
  EXPECT_TRUE(Listed(pairs, 0, 2));
  EXPECT_TRUE(Listed(pairs, 1, 2));
}

TEST(ContactPairsTest, NonFiniteOrHugeCoordinatesRebuildAtEveryMove) {
  testing::FpTrapsOff traps_off;  // NaN is compared on purpose.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Vec2 odd : {Vec2{nan, 0.0}, Vec2{0.0, 3e6}}) {
    std::vector<Vec2> x = {{0.0, 0.0}, {2.0, 0.0}, odd};
    const std::vector<double> r = {1.0, 1.0, 1.0};
    ContactPairs pairs(kSkin);
    pairs.Update(x, r, kRange);
    // The same bits again: the list built for them still holds.
    pairs.Update(x, r, kRange);
    EXPECT_EQ(pairs.builds(), 1) << odd.x << ", " << odd.y;
    // The least move of another cell: no margin can be trusted, so the
    // list is built again.
    x[1].x = std::nextafter(x[1].x, 3.0);
    pairs.Update(x, r, kRange);
    EXPECT_EQ(pairs.builds(), 2) << odd.x << ", " << odd.y;
    // A NaN pair is listed (the mechanics' own test rejects it).
    EXPECT_EQ(Listed(pairs, 0, 2), std::isnan(odd.x));
  }
}

TEST(ContactPairsTest, RandomWalksNeverLoseAPairInRange) {
  // Cells of radius 1 to 1.5 in a box of 12 x 12 radii take random steps
  // of up to 0.05 radii along each axis, with a new cell now and then: a
  // list lasts a few dozen steps (until some cell has moved 0.225 radii),
  // and a list never rebuilt would miss pairs as the cells wander.
  RandomStream random(7, 0, StreamPurpose::kRandomGenome);
  std::vector<Vec2> x;
  std::vector<double> r;
  for (int i = 0; i < 12; ++i) {
    x.push_back({random.Uniform(0.0, 12.0), random.Uniform(0.0, 12.0)});
    r.push_back(random.Uniform(1.0, 1.5));
  }
  ContactPairs pairs(kSkin);
  for (int step = 0; step < 2000; ++step) {
    pairs.Update(x, r, kRange);
    ExpectEveryPairInRangeListed(pairs, x, r);
    if (::testing::Test::HasFailure()) return;
    for (Vec2& p : x) {
      p += Vec2{random.Uniform(-0.05, 0.05), random.Uniform(-0.05, 0.05)};
    }
    if (step % 200 == 199 && x.size() < 32) {
      x.push_back(x.back() + Vec2{0.5, 0.0});
      r.push_back(random.Uniform(1.0, 1.5));
    }
  }
  EXPECT_GT(pairs.builds(), 20);
  EXPECT_LT(pairs.builds(), 1000);
}

}  // namespace
}  // namespace animat
