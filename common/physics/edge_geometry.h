// The length and unit direction of many edges at once (docs/model.md §7.2,
// §7.4): for edge k from node a[k] to node b[k] at positions x,
//
//   d = x[b] - x[a],   l = sqrt(d.x * d.x + d.y * d.y),
//   u = l > 0 ? d / l : (0, 0)
//
// each operation the one written, in double, so the results are those of
// the scalar formula bit for bit. Two edges share one packed square root
// and each edge's two quotients one packed division (SSE4.1 targets, the
// build's x86-64-v2 included; the scalar formula otherwise), which halves
// the work of the division and square-root unit. A zero or non-finite length
// never divides by zero: its direction is (0, 0), as the formula says, and no
// floating-point exception is raised that the scalar formula would not raise.
//
// Pure function; thread-safe. `length` and `unit` hold `count` entries.
#ifndef ANIMAT_COMMON_PHYSICS_EDGE_GEOMETRY_H_
#define ANIMAT_COMMON_PHYSICS_EDGE_GEOMETRY_H_

#include "common/base/vec2.h"

namespace animat {

void MeasureEdges(const Vec2* x, const int* a, const int* b, int count,
                  double* length, Vec2* unit);

}  // namespace animat

#endif  // ANIMAT_COMMON_PHYSICS_EDGE_GEOMETRY_H_
