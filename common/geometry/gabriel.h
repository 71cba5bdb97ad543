// The Gabriel graph of a point set, made plane (MODEL §6).
//
// Pure functions on caller-owned spans; thread-safe. O(n^3) in the number
// of points, which is at most a few dozen cells.
#ifndef ANIMAT_COMMON_GEOMETRY_GABRIEL_H_
#define ANIMAT_COMMON_GEOMETRY_GABRIEL_H_

#include <span>
#include <vector>

#include "common/base/vec2.h"

namespace animat {

// Points closer than this are coincident: development separates them and
// a body that still has them fails (MODEL §4, §6).
inline constexpr double kCoincidentDistance = 1e-9;

// An undirected edge between point indices a < b.
struct IndexEdge {
  int a = 0;
  int b = 0;
  auto operator<=>(const IndexEdge&) const = default;
};

// True when p lies strictly inside the circle with diameter a-b, computed
// exactly as MODEL §6 writes it: (p - a) . (p - b) < 0 in double.
bool InsideDiametralCircle(Vec2 p, Vec2 a, Vec2 b);

// Twice the signed area of triangle a, b, c: > 0 when counter-clockwise.
double Orient(Vec2 a, Vec2 b, Vec2 c);

// True when segments a-b and c-d cross at a point interior to both (each
// segment's endpoints lie strictly on opposite sides of the other's line).
// Segments that share an endpoint or only touch do not cross properly.
bool SegmentsProperlyCross(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// The Gabriel graph of `points`: i-j (i < j) is an edge iff no other point
// is strictly inside the circle with diameter i-j. Where cocircular points
// let edges cross (a rectangle's diagonals), every edge that properly
// crosses another is removed, so the result is a plane graph. Edges come
// sorted by (a, b). Coincident points are the caller's concern: they give
// zero-length edges.
std::vector<IndexEdge> PlaneGabrielGraph(std::span<const Vec2> points);

}  // namespace animat

#endif  // ANIMAT_COMMON_GEOMETRY_GABRIEL_H_
