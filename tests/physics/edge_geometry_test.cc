// Tests of MeasureEdges (common/physics/edge_geometry.h): the lengths and
// unit directions of edges, against the scalar formula of docs/model.md
// §7.2 written out here, bit for bit, for every count (the paired path and
// its odd tail), coincident nodes, and non-finite or huge coordinates,
// including the floating-point exceptions each raises.
#include "common/physics/edge_geometry.h"

#include <gtest/gtest.h>

#include <cfenv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "common/base/vec2.h"
#include "tests/test_util.h"

namespace animat {
namespace {

struct Edges {
  std::vector<Vec2> x;
  std::vector<int> a, b;
};

struct Measured {
  std::vector<double> length;
  std::vector<Vec2> unit;
};

// The model's formula, one edge at a time.
Measured Scalar(const Edges& e) {
  Measured m;
  for (size_t k = 0; k < e.a.size(); ++k) {
    const Vec2 d = e.x[e.b[k]] - e.x[e.a[k]];
    const double l = std::sqrt(d.x * d.x + d.y * d.y);
    m.length.push_back(l);
    m.unit.push_back(l > 0.0 ? Vec2{d.x / l, d.y / l} : Vec2{0.0, 0.0});
  }
  return m;
}

Measured Fast(const Edges& e) {
  Measured m;
  m.length.assign(e.a.size(), -1.0);
  m.unit.assign(e.a.size(), Vec2{-1.0, -1.0});
  MeasureEdges(e.x.data(), e.a.data(), e.b.data(), static_cast<int>(e.a.size()),
               m.length.data(), m.unit.data());
  return m;
}

uint64_t Bits(double v) {
  uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

// Equal bits, or both NaN (which NaN a sum of two NaNs keeps is not part
// of the model).
void ExpectSame(double want, double got, const char* what, size_t k) {
  if (std::isnan(want)) {
    EXPECT_TRUE(std::isnan(got)) << what << " of edge " << k;
  } else {
    EXPECT_EQ(Bits(want), Bits(got))
        << what << " of edge " << k << ": " << want << " vs " << got;
  }
}

void ExpectSame(const Measured& want, const Measured& got) {
  ASSERT_EQ(want.length.size(), got.length.size());
  for (size_t k = 0; k < want.length.size(); ++k) {
    ExpectSame(want.length[k], got.length[k], "length", k);
    ExpectSame(want.unit[k].x, got.unit[k].x, "unit x", k);
    ExpectSame(want.unit[k].y, got.unit[k].y, "unit y", k);
  }
}

Edges RandomEdges(int nodes, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coordinate(-20.0, 20.0);
  std::uniform_int_distribution<int> node(0, nodes - 1);
  Edges e;
  for (int i = 0; i < nodes; ++i) {
    e.x.push_back({coordinate(rng), coordinate(rng)});
  }
  for (int k = 0; k < count; ++k) {
    e.a.push_back(node(rng));
    e.b.push_back(node(rng));  // Sometimes a[k] == b[k]: a zero length.
  }
  return e;
}

TEST(MeasureEdgesTest, EveryCountGivesTheFormulasBits) {
  for (int count = 0; count <= 13; ++count) {
    for (uint32_t seed = 1; seed <= 20; ++seed) {
      const Edges e = RandomEdges(6, count, seed * 101 + count);
      ExpectSame(Scalar(e), Fast(e));
    }
  }
}

TEST(MeasureEdgesTest, CoincidentNodesHaveZeroLengthAndAPositiveZeroDirection) {
  Edges e;
  e.x = {{1.5, -2.0}, {1.5, -2.0}, {4.0, 2.0}};
  e.a = {0, 0, 2, 1, 2};
  e.b = {1, 2, 2, 0, 0};
  const Measured got = Fast(e);
  ExpectSame(Scalar(e), got);
  for (int k : {0, 2, 3}) {
    EXPECT_EQ(Bits(got.length[k]), Bits(0.0));
    EXPECT_EQ(Bits(got.unit[k].x), Bits(0.0));
    EXPECT_EQ(Bits(got.unit[k].y), Bits(0.0));
  }
}

TEST(MeasureEdgesTest, TinyAndHugeLengthsKeepTheFormulasRounding) {
  Edges e;
  const double tiny = std::numeric_limits<double>::denorm_min();
  e.x = {
      {0.0, 0.0}, {tiny, 0.0}, {1e150, -1e150}, {3e-160, 4e-160}, {1e300, 0.0}};
  e.a = {0, 0, 0, 0, 1, 2, 0};
  e.b = {1, 2, 3, 4, 3, 4, 2};
  testing::FpTrapsOff traps_off;  // Underflow and overflow are the point.
  ExpectSame(Scalar(e), Fast(e));
}

// Raises the same floating-point exceptions as the formula, edge pair by
// edge pair: a NaN length's direction is (0, 0) without a division, and
// nothing divides by zero.
TEST(MeasureEdgesTest, NonFiniteCoordinatesGiveTheFormulasValuesAndFlags) {
  testing::FpTrapsOff traps_off;  // NaN and infinity on purpose.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Vec2> odd = {{nan, 0.0},  {0.0, nan},     {inf, 0.0},
                                 {-inf, inf}, {1e200, 1e200}, {0.0, 0.0}};
  for (size_t i = 0; i < odd.size(); ++i) {
    for (size_t j = 0; j < odd.size(); ++j) {
      Edges e;
      e.x = {{0.0, 0.0}, {1.0, 2.0}, odd[i], odd[j]};
      e.a = {0, 1, 0, 2};
      e.b = {2, 3, 1, 3};
      feclearexcept(FE_ALL_EXCEPT);
      const Measured want = Scalar(e);
      const int want_flags =
          fetestexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
      feclearexcept(FE_ALL_EXCEPT);
      const Measured got = Fast(e);
      const int got_flags =
          fetestexcept(FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
      SCOPED_TRACE(::testing::Message() << "odd " << i << ", " << j);
      ExpectSame(want, got);
      EXPECT_EQ(got_flags & FE_DIVBYZERO, 0);
      EXPECT_EQ(got_flags & ~want_flags, 0)
          << "raised " << got_flags << ", the formula " << want_flags;
    }
  }
}

}  // namespace
}  // namespace animat
