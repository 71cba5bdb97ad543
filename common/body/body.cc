#include "common/body/body.h"

#include <string>

#include "common/geometry/plane_faces.h"

namespace animat {
Result<Body> BuildBody(std::span<const Vec2> centres,
                       std::span<const double> radii) {
  const int n = static_cast<int>(centres.size());
  if (n < 2) {
    return Status::InvalidArgument(std::to_string(n) +
                                   " cells; a body needs at least 2");
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (Length(centres[j] - centres[i]) < kCoincidentDistance) {
        return Status::InvalidArgument("cells " + std::to_string(i) + " and " +
                                       std::to_string(j) +
                                       " are coincident (closer than 1e-9)");
      }
    }
  }
  const std::vector<IndexEdge> edges = PlaneGabrielGraph(centres);
  Result<PlaneFaces> faces = FacesOfPlaneGraph(centres, edges);
  if (!faces.ok()) {
    return Status::InvalidArgument("spring graph: " + faces.status().message());
  }
  Body body;
  body.position.assign(centres.begin(), centres.end());
  if (radii.empty()) {
    body.radius.assign(centres.size(), 1.0);
  } else {
    body.radius.assign(radii.begin(), radii.end());
  }
  for (const IndexEdge& e : edges) {
    body.springs.push_back({e.a, e.b, Length(centres[e.b] - centres[e.a])});
  }
  for (size_t f = 0; f < faces->bounded.size(); ++f) {
    body.chambers.push_back({faces->bounded[f], faces->bounded_area[f]});
  }
  body.skin = faces->outer_edges;
  return body;
}

}  // namespace animat
