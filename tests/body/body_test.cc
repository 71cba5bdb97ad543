// Tests of the soft body built on the cell centres (docs/model.md §6).
//
// The references are written from the model's words, not from the code:
// springs are the Gabriel graph (i-j iff no other p has
// (px-cix)(px-cjx) + (py-ciy)(py-cjy) < 0) with every properly crossing
// edge removed; chambers are the bounded faces, counter-clockwise, with their
// true area; the skin is the edges on the outer face, each once.
#include "common/body/body.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <ostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "common/base/status.h"
#include "common/base/vec2.h"
#include "common/geometry/gabriel.h"

namespace animat {

// Lets gtest print edges in failure messages (found by ADL).
inline void PrintTo(const IndexEdge& e, std::ostream* os) {
  *os << e.a << "-" << e.b;
}
inline void PrintTo(const Vec2& v, std::ostream* os) {
  *os << "(" << v.x << ", " << v.y << ")";
}

namespace {

// Fixed-seed numbers; the double recipe (53 high bits) is written out so the
// sets are the same with every standard library.
class Source {
 public:
  explicit Source(uint64_t seed) : engine_(seed) {}
  double Uniform(double lo, double hi) {
    const double u = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * u;
  }
  int Int(int lo, int hi) {  // In [lo, hi].
    return lo +
           static_cast<int>(engine_() % static_cast<uint64_t>(hi - lo + 1));
  }

 private:
  std::mt19937_64 engine_;
};

// n points in [0, side)^2, no two closer than `gap`.
std::vector<Vec2> RandomCentres(Source& source, int n, double side,
                                double gap) {
  std::vector<Vec2> points;
  while (static_cast<int>(points.size()) < n) {
    const Vec2 p{source.Uniform(0, side), source.Uniform(0, side)};
    bool far = true;
    for (const Vec2& q : points) far = far && Length(p - q) >= gap;
    if (far) points.push_back(p);
  }
  return points;
}

// Signed area of a closed walk by the shoelace formula (sum of x_k y_{k+1} -
// x_{k+1} y_k), written independently of the code under test.
double ShoelaceArea(const std::vector<Vec2>& p, const std::vector<int>& walk) {
  double twice = 0.0;
  for (size_t k = 0; k < walk.size(); ++k) {
    const Vec2 a = p[walk[k]];
    const Vec2 b = p[walk[(k + 1) % walk.size()]];
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * twice;
}

// The spring rule of model §6.1, brute force.
std::vector<IndexEdge> ReferenceSprings(const std::vector<Vec2>& c) {
  const int n = static_cast<int>(c.size());
  std::vector<IndexEdge> gabriel;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      bool empty = true;
      for (int k = 0; k < n; ++k) {
        if (k == i || k == j) continue;
        const Vec2 p = c[k];
        if ((p.x - c[i].x) * (p.x - c[j].x) + (p.y - c[i].y) * (p.y - c[j].y) <
            0.0) {
          empty = false;
        }
      }
      if (empty) gabriel.push_back({i, j});
    }
  }
  auto side = [](Vec2 a, Vec2 b, Vec2 p) {
    const double o = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    return o > 0.0 ? 1 : (o < 0.0 ? -1 : 0);
  };
  std::vector<IndexEdge> plane;
  for (const IndexEdge& e : gabriel) {
    bool crossed = false;
    for (const IndexEdge& f : gabriel) {
      if (e.a == f.a || e.a == f.b || e.b == f.a || e.b == f.b) continue;
      const Vec2 a = c[e.a], b = c[e.b], p = c[f.a], q = c[f.b];
      if (side(a, b, p) * side(a, b, q) < 0 &&
          side(p, q, a) * side(p, q, b) < 0)
        crossed = true;
    }
    if (!crossed) plane.push_back(e);
  }
  return plane;
}

std::vector<IndexEdge> SpringEdges(const Body& body) {
  std::vector<IndexEdge> edges;
  for (const Spring& s : body.springs) {
    edges.push_back({std::min(s.a, s.b), std::max(s.a, s.b)});
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

std::vector<IndexEdge> SortedSkin(const Body& body) {
  std::vector<IndexEdge> skin;
  for (const IndexEdge& e : body.skin) {
    skin.push_back({std::min(e.a, e.b), std::max(e.a, e.b)});
  }
  std::sort(skin.begin(), skin.end());
  return skin;
}

// The lexicographically least rotation of a cyclic walk, so walks compare
// whatever vertex they start at.
std::vector<int> CanonicalCycle(const std::vector<int>& walk) {
  std::vector<int> best = walk;
  for (size_t r = 1; r < walk.size(); ++r) {
    std::vector<int> rotated(walk.begin() + r, walk.end());
    rotated.insert(rotated.end(), walk.begin(), walk.begin() + r);
    best = std::min(best, rotated);
  }
  return best;
}

// True when `message` contains `number` as a whole number (not as a digit
// of a longer one).
bool NamesNumber(const std::string& message, int number) {
  const std::string s = std::to_string(number);
  for (size_t at = message.find(s); at != std::string::npos;
       at = message.find(s, at + 1)) {
    const bool left = at == 0 || !std::isdigit(message[at - 1]);
    const size_t end = at + s.size();
    const bool right = end == message.size() || !std::isdigit(message[end]);
    if (left && right) return true;
  }
  return false;
}

Body MustBuild(const std::vector<Vec2>& centres) {
  Result<Body> body = BuildBody(centres);
  EXPECT_TRUE(body.ok()) << body.status().ToString();
  return body.ok() ? std::move(body).value() : Body{};
}

// Checks that apply to every body: springs are the plane Gabriel graph with
// a < b, rest lengths are the edge lengths, chambers run counter-clockwise
// with their true area, and every side of every spring lies in exactly one
// face: a chamber (each direction at most once) or the outer face (the skin).
void ExpectWellFormed(const std::vector<Vec2>& c, const Body& body) {
  ASSERT_EQ(body.nodes(), static_cast<int>(c.size()));
  for (int i = 0; i < body.nodes(); ++i) EXPECT_EQ(body.position[i], c[i]);
  EXPECT_EQ(SpringEdges(body), ReferenceSprings(c));
  for (const Spring& s : body.springs) {
    EXPECT_LT(s.a, s.b);
    EXPECT_EQ(s.rest_length, Length(c[s.b] - c[s.a]))
        << "spring " << s.a << "-" << s.b;
  }
  // Directed sides used by chambers.
  std::map<std::pair<int, int>, int> used;
  for (const Chamber& ch : body.chambers) {
    ASSERT_GE(ch.walk.size(), 3u);
    const double area = ShoelaceArea(c, ch.walk);
    EXPECT_GT(area, 0.0) << "chamber not counter-clockwise";
    EXPECT_NEAR(ch.rest_area, area, 1e-12 * (1.0 + std::fabs(area)));
    for (size_t k = 0; k < ch.walk.size(); ++k) {
      ++used[{ch.walk[k], ch.walk[(k + 1) % ch.walk.size()]}];
    }
  }
  const std::vector<IndexEdge> springs = SpringEdges(body);
  std::vector<IndexEdge> expected_skin;
  for (const IndexEdge& e : springs) {
    const int forward = used.count({e.a, e.b}) ? used[{e.a, e.b}] : 0;
    const int backward = used.count({e.b, e.a}) ? used[{e.b, e.a}] : 0;
    EXPECT_LE(forward, 1) << e.a << "->" << e.b << " in two chambers";
    EXPECT_LE(backward, 1) << e.b << "->" << e.a << " in two chambers";
    if (forward + backward < 2) expected_skin.push_back(e);
  }
  size_t sides = 0;
  for (const auto& [side, count] : used) sides += count;
  // Chambers walk only springs.
  for (const auto& [side, count] : used) {
    const IndexEdge e{std::min(side.first, side.second),
                      std::max(side.first, side.second)};
    EXPECT_TRUE(std::binary_search(springs.begin(), springs.end(), e))
        << side.first << "->" << side.second << " is not a spring";
  }
  EXPECT_LE(sides, 2 * springs.size());
  EXPECT_EQ(SortedSkin(body), expected_skin);
  // "Each counted once".
  std::vector<IndexEdge> skin = SortedSkin(body);
  EXPECT_EQ(std::adjacent_find(skin.begin(), skin.end()), skin.end());
}

TEST(BodyTest, TriangleIsThreeSpringsAndOneCounterClockwiseChamber) {
  // Acute triangle: every edge is Gabriel. Given clockwise, so the chamber
  // must be reordered.
  const std::vector<Vec2> c = {{0, 0}, {1, 3}, {4, 0}};
  const Body body = MustBuild(c);
  ExpectWellFormed(c, body);
  EXPECT_EQ(SpringEdges(body),
            (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}}));
  ASSERT_EQ(body.chambers.size(), 1u);
  EXPECT_EQ(CanonicalCycle(body.chambers[0].walk),
            (std::vector<int>{0, 2, 1}));             // Counter-clockwise.
  EXPECT_DOUBLE_EQ(body.chambers[0].rest_area, 6.0);  // 4 * 3 / 2.
  EXPECT_EQ(SortedSkin(body), (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}}));
  std::map<std::pair<int, int>, double> length;
  for (const Spring& s : body.springs) length[{s.a, s.b}] = s.rest_length;
  EXPECT_DOUBLE_EQ((length[{0, 1}]), std::sqrt(10.0));
  EXPECT_DOUBLE_EQ((length[{0, 2}]), 4.0);
  EXPECT_DOUBLE_EQ((length[{1, 2}]), std::sqrt(18.0));
}

TEST(BodyTest, TwoCellsAreOneSpringOfSkin) {
  const std::vector<Vec2> c = {{1, 1}, {4, 5}};
  const Body body = MustBuild(c);
  ExpectWellFormed(c, body);
  ASSERT_EQ(body.springs.size(), 1u);
  EXPECT_DOUBLE_EQ(body.springs[0].rest_length, 5.0);
  EXPECT_TRUE(body.chambers.empty());
  EXPECT_EQ(SortedSkin(body), (std::vector<IndexEdge>{{0, 1}}));
}

TEST(BodyTest, CollinearCellsFormAPathWithoutChamber) {
  // The middle cell lies inside the circle on 0-2: (1-0)(1-2.5) < 0.
  const std::vector<Vec2> c = {{0, 0}, {2.5, 0}, {1, 0}};
  const Body body = MustBuild(c);
  ExpectWellFormed(c, body);
  EXPECT_EQ(SpringEdges(body), (std::vector<IndexEdge>{{0, 2}, {1, 2}}));
  EXPECT_TRUE(body.chambers.empty());
  EXPECT_EQ(SortedSkin(body), (std::vector<IndexEdge>{{0, 2}, {1, 2}}));
}

TEST(BodyTest, RectangleLosesItsCrossingDiagonalsAndIsOneFourSidedChamber) {
  // Cocircular: each diagonal has the other corners exactly on its circle,
  // so both are Gabriel edges; they cross and are both removed.
  const std::vector<Vec2> c = {{0, 0}, {3, 0}, {3, 2}, {0, 2}};
  const Body body = MustBuild(c);
  ExpectWellFormed(c, body);
  EXPECT_EQ(SpringEdges(body),
            (std::vector<IndexEdge>{{0, 1}, {0, 3}, {1, 2}, {2, 3}}));
  ASSERT_EQ(body.chambers.size(), 1u);
  EXPECT_EQ(CanonicalCycle(body.chambers[0].walk),
            (std::vector<int>{0, 1, 2, 3}));
  EXPECT_DOUBLE_EQ(body.chambers[0].rest_area, 6.0);
  EXPECT_EQ(SortedSkin(body),
            (std::vector<IndexEdge>{{0, 1}, {0, 3}, {1, 2}, {2, 3}}));
}

TEST(BodyTest, DanglingEdgeOutsideIsSkinButNoChamber) {
  // Triangle 0, 1, 2 and a far cell 3 above the apex 2: the apex lies
  // inside the circles on 3-0 and 3-1 ((1-1)(1-0) + (1.5-4)(1.5-0) < 0),
  // so 3 hangs from 2 alone.
  const std::vector<Vec2> c = {{0, 0}, {2, 0}, {1, 1.5}, {1, 4}};
  const Body body = MustBuild(c);
  ExpectWellFormed(c, body);
  EXPECT_EQ(SpringEdges(body),
            (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}, {2, 3}}));
  ASSERT_EQ(body.chambers.size(), 1u);
  EXPECT_EQ(CanonicalCycle(body.chambers[0].walk), (std::vector<int>{0, 1, 2}));
  EXPECT_DOUBLE_EQ(body.chambers[0].rest_area, 1.5);
  EXPECT_EQ(SortedSkin(body),
            (std::vector<IndexEdge>{{0, 1}, {0, 2}, {1, 2}, {2, 3}}));
}

TEST(BodyTest, BridgeBetweenTwoChambersIsSkin) {
  // Two triangles, apex to apex, joined by the bridge 2-3.
  const std::vector<Vec2> c = {{0, 0}, {2, 0},   {1, 1.5},
                               {1, 4}, {0, 5.5}, {2, 5.5}};
  const Body body = MustBuild(c);
  ExpectWellFormed(c, body);
  const std::vector<IndexEdge> all = {{0, 1}, {0, 2}, {1, 2}, {2, 3},
                                      {3, 4}, {3, 5}, {4, 5}};
  EXPECT_EQ(SpringEdges(body), all);
  ASSERT_EQ(body.chambers.size(), 2u);
  std::vector<std::vector<int>> walks;
  for (const Chamber& ch : body.chambers) {
    walks.push_back(CanonicalCycle(ch.walk));
    EXPECT_DOUBLE_EQ(ch.rest_area, 1.5);
  }
  std::sort(walks.begin(), walks.end());
  EXPECT_EQ(walks, (std::vector<std::vector<int>>{{0, 1, 2}, {3, 5, 4}}));
  EXPECT_EQ(SortedSkin(body), all);  // Every edge, the bridge once.
}

TEST(BodyTest, EdgeDanglingIntoAChamberIsWalkedTwiceAndAddsNoArea) {
  // A ring 3-4-5-6-1-2 with cell 0 inside, hanging from 3 alone (found by
  // a search; checked against the Gabriel rule below).
  const std::vector<Vec2> c = {{8, 7}, {5.5, 0},  {9, 5.5}, {8.5, 7},
                               {9, 8}, {7.5, 10}, {0, 9.5}};
  const Body body = MustBuild(c);
  ExpectWellFormed(c, body);
  EXPECT_EQ(SpringEdges(body),
            (std::vector<IndexEdge>{
                {0, 3}, {1, 2}, {1, 6}, {2, 3}, {3, 4}, {4, 5}, {5, 6}}));
  ASSERT_EQ(body.chambers.size(), 1u);
  EXPECT_EQ(CanonicalCycle(body.chambers[0].walk),
            (std::vector<int>{0, 3, 4, 5, 6, 1, 2, 3}));
  const double ring = ShoelaceArea(c, {3, 4, 5, 6, 1, 2});
  EXPECT_DOUBLE_EQ(ring, 50.25);
  EXPECT_DOUBLE_EQ(body.chambers[0].rest_area, ring);
  EXPECT_EQ(
      SortedSkin(body),
      (std::vector<IndexEdge>{{1, 2}, {1, 6}, {2, 3}, {3, 4}, {4, 5}, {5, 6}}));
}

TEST(BodyTest, RandomBodiesAreWellFormed) {
  Source source(20240611);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = source.Int(2, 24);
    const std::vector<Vec2> c = RandomCentres(source, n, 10.0, 0.3);
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Body body = MustBuild(c);
    ExpectWellFormed(c, body);
  }
}

TEST(BodyTest, GridBodiesWithCocircularCellsAreWellFormed) {
  // Integer grids are full of cocircular quadruples.
  Source source(77);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<Vec2> grid;
    for (int x = 0; x < 6; ++x) {
      for (int y = 0; y < 6; ++y) {
        grid.push_back({static_cast<double>(x), static_cast<double>(y)});
      }
    }
    for (int i = static_cast<int>(grid.size()) - 1; i > 0; --i) {
      std::swap(grid[i], grid[source.Int(0, i)]);
    }
    grid.resize(source.Int(2, 20));
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Body body = MustBuild(grid);
    ExpectWellFormed(grid, body);
  }
}

// The area enclosed by the skin, from the skin alone: drop the skin edges
// that are bridges of the spring graph (they enclose nothing); the rest
// bound the enclosed region. Orient each so the region is on its left,
// deciding the side by an even-odd ray test, and sum the shoelace terms.
double AreaEnclosedBySkin(const std::vector<Vec2>& c, const Body& body) {
  const std::vector<IndexEdge> springs = SpringEdges(body);
  const int n = body.nodes();
  auto connected_without = [&](const IndexEdge& cut) {
    std::vector<std::vector<int>> adj(n);
    for (const IndexEdge& e : springs) {
      if (e == cut) continue;
      adj[e.a].push_back(e.b);
      adj[e.b].push_back(e.a);
    }
    std::vector<bool> seen(n, false);
    std::vector<int> stack = {cut.a};
    seen[cut.a] = true;
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (int w : adj[v]) {
        if (!seen[w]) {
          seen[w] = true;
          stack.push_back(w);
        }
      }
    }
    return static_cast<bool>(seen[cut.b]);
  };
  std::vector<IndexEdge> boundary;
  for (const IndexEdge& e : SortedSkin(body)) {
    if (connected_without(e)) boundary.push_back(e);
  }
  // Even-odd test with a ray in a direction no edge is parallel to.
  const Vec2 dir{std::cos(0.7123), std::sin(0.7123)};
  auto inside = [&](Vec2 p) {
    int crossings = 0;
    for (const IndexEdge& e : boundary) {
      const Vec2 a = c[e.a] - p;
      const Vec2 b = c[e.b] - p;
      const double sa = Cross(dir, a);
      const double sb = Cross(dir, b);
      if ((sa > 0) == (sb > 0)) continue;
      // Ray parameter of the crossing: p + t dir on segment a-b.
      const double t = Cross(a, b - a) / Cross(dir, b - a);
      if (t > 0) ++crossings;
    }
    return crossings % 2 == 1;
  };
  double twice = 0.0;
  for (const IndexEdge& e : boundary) {
    const Vec2 a = c[e.a];
    const Vec2 b = c[e.b];
    const Vec2 mid = (a + b) * 0.5;
    const Vec2 left = Vec2{-(b.y - a.y), b.x - a.x} * 1e-6;
    const bool in_left = inside(mid + left);
    EXPECT_NE(in_left, inside(mid - left))
        << "skin edge " << e.a << "-" << e.b << " does not bound";
    twice += in_left ? Cross(a, b) : Cross(b, a);
  }
  return 0.5 * twice;
}

TEST(BodyTest, ChamberAreasSumToTheAreaEnclosedByTheSkin) {
  Source source(99);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = source.Int(2, 20);
    const std::vector<Vec2> c = RandomCentres(source, n, 10.0, 0.3);
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Body body = MustBuild(c);
    double sum = 0.0;
    for (const Chamber& ch : body.chambers) sum += ch.rest_area;
    const double enclosed = AreaEnclosedBySkin(c, body);
    EXPECT_NEAR(sum, enclosed, 1e-9 * (1.0 + enclosed));
  }
  // And on the hand-made shapes.
  for (const std::vector<Vec2>& c : std::vector<std::vector<Vec2>>{
           {{0, 0}, {3, 0}, {3, 2}, {0, 2}},
           {{0, 0}, {2, 0}, {1, 1.5}, {1, 4}, {0, 5.5}, {2, 5.5}},
           {{8, 7},
            {5.5, 0},
            {9, 5.5},
            {8.5, 7},
            {9, 8},
            {7.5, 10},
            {0, 9.5}}}) {
    const Body body = MustBuild(c);
    double sum = 0.0;
    for (const Chamber& ch : body.chambers) sum += ch.rest_area;
    EXPECT_NEAR(sum, AreaEnclosedBySkin(c, body), 1e-12);
  }
}

TEST(BodyTest, RestLengthsAreEdgeLengthsAtAnyScale) {
  Source source(5);
  for (int trial = 0; trial < 20; ++trial) {
    const double scale = std::pow(10.0, source.Uniform(-3, 3));
    std::vector<Vec2> c = RandomCentres(source, source.Int(3, 15), 1.0, 0.05);
    for (Vec2& p : c) p = p * scale;
    const Body body = MustBuild(c);
    ASSERT_FALSE(body.springs.empty());
    for (const Spring& s : body.springs) {
      const double dx = c[s.b].x - c[s.a].x;
      const double dy = c[s.b].y - c[s.a].y;
      EXPECT_EQ(s.rest_length, std::sqrt(dx * dx + dy * dy));
    }
  }
}

TEST(BodyTest, CoincidentCentresFailNamingBothCells) {
  // Cells 2 and 4 are 0.58e-9 apart.
  const std::vector<Vec2> c = {
      {0, 0}, {1, 1}, {5, 0}, {2, 4}, {5 + 0.5e-9, 0.3e-9}};
  Result<Body> body = BuildBody(c);
  ASSERT_FALSE(body.ok());
  EXPECT_EQ(body.status().code(), StatusCode::kInvalidArgument);
  const std::string& message = body.status().message();
  EXPECT_TRUE(NamesNumber(message, 2)) << message;
  EXPECT_TRUE(NamesNumber(message, 4)) << message;
  EXPECT_FALSE(NamesNumber(message, 0)) << message;
  EXPECT_FALSE(NamesNumber(message, 3)) << message;

  // Identical centres.
  Result<Body> same = BuildBody(std::vector<Vec2>{{2, 2}, {7, 1}, {2, 2}});
  ASSERT_FALSE(same.ok());
  EXPECT_TRUE(NamesNumber(same.status().message(), 0))
      << same.status().message();
  EXPECT_TRUE(NamesNumber(same.status().message(), 2))
      << same.status().message();
}

TEST(BodyTest, CentresJustFartherThanTheCoincidenceDistanceAreABody) {
  const std::vector<Vec2> c = {{0, 0}, {2e-9, 0}, {5, 3}};
  Result<Body> body = BuildBody(c);
  ASSERT_TRUE(body.ok()) << body.status().ToString();
  ExpectWellFormed(c, *body);
}

TEST(BodyTest, FewerThanTwoCentresFail) {
  Result<Body> none = BuildBody(std::vector<Vec2>{});
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(none.status().message().empty());
  Result<Body> one = BuildBody(std::vector<Vec2>{{1, 2}});
  ASSERT_FALSE(one.ok());
  EXPECT_EQ(one.status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(one.status().message().empty());
}

TEST(BodyTest, BuildingIsDeterministic) {
  Source source(3);
  const std::vector<Vec2> c = RandomCentres(source, 20, 8.0, 0.3);
  const Body a = MustBuild(c);
  const Body b = MustBuild(c);
  ASSERT_EQ(a.springs.size(), b.springs.size());
  for (size_t s = 0; s < a.springs.size(); ++s) {
    EXPECT_EQ(a.springs[s].a, b.springs[s].a);
    EXPECT_EQ(a.springs[s].b, b.springs[s].b);
    EXPECT_EQ(a.springs[s].rest_length, b.springs[s].rest_length);
  }
  ASSERT_EQ(a.chambers.size(), b.chambers.size());
  for (size_t k = 0; k < a.chambers.size(); ++k) {
    EXPECT_EQ(a.chambers[k].walk, b.chambers[k].walk);
    EXPECT_EQ(a.chambers[k].rest_area, b.chambers[k].rest_area);
  }
  EXPECT_EQ(a.skin, b.skin);
}

// model §6.5 (v2): a body must enclose area.
TEST(ChamberRuleTest, StraightChainHasNoChamberAndFails) {
  std::vector<Vec2> chain;
  for (int i = 0; i < 32; ++i) chain.push_back({1.0 * i, 0.0});
  const BodySummary summary = SummarizeBody(MustBuild(chain));
  EXPECT_EQ(summary.cells, 32);
  EXPECT_EQ(summary.springs, 31);
  EXPECT_EQ(summary.chambers, 0);
  EXPECT_EQ(summary.skin_edges, 31);
  EXPECT_EQ(ChamberShortfall(summary, 1),
            "no chamber: the body encloses no area");
  EXPECT_EQ(ChamberShortfall(summary, 0), "");  // The old rule.
}

TEST(ChamberRuleTest, BentChainWithoutABoundedFaceFails) {
  // 12 cells one radius apart on a quarter circle of radius 7: the angle at
  // every inner cell is obtuse, so each cell lies inside the circle on its
  // neighbours' diameter and only consecutive cells are joined.
  std::vector<Vec2> arc;
  for (int i = 0; i < 12; ++i) {
    const double angle = i / 7.0;
    arc.push_back({7.0 * std::cos(angle), 7.0 * std::sin(angle)});
  }
  const BodySummary summary = SummarizeBody(MustBuild(arc));
  EXPECT_EQ(summary.springs, 11);
  EXPECT_EQ(summary.chambers, 0);
  EXPECT_GT(summary.spread_minor, 0.5);  // Bent: not a line.
  EXPECT_EQ(ChamberShortfall(summary, 1),
            "no chamber: the body encloses no area");
}

TEST(ChamberRuleTest, SingleTriangleEnclosesAreaAndPasses) {
  const BodySummary summary =
      SummarizeBody(MustBuild({{0.0, 0.0}, {2.0, 0.0}, {1.0, 1.7}}));
  EXPECT_EQ(summary.springs, 3);
  EXPECT_EQ(summary.chambers, 1);
  EXPECT_EQ(summary.skin_edges, 3);
  EXPECT_EQ(ChamberShortfall(summary, 1), "");
  EXPECT_NE(ChamberShortfall(summary, 2), "");
}

TEST(BodySummaryTest, SpreadsArePrincipalStandardDeviations) {
  // A 3 x 2 grid of cells two radii apart, turned by 30 degrees: the
  // spreads do not depend on the turn. Along the long side the positions
  // -2, 0, 2 have variance 8/3; along the short side -1, 1 have variance 1.
  const double c = std::cos(0.5235987755982988);
  const double s = std::sin(0.5235987755982988);
  std::vector<Vec2> grid;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 2; ++j) {
      const double x = 2.0 * i, y = 2.0 * j;
      grid.push_back({c * x - s * y + 5.0, s * x + c * y - 3.0});
    }
  }
  const BodySummary summary = SummarizeBody(MustBuild(grid));
  EXPECT_NEAR(summary.spread_major, std::sqrt(8.0 / 3.0), 1e-12);
  EXPECT_NEAR(summary.spread_minor, 1.0, 1e-12);
}

TEST(BodySummaryTest, StraightChainHasNoMinorSpread) {
  std::vector<Vec2> chain;
  for (int i = 0; i < 5; ++i) chain.push_back({0.6 * i, 0.8 * i});
  const BodySummary summary = SummarizeBody(MustBuild(chain));
  EXPECT_NEAR(summary.spread_major, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(summary.spread_minor, 0.0, 1e-7);
}

}  // namespace
}  // namespace animat
