// The Gabriel graph of a point set, made plane (docs/model.md §6).
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
// a body that still has them fails (model §4.3, §6.4).
inline constexpr double kCoincidentDistance = 1e-9;

// An undirected edge between point indices a < b.
struct IndexEdge {
  int a = 0;
  int b = 0;
  auto operator<=>(const IndexEdge&) const = default;
};

// True when p lies strictly inside the circle with diameter a-b, computed
// exactly as model §6.1 writes it: (p - a) . (p - b) < 0 in double.
bool InsideDiametralCircle(Vec2 p, Vec2 a, Vec2 b);

// Twice the signed area of triangle a, b, c: > 0 when counter-clockwise.
double Orient(Vec2 a, Vec2 b, Vec2 c);

// The sign of Orient(a, b, c): +1 or -1 when rounding cannot have decided
// it, 0 when it could have (|Orient| within Shewchuk's forward error bound
// for orient2d, (3 + 16 eps) eps (|t1| + |t2|) for its two products t1, t2).
int OrientSign(Vec2 a, Vec2 b, Vec2 c);

// True when segments a-b and c-d cross at a point interior to both: each
// segment's endpoints lie certainly on opposite sides of the other's line
// (OrientSign +1 and -1). Segments that share an endpoint, only touch, or
// are so nearly collinear that rounding could decide do not cross.
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
