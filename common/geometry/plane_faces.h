// Faces of a connected plane graph with straight edges (docs/model.md §6).
//
// Pure function; thread-safe. O(E * degree) after sorting neighbours.
#ifndef ANIMAT_COMMON_GEOMETRY_PLANE_FACES_H_
#define ANIMAT_COMMON_GEOMETRY_PLANE_FACES_H_

#include <span>
#include <vector>

#include "common/base/status.h"
#include "common/base/vec2.h"
#include "common/geometry/gabriel.h"

namespace animat {

struct PlaneFaces {
  // Bounded faces as boundary walks of vertex indices, counter-clockwise;
  // consecutive entries (cyclically) are the face's directed edges. A walk
  // passes an edge that dangles into its face twice (once each way).
  std::vector<std::vector<int>> bounded;
  // Signed area of each bounded face (> 0), same order.
  std::vector<double> bounded_area;
  // The outer face's walk (clockwise; a bridge or a tree edge appears
  // twice) and its signed area: minus the enclosed area (for a tree, 0 up
  // to rounding).
  std::vector<int> outer;
  double outer_area = 0.0;
  // Edges on the outer face, each once, sorted: the skin.
  std::vector<IndexEdge> outer_edges;
};

// Finds the faces of the graph (points, edges), which must be a plane
// graph (no two edges cross) with distinct edges, a != b. Fails with
// kInvalidArgument, saying why, when the graph has fewer than two vertices,
// is disconnected or has a zero-length edge; crossing edges are detected
// only when they break Euler's formula or give a bounded face that is not
// counter-clockwise.
Result<PlaneFaces> FacesOfPlaneGraph(std::span<const Vec2> points,
                                     std::span<const IndexEdge> edges);

}  // namespace animat

#endif  // ANIMAT_COMMON_GEOMETRY_PLANE_FACES_H_
