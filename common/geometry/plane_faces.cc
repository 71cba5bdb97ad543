#include "common/geometry/plane_faces.h"

#include <algorithm>
#include <string>

#include "common/base/text.h"
#include "common/geometry/polygon.h"

namespace animat {
namespace {

// 0 for directions with angle in [0, pi), 1 for [pi, 2 pi).
int HalfPlane(Vec2 v) { return (v.y < 0.0 || (v.y == 0.0 && v.x < 0.0)); }

// Counter-clockwise angular order of non-zero directions from one vertex,
// ties (same direction) broken by neighbour index: a total order.
struct AngleLess {
  Vec2 origin;
  std::span<const Vec2> points;
  bool operator()(int i, int j) const {
    const Vec2 u = points[i] - origin;
    const Vec2 v = points[j] - origin;
    const int hu = HalfPlane(u);
    const int hv = HalfPlane(v);
    if (hu != hv) return hu < hv;
    const double c = Cross(u, v);
    if (c != 0.0) return c > 0.0;
    return i < j;
  }
};

bool Connected(int n, const std::vector<std::vector<int>>& neighbours) {
  std::vector<bool> seen(n, false);
  std::vector<int> stack = {0};
  seen[0] = true;
  int count = 1;
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int w : neighbours[v]) {
      if (!seen[w]) {
        seen[w] = true;
        ++count;
        stack.push_back(w);
      }
    }
  }
  return count == n;
}

// Each vertex's neighbours in order of angle, after checking that every
// edge joins two distinct vertices at distinct points and that the graph
// is connected.
Result<std::vector<std::vector<int>>> SortedNeighbours(
    std::span<const Vec2> points, std::span<const IndexEdge> edges) {
  const int n = static_cast<int>(points.size());
  std::vector<std::vector<int>> neighbours(n);
  for (const IndexEdge& e : edges) {
    if (e.a < 0 || e.b < 0 || e.a >= n || e.b >= n || e.a == e.b) {
      return Status::InvalidArgument("edge " + std::to_string(e.a) + "-" +
                                     std::to_string(e.b) + " is invalid");
    }
    if (points[e.a] == points[e.b]) {
      return Status::InvalidArgument("edge " + std::to_string(e.a) + "-" +
                                     std::to_string(e.b) + " has length 0");
    }
    neighbours[e.a].push_back(e.b);
    neighbours[e.b].push_back(e.a);
  }
  if (!Connected(n, neighbours)) {
    return Status::InvalidArgument("the graph is disconnected");
  }
  for (int v = 0; v < n; ++v) {
    std::sort(neighbours[v].begin(), neighbours[v].end(),
              AngleLess{points[v], points});
  }
  return neighbours;
}

// Every face's walk, each half-edge walked once, the face on its left.
std::vector<std::vector<int>> TraceFaces(
    const std::vector<std::vector<int>>& neighbours) {
  const int n = static_cast<int>(neighbours.size());
  // Half-edge v -> neighbours[v][slot] has id offset[v] + slot.
  std::vector<int> offset(n + 1, 0);
  for (int v = 0; v < n; ++v) {
    offset[v + 1] = offset[v] + static_cast<int>(neighbours[v].size());
  }
  std::vector<bool> visited(offset[n], false);

  std::vector<std::vector<int>> faces;
  for (int v = 0; v < n; ++v) {
    for (size_t slot = 0; slot < neighbours[v].size(); ++slot) {
      if (visited[offset[v] + slot]) continue;
      std::vector<int> walk;
      int from = v;
      size_t from_slot = slot;
      while (!visited[offset[from] + from_slot]) {
        visited[offset[from] + from_slot] = true;
        walk.push_back(from);
        const int to = neighbours[from][from_slot];
        // At `to`, turn to the edge just clockwise of the way back: the
        // face stays on the left, so bounded faces run counter-clockwise.
        const std::vector<int>& around = neighbours[to];
        const size_t back = static_cast<size_t>(
            std::find(around.begin(), around.end(), from) - around.begin());
        from_slot = (back + around.size() - 1) % around.size();
        from = to;
      }
      faces.push_back(std::move(walk));
    }
  }
  return faces;
}

}  // namespace

Result<PlaneFaces> FacesOfPlaneGraph(std::span<const Vec2> points,
                                     std::span<const IndexEdge> edges) {
  const int n = static_cast<int>(points.size());
  if (n < 2) return Status::InvalidArgument("fewer than two vertices");
  Result<std::vector<std::vector<int>>> neighbours =
      SortedNeighbours(points, edges);
  if (!neighbours.ok()) return neighbours.status();
  std::vector<std::vector<int>> faces = TraceFaces(*neighbours);

  const int edge_count = static_cast<int>(edges.size());
  if (static_cast<int>(faces.size()) != edge_count - n + 2) {
    return Status::InvalidArgument(
        "not a plane graph: " + std::to_string(faces.size()) + " faces for " +
        std::to_string(n) + " vertices and " + std::to_string(edge_count) +
        " edges");
  }

  std::vector<double> areas(faces.size());
  size_t outer = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    areas[f] = WalkArea(points.data(), std::span<const int>(faces[f]));
    if (areas[f] < areas[outer]) outer = f;
  }

  PlaneFaces result;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (f == outer) continue;
    if (!(areas[f] > 0.0)) {
      return Status::InvalidArgument(
          "not a plane graph: a bounded face has area " +
          ShortestDouble(areas[f]));
    }
    result.bounded.push_back(std::move(faces[f]));
    result.bounded_area.push_back(areas[f]);
  }
  result.outer = std::move(faces[outer]);
  result.outer_area = areas[outer];
  const std::vector<int>& walk = result.outer;
  for (size_t k = 0; k < walk.size(); ++k) {
    const int a = walk[k];
    const int b = walk[(k + 1) % walk.size()];
    result.outer_edges.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(result.outer_edges.begin(), result.outer_edges.end());
  result.outer_edges.erase(
      std::unique(result.outer_edges.begin(), result.outer_edges.end()),
      result.outer_edges.end());
  return result;
}

}  // namespace animat
