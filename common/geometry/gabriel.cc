#include "common/geometry/gabriel.h"

namespace animat {

bool InsideDiametralCircle(Vec2 p, Vec2 a, Vec2 b) {
  return (p.x - a.x) * (p.x - b.x) + (p.y - a.y) * (p.y - b.y) < 0.0;
}

double Orient(Vec2 a, Vec2 b, Vec2 c) { return Cross(b - a, c - a); }

bool SegmentsProperlyCross(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double o1 = Orient(a, b, c);
  const double o2 = Orient(a, b, d);
  const double o3 = Orient(c, d, a);
  const double o4 = Orient(c, d, b);
  const bool split_cd = (o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0);
  const bool split_ab = (o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0);
  return split_cd && split_ab;
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
