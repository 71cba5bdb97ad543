#include "common/geometry/gabriel.h"

#include <cmath>

namespace animat {

bool InsideDiametralCircle(Vec2 p, Vec2 a, Vec2 b) {
  return (p.x - a.x) * (p.x - b.x) + (p.y - a.y) * (p.y - b.y) < 0.0;
}

double Orient(Vec2 a, Vec2 b, Vec2 c) { return Cross(b - a, c - a); }

int OrientSign(Vec2 a, Vec2 b, Vec2 c) {
  const double left = (b.x - a.x) * (c.y - a.y);
  const double right = (b.y - a.y) * (c.x - a.x);
  const double det = left - right;
  constexpr double kEpsilon = 0x1p-53;
  const double bound =
      (3.0 + 16.0 * kEpsilon) * kEpsilon * (std::fabs(left) + std::fabs(right));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return 0;
}

bool SegmentsProperlyCross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int o1 = OrientSign(a, b, c);
  const int o2 = OrientSign(a, b, d);
  const int o3 = OrientSign(c, d, a);
  const int o4 = OrientSign(c, d, b);
  return o1 * o2 == -1 && o3 * o4 == -1;
}

std::vector<IndexEdge> PlaneGabrielGraph(std::span<const Vec2> points) {
  const int n = static_cast<int>(points.size());
  std::vector<IndexEdge> gabriel;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      bool empty = true;
      for (int k = 0; k < n && empty; ++k) {
        if (k == i || k == j) continue;
        empty = !InsideDiametralCircle(points[k], points[i], points[j]);
      }
      if (empty) gabriel.push_back({i, j});
    }
  }
  // Remove every edge that properly crosses another (cocircular points).
  std::vector<bool> crossed(gabriel.size(), false);
  for (size_t e = 0; e < gabriel.size(); ++e) {
    for (size_t f = e + 1; f < gabriel.size(); ++f) {
      const IndexEdge& p = gabriel[e];
      const IndexEdge& q = gabriel[f];
      if (p.a == q.a || p.a == q.b || p.b == q.a || p.b == q.b) continue;
      if (SegmentsProperlyCross(points[p.a], points[p.b], points[q.a],
                                points[q.b])) {
        crossed[e] = true;
        crossed[f] = true;
      }
    }
  }
  std::vector<IndexEdge> plane;
  for (size_t e = 0; e < gabriel.size(); ++e) {
    if (!crossed[e]) plane.push_back(gabriel[e]);
  }
  return plane;
}

}  // namespace animat
