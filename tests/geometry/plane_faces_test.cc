// Tests of the faces of a plane graph (chambers and skin, docs/model.md §6.2)
// and of WalkArea.
#include "common/geometry/plane_faces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <ostream>
#include <random>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/base/status.h"
#include "common/base/vec2.h"
#include "common/geometry/gabriel.h"
#include "common/geometry/polygon.h"
#include "tests/geometry/point_source.h"

namespace animat {

namespace {

using testing::PointSource;

double Area(std::span<const Vec2> points, const std::vector<int>& walk) {
  return WalkArea(points.data(), std::span<const int>(walk));
}

IndexEdge Undirected(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// The walk rotated to its lexicographically least rotation, so walks can
// be compared whatever vertex they start at.
std::vector<int> LeastRotation(const std::vector<int>& walk) {
  std::vector<int> best = walk;
  std::vector<int> rotated = walk;
  for (size_t k = 1; k < walk.size(); ++k) {
    std::rotate(rotated.begin(), rotated.begin() + 1, rotated.end());
    best = std::min(best, rotated);
  }
  return best;
}

std::vector<std::vector<int>> SortedWalks(
    const std::vector<std::vector<int>>& walks) {
  std::vector<std::vector<int>> result;
  for (const std::vector<int>& walk : walks) {
    result.push_back(LeastRotation(walk));
  }
  std::sort(result.begin(), result.end());
  return result;
}

// Which edges are bridges: removing one disconnects the graph. By search
// from vertex 0 without each edge in turn, independent of the code under
// test. Precondition: the graph is connected.
std::vector<bool> Bridges(int n, std::span<const IndexEdge> edges) {
  std::vector<std::vector<std::pair<int, size_t>>> adjacent(n);
  for (size_t e = 0; e < edges.size(); ++e) {
    adjacent[edges[e].a].push_back({edges[e].b, e});
    adjacent[edges[e].b].push_back({edges[e].a, e});
  }
  std::vector<bool> bridge(edges.size(), false);
  std::vector<bool> seen(n);
  std::vector<int> stack;
  for (size_t skip = 0; skip < edges.size(); ++skip) {
    std::fill(seen.begin(), seen.end(), false);
    stack.assign(1, 0);
    seen[0] = true;
    int count = 1;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (const auto& [w, e] : adjacent[v]) {
        if (e != skip && !seen[w]) {
          seen[w] = true;
          ++count;
          stack.push_back(w);
        }
      }
    }
    bridge[skip] = count != n;
  }
  return bridge;
}

// Everything model §6 and plane_faces.h promise about a successful result.
void ExpectValidFaces(std::span<const Vec2> points,
                      std::span<const IndexEdge> edges,
                      const PlaneFaces& faces) {
  const int v = static_cast<int>(points.size());
  const int e = static_cast<int>(edges.size());

  // Euler for a connected plane graph: F = E - V + 2, one face outer.
  ASSERT_EQ(faces.bounded.size(), faces.bounded_area.size());
  EXPECT_EQ(static_cast<int>(faces.bounded.size()), e - v + 1);

  // Every directed half-edge is walked exactly once over all faces, so
  // every undirected edge occurs exactly twice in total.
  std::map<std::pair<int, int>, int> walked;
  for (const IndexEdge& edge : edges) {
    walked[{edge.a, edge.b}] = 0;
    walked[{edge.b, edge.a}] = 0;
  }
  // Faces each undirected edge borders: bounded index, or -1 for outer.
  std::map<IndexEdge, std::vector<int>> sides;
  auto walk_face = [&](const std::vector<int>& walk, int face) {
    for (size_t k = 0; k < walk.size(); ++k) {
      const int a = walk[k];
      const int b = walk[(k + 1) % walk.size()];
      const auto it = walked.find({a, b});
      if (it == walked.end()) {
        ADD_FAILURE() << "face " << face << " walks " << a << "->" << b
                      << ", not an edge";
        continue;
      }
      ++it->second;
      sides[Undirected(a, b)].push_back(face);
    }
  };
  for (size_t f = 0; f < faces.bounded.size(); ++f) {
    walk_face(faces.bounded[f], static_cast<int>(f));
  }
  walk_face(faces.outer, -1);
  for (const auto& [half_edge, count] : walked) {
    if (count != 1) {
      ADD_FAILURE() << half_edge.first << "->" << half_edge.second
                    << " is walked " << count << " times";
    }
  }

  // Chambers are counter-clockwise and tile the region inside the skin.
  double extent = 0.0;
  for (const Vec2& p : points) {
    extent = std::max(
        {extent, std::abs(p.x - points[0].x), std::abs(p.y - points[0].y)});
  }
  double total = 0.0;
  for (size_t f = 0; f < faces.bounded.size(); ++f) {
    EXPECT_GT(faces.bounded_area[f], 0.0) << "chamber " << f;
    EXPECT_EQ(faces.bounded_area[f], Area(points, faces.bounded[f]));
    total += faces.bounded_area[f];
  }
  EXPECT_EQ(faces.outer_area, Area(points, faces.outer));
  EXPECT_NEAR(total, -faces.outer_area,
              1e-12 * std::max(total, extent * extent));
  if (!faces.bounded.empty()) {
    EXPECT_LT(faces.outer_area, 0.0);
  }

  // The skin: the outer walk's edges, each once, sorted. A skin edge
  // borders one chamber, or none exactly when it is a bridge (the outer
  // walk passes it twice). Any edge bordering one face twice is a bridge.
  std::vector<IndexEdge> skin;
  for (size_t k = 0; k < faces.outer.size(); ++k) {
    skin.push_back(
        Undirected(faces.outer[k], faces.outer[(k + 1) % faces.outer.size()]));
  }
  std::sort(skin.begin(), skin.end());
  skin.erase(std::unique(skin.begin(), skin.end()), skin.end());
  EXPECT_EQ(faces.outer_edges, skin);
  const std::vector<bool> bridges = Bridges(v, edges);
  for (size_t i = 0; i < edges.size(); ++i) {
    const IndexEdge key = Undirected(edges[i].a, edges[i].b);
    const std::vector<int>& by = sides[key];
    ASSERT_EQ(by.size(), 2u) << ::testing::PrintToString(key);
    const int outer_count =
        static_cast<int>(std::count(by.begin(), by.end(), -1));
    const bool on_skin = std::binary_search(faces.outer_edges.begin(),
                                            faces.outer_edges.end(), key);
    // A bridge has one face on both sides; on the skin, that is the outer
    // face twice and no chamber, otherwise one chamber and the outer face.
    const bool ok = (by[0] == by[1]) == bridges[i] &&
                    on_skin == (outer_count > 0) &&
                    (!on_skin || outer_count == (bridges[i] ? 2 : 1));
    if (!ok) {
      ADD_FAILURE() << "edge " << ::testing::PrintToString(key)
                    << (bridges[i] ? " (a bridge)" : "") << " borders faces "
                    << by[0] << " and " << by[1] << " (-1: outer)"
                    << (on_skin ? ", on the skin" : ", not on the skin");
    }
  }
}

// The Gabriel graph of `points` and its faces, checked.
void ExpectValidGabrielFaces(std::span<const Vec2> points) {
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
}

void ExpectInvalid(std::span<const Vec2> points,
                   std::span<const IndexEdge> edges, const std::string& why) {
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_FALSE(faces.ok());
  EXPECT_EQ(faces.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(faces.status().message().find(why), std::string::npos)
      << faces.status().message();
}

TEST(PlaneFacesTest, ChambersOfRandomGabrielGraphsTileTheBody) {
  PointSource source(1234);
  for (int n = 2; n <= 40; ++n) {
    for (int set = 0; set < 2; ++set) {
      SCOPED_TRACE(::testing::Message() << "n=" << n << " set=" << set);
      ExpectValidGabrielFaces(source.InSquare(n));
    }
  }
}

TEST(PlaneFacesTest, ChambersOfGabrielGraphsWithTiesTileTheBody) {
  PointSource source(77);
  for (int n = 2; n <= 36; ++n) {
    for (int set = 0; set < 2; ++set) {
      SCOPED_TRACE(::testing::Message() << "n=" << n << " set=" << set);
      ExpectValidGabrielFaces(source.OnGrid(n, 6));
    }
  }
}

TEST(PlaneFacesTest, ChambersOfRegularPolygonsTileTheBody) {
  for (const int n : {3, 4, 5, 6, 8, 11, 16, 24}) {
    SCOPED_TRACE(n);
    std::vector<Vec2> points;
    for (int i = 0; i < n; ++i) {
      const double angle = 2.0 * std::numbers::pi * i / n;
      points.push_back({1.5 + std::cos(angle), -2.0 + std::sin(angle)});
    }
    ExpectValidGabrielFaces(points);
    // With the centre: a fan of triangles.
    points.push_back({1.5, -2.0});
    ExpectValidGabrielFaces(points);
  }
}

TEST(PlaneFacesTest, RectangleIsOneFourSidedChamber) {
  const std::vector<Vec2> points = {{0, 0}, {3, 0}, {3, 2}, {0, 2}};
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_EQ(SortedWalks(faces->bounded),
            (std::vector<std::vector<int>>{{0, 1, 2, 3}}));
  EXPECT_EQ(faces->bounded_area, std::vector<double>{6.0});
  EXPECT_EQ(LeastRotation(faces->outer), (std::vector<int>{0, 3, 2, 1}));
  EXPECT_EQ(faces->outer_area, -6.0);
  EXPECT_EQ(faces->outer_edges,
            (std::vector<IndexEdge>{{0, 1}, {0, 3}, {1, 2}, {2, 3}}));
}

TEST(PlaneFacesTest, SquareLatticeHasUnitChambers) {
  // 4 x 4 lattice, index 4 * row + column.
  std::vector<Vec2> points;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) {
      points.push_back({static_cast<double>(col), static_cast<double>(row)});
    }
  }
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  ASSERT_EQ(edges.size(), 24u);
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);

  std::vector<std::vector<int>> cells;
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      const int i = 4 * row + col;
      cells.push_back({i, i + 1, i + 5, i + 4});
    }
  }
  std::sort(cells.begin(), cells.end());
  EXPECT_EQ(SortedWalks(faces->bounded), cells);
  EXPECT_EQ(faces->bounded_area, std::vector<double>(9, 1.0));
  EXPECT_EQ(faces->outer_area, -9.0);
  EXPECT_EQ(faces->outer.size(), 12u);
  EXPECT_EQ(faces->outer_edges.size(), 12u);
}

TEST(PlaneFacesTest, PathHasNoChambersAndIsAllSkin) {
  // 32 collinear points, exactly representable, in scrambled order.
  std::vector<Vec2> points(32);
  for (int i = 0; i < 32; ++i) {
    const int slot = (i * 13) % 32;
    points[slot] = {2.0 + 3.0 * i, -1.0 + 2.0 * i};
  }
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  ASSERT_EQ(edges.size(), 31u);
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_TRUE(faces->bounded.empty());
  EXPECT_TRUE(faces->bounded_area.empty());
  EXPECT_EQ(faces->outer.size(), 62u);
  EXPECT_EQ(faces->outer_area, 0.0);
  EXPECT_EQ(faces->outer_edges, edges);
}

TEST(PlaneFacesTest, TreeHasNoChambersAndIsAllSkin) {
  // A star with a branch, exact coordinates.
  const std::vector<Vec2> points = {{0, 0},  {2, 0}, {0, 2},  {-2, 0},
                                    {0, -2}, {3, 1}, {-3, -1}};
  const std::vector<IndexEdge> edges = {{0, 1}, {0, 2}, {0, 3},
                                        {0, 4}, {1, 5}, {3, 6}};
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_TRUE(faces->bounded.empty());
  EXPECT_EQ(faces->outer.size(), 12u);
  EXPECT_EQ(faces->outer_area, 0.0);
  EXPECT_EQ(faces->outer_edges, edges);
}

TEST(PlaneFacesTest, TwoPointsGiveOneSkinEdgeAndNoChamber) {
  const std::vector<Vec2> points = {{1, 2}, {-3, 5}};
  const std::vector<IndexEdge> edges = {{0, 1}};
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_TRUE(faces->bounded.empty());
  EXPECT_EQ(LeastRotation(faces->outer), (std::vector<int>{0, 1}));
  EXPECT_EQ(faces->outer_area, 0.0);
  EXPECT_EQ(faces->outer_edges, edges);
}

TEST(PlaneFacesTest, DanglingEdgeAppearsTwiceInItsChamber) {
  // Triangle 0-1-2 with an edge from corner 0 to the interior point 3.
  const std::vector<Vec2> points = {{0, 0}, {4, 0}, {0, 4}, {1, 1}};
  const std::vector<IndexEdge> edges = {{0, 1}, {1, 2}, {0, 2}, {0, 3}};
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_EQ(SortedWalks(faces->bounded),
            (std::vector<std::vector<int>>{{0, 1, 2, 0, 3}}));
  EXPECT_EQ(faces->bounded_area, std::vector<double>{8.0});
  EXPECT_EQ(LeastRotation(faces->outer), (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(faces->outer_area, -8.0);
  EXPECT_EQ(faces->outer_edges,
            (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}}));
}

TEST(PlaneFacesTest, OutwardTailIsSkinAndBordersNoChamber) {
  // Triangle 0-1-2 with an edge from corner 1 out to point 3.
  const std::vector<Vec2> points = {{0, 0}, {4, 0}, {0, 4}, {6, -1}};
  const std::vector<IndexEdge> edges = {{0, 1}, {1, 2}, {0, 2}, {1, 3}};
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_EQ(SortedWalks(faces->bounded),
            (std::vector<std::vector<int>>{{0, 1, 2}}));
  EXPECT_EQ(faces->bounded_area, std::vector<double>{8.0});
  EXPECT_EQ(LeastRotation(faces->outer), (std::vector<int>{0, 2, 1, 3, 1}));
  EXPECT_EQ(faces->outer_area, -8.0);
  EXPECT_EQ(faces->outer_edges,
            (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}, {1, 3}}));
}

TEST(PlaneFacesTest, BarbellBridgeIsSkinAndBordersNoChamber) {
  // Triangles 0-1-2 and 3-4-5 joined by the bridge 1-3.
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {0, 1},
                                    {3, 0}, {4, 0}, {3, 1}};
  const std::vector<IndexEdge> edges = {{0, 1}, {0, 2}, {1, 2}, {1, 3},
                                        {3, 4}, {3, 5}, {4, 5}};
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_EQ(SortedWalks(faces->bounded),
            (std::vector<std::vector<int>>{{0, 1, 2}, {3, 4, 5}}));
  EXPECT_EQ(faces->bounded_area, (std::vector<double>{0.5, 0.5}));
  EXPECT_EQ(LeastRotation(faces->outer),
            (std::vector<int>{0, 2, 1, 3, 5, 4, 3, 1}));
  EXPECT_EQ(faces->outer_area, -1.0);
  EXPECT_EQ(faces->outer_edges, edges);
}

TEST(PlaneFacesTest, TrianglesSharingAVertexAreTwoChambers) {
  // Two triangles meeting at vertex 0 (a bow tie): no bridge, but the
  // outer walk passes vertex 0 twice.
  const std::vector<Vec2> points = {{0, 0}, {-2, -1}, {-2, 1}, {2, -1}, {2, 1}};
  const std::vector<IndexEdge> edges = {{0, 1}, {0, 2}, {1, 2},
                                        {0, 3}, {0, 4}, {3, 4}};
  const Result<PlaneFaces> faces = FacesOfPlaneGraph(points, edges);
  ASSERT_TRUE(faces.ok()) << faces.status().ToString();
  ExpectValidFaces(points, edges, *faces);
  EXPECT_EQ(SortedWalks(faces->bounded),
            (std::vector<std::vector<int>>{{0, 2, 1}, {0, 3, 4}}));
  EXPECT_EQ(faces->bounded_area, (std::vector<double>{2.0, 2.0}));
  EXPECT_EQ(LeastRotation(faces->outer), (std::vector<int>{0, 1, 2, 0, 4, 3}));
  EXPECT_EQ(faces->outer_area, -4.0);
  EXPECT_EQ(
      faces->outer_edges,
      (std::vector<IndexEdge>{{0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 2}, {3, 4}}));
}

TEST(PlaneFacesTest, FacesDoNotDependOnEdgeOrderOrDirection) {
  PointSource source(31);
  const std::vector<Vec2> points = source.InSquare(25);
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(points);
  std::vector<IndexEdge> scrambled = edges;
  std::mt19937_64 shuffle(8);
  std::shuffle(scrambled.begin(), scrambled.end(), shuffle);
  for (size_t i = 0; i < scrambled.size(); i += 2) {
    std::swap(scrambled[i].a, scrambled[i].b);
  }
  const Result<PlaneFaces> a = FacesOfPlaneGraph(points, edges);
  const Result<PlaneFaces> b = FacesOfPlaneGraph(points, scrambled);
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  ASSERT_TRUE(b.ok()) << b.status().ToString();
  ExpectValidFaces(points, scrambled, *b);
  EXPECT_EQ(a->bounded, b->bounded);
  EXPECT_EQ(a->bounded_area, b->bounded_area);
  EXPECT_EQ(a->outer, b->outer);
  EXPECT_EQ(a->outer_area, b->outer_area);
  EXPECT_EQ(a->outer_edges, b->outer_edges);
}

TEST(PlaneFacesTest, RejectsFewerThanTwoVertices) {
  ExpectInvalid({}, {}, "fewer than two");
  const std::vector<Vec2> one = {{1, 1}};
  ExpectInvalid(one, {}, "fewer than two");
}

TEST(PlaneFacesTest, RejectsDisconnectedGraph) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {5, 5}, {6, 5}};
  const std::vector<IndexEdge> two_pieces = {{0, 1}, {2, 3}};
  ExpectInvalid(points, two_pieces, "disconnected");
  const std::vector<IndexEdge> isolated_vertex = {{0, 1}, {1, 2}};
  ExpectInvalid(points, isolated_vertex, "disconnected");
  ExpectInvalid(std::span<const Vec2>(points).first(2), {}, "disconnected");
}

TEST(PlaneFacesTest, RejectsZeroLengthEdge) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {1, 0}};
  const std::vector<IndexEdge> edges = {{0, 1}, {1, 2}};
  ExpectInvalid(points, edges, "length 0");
  // The Gabriel graph joins coincident points.
  const std::vector<Vec2> cells = {{0, 0}, {3, 0}, {1, 2}, {3, 0}};
  ExpectInvalid(cells, PlaneGabrielGraph(cells), "length 0");
}

TEST(PlaneFacesTest, RejectsEdgeWithBadIndex) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {0, 1}};
  const std::vector<IndexEdge> out_of_range = {{0, 1}, {1, 3}};
  ExpectInvalid(points, out_of_range, "invalid");
  const std::vector<IndexEdge> negative = {{0, 1}, {-1, 2}};
  ExpectInvalid(points, negative, "invalid");
  const std::vector<IndexEdge> loop = {{0, 1}, {1, 2}, {2, 2}};
  ExpectInvalid(points, loop, "invalid");
}

TEST(PlaneFacesTest, RejectsSquareWithBothDiagonals) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<IndexEdge> edges = {{0, 1}, {1, 2}, {2, 3},
                                        {0, 3}, {0, 2}, {1, 3}};
  ExpectInvalid(points, edges, "not a plane graph");
}

TEST(PlaneFacesTest, RejectsSelfCrossingCycleWithNoArea) {
  // The 4-cycle 0-1-3-2 crosses itself in a symmetric bow tie: Euler's
  // count holds, but the would-be chamber has area 0.
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<IndexEdge> edges = {{0, 1}, {1, 3}, {2, 3}, {0, 2}};
  ExpectInvalid(points, edges, "not a plane graph");
}

TEST(WalkAreaTest, CounterClockwiseUnitSquareHasAreaOne) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(Area(points, {0, 1, 2, 3}), 1.0);
  EXPECT_EQ(Area(points, {2, 3, 0, 1}), 1.0);
}

TEST(WalkAreaTest, ClockwiseUnitSquareHasAreaMinusOne) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(Area(points, {0, 3, 2, 1}), -1.0);
  EXPECT_EQ(Area(points, {1, 0, 3, 2}), -1.0);
}

TEST(WalkAreaTest, WalksOfFewerThanThreeVerticesHaveNoArea) {
  const std::vector<Vec2> points = {{0, 0}, {1, 0}};
  EXPECT_EQ(Area(points, {}), 0.0);
  EXPECT_EQ(Area(points, {1}), 0.0);
  EXPECT_EQ(Area(points, {0, 1}), 0.0);
}

TEST(WalkAreaTest, DanglingEdgeAddsNoArea) {
  // Square 0-1-2-3 with point 4 inside, joined to corner 1.
  const std::vector<Vec2> points = {{0, 0}, {3, 0}, {3, 3}, {0, 3}, {2, 1}};
  EXPECT_EQ(Area(points, {0, 1, 2, 3}), 9.0);
  EXPECT_EQ(Area(points, {0, 1, 4, 1, 2, 3}), 9.0);
  EXPECT_EQ(Area(points, {4, 1, 2, 3, 0, 1}), 9.0);
  EXPECT_EQ(Area(points, {1, 4, 1, 2, 3, 0}), 9.0);

  // The same with coordinates that round: equal up to rounding.
  PointSource source(2);
  for (int trial = 0; trial < 100; ++trial) {
    const double r = source.Uniform(0.5, 2.0);
    std::vector<Vec2> p;
    for (int i = 0; i < 5; ++i) {
      const double angle =
          2.0 * std::numbers::pi * i / 5 + source.Uniform(0, 1);
      p.push_back({0.1 + r * std::cos(angle), 0.2 + r * std::sin(angle)});
    }
    p.push_back({0.1 + 0.3 * r, 0.2 - 0.1 * r});  // 5: inside, tied to 2
    const double polygon = Area(p, {0, 1, 2, 3, 4});
    const double tolerance =
        64 * std::numeric_limits<double>::epsilon() * r * r;
    EXPECT_GT(polygon, 0.0);
    EXPECT_NEAR(Area(p, {0, 1, 2, 5, 2, 3, 4}), polygon, tolerance);
    EXPECT_NEAR(Area(p, {5, 2, 3, 4, 0, 1, 2}), polygon, tolerance);
  }
}

TEST(WalkAreaTest, TranslationChangesAreaOnlyByRounding) {
  PointSource source(17);
  for (int trial = 0; trial < 100; ++trial) {
    // A convex polygon of 3 to 12 vertices, counter-clockwise.
    const int n = 3 + trial % 10;
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) {
      angles.push_back(source.Uniform(0, 2 * std::numbers::pi));
    }
    std::sort(angles.begin(), angles.end());
    std::vector<Vec2> points;
    std::vector<int> walk;
    for (int i = 0; i < n; ++i) {
      points.push_back({std::cos(angles[i]), std::sin(angles[i])});
      walk.push_back(i);
    }
    const double area = Area(points, walk);
    for (const Vec2 offset : {Vec2{1e6, -3e6}, Vec2{-12345.678, 98765.4321}}) {
      std::vector<Vec2> moved;
      for (const Vec2& p : points) moved.push_back(p + offset);
      // Each coordinate moves by at most half an ulp of the offset; the
      // area (diameter 2) changes by at most a few of those times n.
      const double ulp = std::max(std::abs(offset.x), std::abs(offset.y)) *
                         std::numeric_limits<double>::epsilon();
      EXPECT_NEAR(Area(moved, walk), area, 4.0 * n * ulp);
    }
  }
}

TEST(WalkAreaTest, AcceptsAnyIndexType) {
  const std::vector<Vec2> points = {{0, 0}, {2, 0}, {2, 3}};
  const std::vector<uint16_t> small = {0, 1, 2};
  const std::vector<size_t> large = {0, 2, 1};
  EXPECT_EQ(WalkArea(points.data(), std::span<const uint16_t>(small)), 3.0);
  EXPECT_EQ(WalkArea(points.data(), std::span<const size_t>(large)), -3.0);
}

}  // namespace
}  // namespace animat
