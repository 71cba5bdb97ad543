// Tests of the plane Gabriel graph and its predicates (docs/model.md §6).
//
// The reference is a brute force written from the model's words: i-j is an
// edge iff no other p has (px-cix)(px-cjx) + (py-ciy)(py-cjy) < 0, then
// every edge that properly crosses another is removed.
#include "common/geometry/gabriel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <ostream>
#include <random>
#include <span>
#include <vector>

#include "common/base/vec2.h"
#include "tests/geometry/point_source.h"

namespace animat {

namespace {

using testing::PointSource;

// Twice the signed area of a, b, c, written out independently of Orient.
double TwiceArea(Vec2 a, Vec2 b, Vec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

int Sign(double v) { return (v > 0.0) - (v < 0.0); }

// Each segment's endpoints strictly on opposite sides of the other's line.
bool ReferenceProperCross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return Sign(TwiceArea(a, b, c)) * Sign(TwiceArea(a, b, d)) < 0 &&
         Sign(TwiceArea(c, d, a)) * Sign(TwiceArea(c, d, b)) < 0;
}

std::vector<IndexEdge> BruteForcePlaneGabriel(std::span<const Vec2> p) {
  const int n = static_cast<int>(p.size());
  std::vector<IndexEdge> gabriel;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      bool blocked = false;
      for (int k = 0; k < n; ++k) {
        if (k == i || k == j) continue;
        if ((p[k].x - p[i].x) * (p[k].x - p[j].x) +
                (p[k].y - p[i].y) * (p[k].y - p[j].y) <
            0.0) {
          blocked = true;
        }
      }
      if (!blocked) gabriel.push_back({i, j});
    }
  }
  std::vector<IndexEdge> plane;
  for (const IndexEdge& e : gabriel) {
    bool crossed = false;
    for (const IndexEdge& f : gabriel) {
      if (ReferenceProperCross(p[e.a], p[e.b], p[f.a], p[f.b])) crossed = true;
    }
    if (!crossed) plane.push_back(e);
  }
  return plane;
}

// Sorted by (a, b), a < b, in range, and no two edges properly cross.
void ExpectSortedAndPlane(std::span<const Vec2> p,
                          const std::vector<IndexEdge>& edges) {
  const int n = static_cast<int>(p.size());
  for (const IndexEdge& e : edges) {
    if (!(0 <= e.a && e.a < e.b && e.b < n)) {
      ADD_FAILURE() << "bad edge " << ::testing::PrintToString(e);
    }
  }
  EXPECT_TRUE(std::is_sorted(edges.begin(), edges.end()));
  EXPECT_EQ(std::adjacent_find(edges.begin(), edges.end()), edges.end());
  for (size_t i = 0; i < edges.size(); ++i) {
    for (size_t j = i + 1; j < edges.size(); ++j) {
      const IndexEdge& e = edges[i];
      const IndexEdge& f = edges[j];
      if (ReferenceProperCross(p[e.a], p[e.b], p[f.a], p[f.b])) {
        ADD_FAILURE() << ::testing::PrintToString(e) << " crosses "
                      << ::testing::PrintToString(f);
      }
    }
  }
}

void ExpectMatchesBruteForce(std::span<const Vec2> points) {
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  EXPECT_EQ(edges, BruteForcePlaneGabriel(points));
  ExpectSortedAndPlane(points, edges);
}

// The polygon sides i-(i+1) of n points given in order around a circle.
std::vector<IndexEdge> Sides(int n) {
  std::vector<IndexEdge> sides;
  for (int i = 0; i + 1 < n; ++i) sides.push_back({i, i + 1});
  sides.push_back({0, n - 1});
  std::sort(sides.begin(), sides.end());
  return sides;
}

std::vector<Vec2> RegularPolygon(int n, Vec2 centre, double radius) {
  std::vector<Vec2> points;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / n + 0.1;
    points.push_back({centre.x + radius * std::cos(angle),
                      centre.y + radius * std::sin(angle)});
  }
  return points;
}

TEST(GabrielTest, InsideDiametralCircleIsStrict) {
  const Vec2 a{-1, 0};
  const Vec2 b{1, 0};
  EXPECT_TRUE(InsideDiametralCircle({0, 0}, a, b));
  EXPECT_TRUE(InsideDiametralCircle({0, 0.999}, a, b));
  EXPECT_TRUE(InsideDiametralCircle({0.5, -0.5}, a, b));
  // On the circle (exactly, in double): does not count.
  EXPECT_FALSE(InsideDiametralCircle({0, 1}, a, b));
  EXPECT_FALSE(InsideDiametralCircle({0, -1}, a, b));
  EXPECT_FALSE(InsideDiametralCircle({0.6, 0.8}, {0, 0}, {1.2, 0}));
  EXPECT_FALSE(InsideDiametralCircle(a, a, b));
  EXPECT_FALSE(InsideDiametralCircle(b, a, b));
  // Outside.
  EXPECT_FALSE(InsideDiametralCircle({0, 1.001}, a, b));
  EXPECT_FALSE(InsideDiametralCircle({2, 0}, a, b));
  // A degenerate circle (a == b) contains nothing, not even its centre.
  EXPECT_FALSE(InsideDiametralCircle(a, a, a));
}

TEST(GabrielTest, InsideDiametralCircleDoesNotDependOnEndpointOrder) {
  PointSource source(11);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec2 p{source.Uniform(-1, 1), source.Uniform(-1, 1)};
    const Vec2 a{source.Uniform(-1, 1), source.Uniform(-1, 1)};
    const Vec2 b{source.Uniform(-1, 1), source.Uniform(-1, 1)};
    EXPECT_EQ(InsideDiametralCircle(p, a, b), InsideDiametralCircle(p, b, a));
  }
}

TEST(GabrielTest, OrientIsPositiveCounterClockwise) {
  EXPECT_EQ(Orient({0, 0}, {1, 0}, {0, 1}), 1.0);
  EXPECT_EQ(Orient({0, 0}, {0, 1}, {1, 0}), -1.0);
  EXPECT_EQ(Orient({1, 1}, {3, 1}, {1, 4}), 6.0);
  EXPECT_EQ(Orient({0, 0}, {1, 1}, {3, 3}), 0.0);
}

TEST(GabrielTest, CrossingSegmentsCrossProperly) {
  const Vec2 a{0, 0}, b{2, 2}, c{0, 2}, d{2, 0};
  EXPECT_TRUE(SegmentsProperlyCross(a, b, c, d));
  EXPECT_TRUE(SegmentsProperlyCross(b, a, c, d));
  EXPECT_TRUE(SegmentsProperlyCross(a, b, d, c));
  EXPECT_TRUE(SegmentsProperlyCross(c, d, a, b));
  // Crossing near an end is still proper.
  EXPECT_TRUE(SegmentsProperlyCross({0, 0}, {4, 0}, {3.5, -1}, {3.75, 1}));
}

TEST(GabrielTest, SegmentsSharingAnEndpointDoNotCross) {
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {2, 0}, {0, 0}, {1, 3}));
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {2, 0}, {1, 3}, {2, 0}));
  // Sharing an endpoint and collinear, pointing opposite ways.
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {2, 0}, {2, 0}, {5, 0}));
  // The same segment.
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {2, 1}, {0, 0}, {2, 1}));
}

TEST(GabrielTest, TouchingSegmentsDoNotCross) {
  // T-junctions: the foot lies inside the bar, the other end of the stem
  // on either side; every order of segments and endpoints.
  const Vec2 a{0, 0}, b{4, 0}, foot{2, 0};
  for (const Vec2 top : {Vec2{2, 3}, Vec2{2, -3}, Vec2{1, 2}, Vec2{3, -1}}) {
    EXPECT_FALSE(SegmentsProperlyCross(a, b, foot, top));
    EXPECT_FALSE(SegmentsProperlyCross(a, b, top, foot));
    EXPECT_FALSE(SegmentsProperlyCross(b, a, foot, top));
    EXPECT_FALSE(SegmentsProperlyCross(b, a, top, foot));
    EXPECT_FALSE(SegmentsProperlyCross(foot, top, a, b));
    EXPECT_FALSE(SegmentsProperlyCross(top, foot, a, b));
    EXPECT_FALSE(SegmentsProperlyCross(foot, top, b, a));
    EXPECT_FALSE(SegmentsProperlyCross(top, foot, b, a));
  }
}

TEST(GabrielTest, CollinearOverlappingSegmentsDoNotCrossProperly) {
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {4, 0}, {1, 0}, {6, 0}));
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {4, 4}, {1, 1}, {2, 2}));
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {4, 0}, {5, 0}, {6, 0}));
}

TEST(GabrielTest, SegmentsWhoseLinesCrossElsewhereDoNotCross) {
  // The lines meet at (3, 0), outside the second segment.
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {4, 0}, {3, 1}, {3, 2}));
  // Parallel.
  EXPECT_FALSE(SegmentsProperlyCross({0, 0}, {4, 0}, {0, 1}, {4, 1}));
}

TEST(GabrielTest, FewerThanTwoPointsGiveNoEdges) {
  EXPECT_TRUE(PlaneGabrielGraph({}).empty());
  const std::vector<Vec2> one = {{3, 4}};
  EXPECT_TRUE(PlaneGabrielGraph(one).empty());
}

TEST(GabrielTest, TwoPointsGiveOneEdge) {
  const std::vector<Vec2> two = {{3, 4}, {-1, 2}};
  EXPECT_EQ(PlaneGabrielGraph(two), (std::vector<IndexEdge>{{0, 1}}));
}

TEST(GabrielTest, AcuteTriangleKeepsAllEdges) {
  const std::vector<Vec2> points = {{0, 0}, {4, 0}, {2, 3}};
  EXPECT_EQ(PlaneGabrielGraph(points),
            (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}}));
}

TEST(GabrielTest, ObtuseTriangleLosesItsLongestEdge) {
  const std::vector<Vec2> points = {{0, 0}, {4, 0}, {2, 1}};
  EXPECT_EQ(PlaneGabrielGraph(points),
            (std::vector<IndexEdge>{{0, 2}, {1, 2}}));
}

TEST(GabrielTest, RightTriangleKeepsItsHypotenuse) {
  // The right-angle vertex is on the hypotenuse's circle: not inside.
  const std::vector<Vec2> points = {{4, 0}, {0, 3}, {0, 0}};
  EXPECT_EQ(PlaneGabrielGraph(points),
            (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}}));
}

TEST(GabrielTest, MatchesBruteForceOnRandomTriangles) {
  PointSource source(3);
  for (int trial = 0; trial < 300; ++trial) {
    SCOPED_TRACE(trial);
    ExpectMatchesBruteForce(source.InSquare(3));
  }
}

TEST(GabrielTest, MatchesBruteForceOnRandomPoints) {
  PointSource source(20240611);
  for (int n = 2; n <= 40; ++n) {
    for (int set = 0; set < 3; ++set) {
      SCOPED_TRACE(::testing::Message() << "n=" << n << " set=" << set);
      ExpectMatchesBruteForce(source.InSquare(n));
    }
  }
}

TEST(GabrielTest, MatchesBruteForceOnIntegerPointsWithTies) {
  PointSource source(7);
  for (int n = 3; n <= 36; ++n) {
    for (int set = 0; set < 2; ++set) {
      SCOPED_TRACE(::testing::Message() << "n=" << n << " set=" << set);
      ExpectMatchesBruteForce(source.OnGrid(n, 7));
    }
  }
  // Every point of the grid: all unit squares cocircular at once.
  ExpectMatchesBruteForce(source.OnGrid(36, 6));
}

TEST(GabrielTest, CollinearPointsGiveAPath) {
  // 32 points on the line (3s, 1 - 2s), exactly representable, irregular
  // spacing, in shuffled order.
  std::vector<double> s;
  for (int i = 0; i < 32; ++i) {
    s.push_back(i + 0.25 * (i % 3) + (i > 20 ? 7 : 0));
  }
  std::vector<int> order(32);
  for (int i = 0; i < 32; ++i) order[i] = i;
  std::mt19937_64 shuffle(99);
  std::shuffle(order.begin(), order.end(), shuffle);
  std::vector<Vec2> points(32);
  for (int i = 0; i < 32; ++i) {
    points[order[i]] = {3.0 * s[i], 1.0 - 2.0 * s[i]};
  }
  std::vector<IndexEdge> expected;
  for (int i = 0; i + 1 < 32; ++i) {
    expected.push_back(
        {std::min(order[i], order[i + 1]), std::max(order[i], order[i + 1])});
  }
  std::sort(expected.begin(), expected.end());

  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  EXPECT_EQ(edges.size(), 31u);
  EXPECT_EQ(edges, expected);
  EXPECT_EQ(edges, BruteForcePlaneGabriel(points));
}

TEST(GabrielTest, HorizontalLineGivesAPath) {
  std::vector<Vec2> points;
  for (int i = 0; i < 32; ++i) points.push_back({static_cast<double>(i), 5.0});
  std::vector<IndexEdge> expected;
  for (int i = 0; i + 1 < 32; ++i) expected.push_back({i, i + 1});
  EXPECT_EQ(PlaneGabrielGraph(points), expected);
}

TEST(GabrielTest, RectangleKeepsItsSidesAndLosesItsDiagonals) {
  // Each diagonal's circle passes through the other two corners, so both
  // diagonals are Gabriel edges; they cross, so both go.
  const std::vector<Vec2> points = {{0, 0}, {3, 0}, {3, 2}, {0, 2}};
  EXPECT_EQ(PlaneGabrielGraph(points), Sides(4));
  ExpectMatchesBruteForce(points);
}

TEST(GabrielTest, RotatedSquareKeepsItsSidesAndLosesItsDiagonals) {
  const std::vector<Vec2> points = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  EXPECT_EQ(PlaneGabrielGraph(points), Sides(4));
}

TEST(GabrielTest, SquareLatticeKeepsOnlyGridEdges) {
  for (const double spacing : {1.0, 0.5, 3.0}) {
    SCOPED_TRACE(spacing);
    // 4 x 4 lattice, point index 4 * row + column; every unit square is
    // cocircular, so its two diagonals are Gabriel edges that cross.
    std::vector<Vec2> points;
    for (int row = 0; row < 4; ++row) {
      for (int col = 0; col < 4; ++col) {
        points.push_back({spacing * col - 7.0, spacing * row + 2.0});
      }
    }
    std::vector<IndexEdge> expected;
    for (int row = 0; row < 4; ++row) {
      for (int col = 0; col < 4; ++col) {
        const int i = 4 * row + col;
        if (col + 1 < 4) expected.push_back({i, i + 1});
        if (row + 1 < 4) expected.push_back({i, i + 4});
      }
    }
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(expected.size(), 24u);
    EXPECT_EQ(PlaneGabrielGraph(points), expected);
    ExpectMatchesBruteForce(points);
  }
}

TEST(GabrielTest, IntegerPointsOnACircleGiveThePolygon) {
  // All 12 integer points on the circle of radius 5, in angular order:
  // exactly cocircular, so the 6 diameters are Gabriel edges that all cross
  // at the centre and every other chord has a point inside its circle.
  const std::vector<Vec2> points = {{5, 0},   {4, 3},  {3, 4},  {0, 5},
                                    {-3, 4},  {-4, 3}, {-5, 0}, {-4, -3},
                                    {-3, -4}, {0, -5}, {3, -4}, {4, -3}};
  EXPECT_EQ(PlaneGabrielGraph(points), Sides(12));
  ExpectMatchesBruteForce(points);
}

TEST(GabrielTest, OddRegularPolygonGivesItsSides) {
  // No diameters, and every longer chord has a point well inside its
  // circle, so rounding of cos and sin cannot matter.
  for (const int n : {3, 5, 7, 9, 15, 31}) {
    SCOPED_TRACE(n);
    const std::vector<Vec2> points = RegularPolygon(n, {2.5, -1.25}, 3.0);
    EXPECT_EQ(PlaneGabrielGraph(points), Sides(n));
    ExpectMatchesBruteForce(points);
  }
}

TEST(GabrielTest, EvenRegularPolygonMatchesBruteForce) {
  // Diameters have the other points on their circle up to rounding, so
  // which survive depends on the bits; the sides always do.
  for (const int n : {4, 6, 8, 12, 16, 24, 40}) {
    SCOPED_TRACE(n);
    const std::vector<Vec2> points = RegularPolygon(n, {0.3, 0.7}, 1.7);
    const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
    for (const IndexEdge& side : Sides(n)) {
      EXPECT_TRUE(std::binary_search(edges.begin(), edges.end(), side))
          << ::testing::PrintToString(side);
    }
    ExpectMatchesBruteForce(points);
  }
}

TEST(GabrielTest, PointsOnACircleWithCentreKeepTheSpokes) {
  // The centre lies strictly inside each diameter's circle, so the
  // diameters go; no other point is inside a spoke's circle.
  std::vector<Vec2> points = {{0, 0}};
  const std::vector<Vec2> rim = {{5, 0}, {0, 5},  {-5, 0},  {0, -5},
                                 {3, 4}, {-4, 3}, {-3, -4}, {4, -3}};
  points.insert(points.end(), rim.begin(), rim.end());
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  for (int i = 1; i <= 8; ++i) {
    EXPECT_TRUE(std::binary_search(edges.begin(), edges.end(), IndexEdge{0, i}))
        << i;
  }
  ExpectMatchesBruteForce(points);
}

TEST(GabrielTest, CoincidentPointsGiveAZeroLengthEdge) {
  // Documented: coincident points are the caller's concern.
  const std::vector<Vec2> points = {{1, 1}, {4, 1}, {1, 1}};
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  EXPECT_TRUE(std::binary_search(edges.begin(), edges.end(), IndexEdge{0, 2}));
  EXPECT_EQ(edges, BruteForcePlaneGabriel(points));
}

// Regression: rounding made nearly collinear, disjoint segments "cross",
// which removed path edges and disconnected a line of cells.
TEST(GabrielTest, NearlyCollinearDisjointSegmentsDoNotCross) {
  const std::vector<Vec2> p = {{0x1.20cb7e0219968p-2, -0x1.77961586ac569p-1},
                               {-0x1.74775c88817fp-3, -0x1.99940774dfc27p+0},
                               {-0x1.cbb496dc2dd7bp+0, -0x1.2749c7632ae0cp+2},
                               {-0x1.20ea3f21e81dp+1, -0x1.5e7070fdeb518p+2}};
  EXPECT_FALSE(SegmentsProperlyCross(p[0], p[1], p[2], p[3]));
  EXPECT_EQ(PlaneGabrielGraph(p),
            (std::vector<IndexEdge>{{0, 1}, {1, 2}, {2, 3}}));
}

TEST(GabrielTest, LinesOfCellsAtAnyAngleStayPaths) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(0.0, 6.283185307179586);
  std::uniform_real_distribution<double> step(0.5, 2.0);
  for (int trial = 0; trial < 300; ++trial) {
    const double a = angle(rng);
    const Vec2 dir{std::cos(a), std::sin(a)};
    std::vector<Vec2> points;
    double t = 0.0;
    for (int i = 0; i < 32; ++i) {
      points.push_back(dir * t);
      t += step(rng);
    }
    const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
    ASSERT_EQ(edges.size(), 31u) << "trial " << trial;
    for (int i = 0; i < 31; ++i) {
      EXPECT_EQ(edges[i], (IndexEdge{i, i + 1})) << "trial " << trial;
    }
  }
}

TEST(GabrielTest, OrientSignIsZeroOnlyWhenRoundingCouldDecide) {
  EXPECT_EQ(OrientSign({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(OrientSign({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(OrientSign({0, 0}, {1, 1}, {2, 2}), 0);
  EXPECT_EQ(OrientSign({0, 0}, {1, 1}, {2, 2.000001}), 1);
}

}  // namespace
}  // namespace animat
