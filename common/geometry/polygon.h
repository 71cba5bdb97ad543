// Signed area of a closed walk through points.
//
// The body (rest areas) and the physics (current areas) both call this, so
// a body at its rest shape has S == S0 exactly. Pure and thread-safe.
#ifndef ANIMAT_COMMON_GEOMETRY_POLYGON_H_
#define ANIMAT_COMMON_GEOMETRY_POLYGON_H_

#include <cstddef>
#include <span>

#include "common/base/vec2.h"

namespace animat {

// Signed area (> 0 counter-clockwise) of the closed walk
// points[walk[0]] -> points[walk[1]] -> ... -> points[walk[0]], by the
// shoelace formula relative to the first vertex. A walk that passes an edge
// twice (a dangling edge) contributes nothing for it. Empty walks have
// area 0.
template <typename Index>
double WalkArea(const Vec2* points, std::span<const Index> walk) {
  if (walk.size() < 3) return 0.0;
  const Vec2 origin = points[walk[0]];
  double twice = 0.0;
  for (size_t k = 1; k + 1 < walk.size(); ++k) {
    twice += Cross(points[walk[k]] - origin, points[walk[k + 1]] - origin);
  }
  return 0.5 * twice;
}

}  // namespace animat

#endif  // ANIMAT_COMMON_GEOMETRY_POLYGON_H_
