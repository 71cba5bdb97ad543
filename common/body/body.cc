#include "common/body/body.h"

#include <algorithm>
#include <cmath>
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

std::string ChamberShortfall(const BodySummary& summary, int min_chambers) {
  if (summary.chambers >= min_chambers) return "";
  if (summary.chambers == 0) return "no chamber: the body encloses no area";
  return "too few chambers: " + std::to_string(summary.chambers) +
         ", at least " + std::to_string(min_chambers) + " needed";
}

BodySummary SummarizeBody(const Body& body) {
  BodySummary summary;
  summary.cells = body.nodes();
  summary.springs = static_cast<int>(body.springs.size());
  summary.chambers = static_cast<int>(body.chambers.size());
  summary.skin_edges = static_cast<int>(body.skin.size());
  if (body.nodes() == 0) return summary;
  const double n = static_cast<double>(body.nodes());
  Vec2 mean;
  for (const Vec2& x : body.position) mean += x;
  mean = mean / n;
  // Population covariance [sxx sxy; sxy syy], summed in node order.
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const Vec2& x : body.position) {
    const Vec2 d = x - mean;
    sxx += d.x * d.x;
    sxy += d.x * d.y;
    syy += d.y * d.y;
  }
  sxx /= n;
  sxy /= n;
  syy /= n;
  // Eigenvalues of a symmetric 2x2 matrix in closed form.
  const double centre = 0.5 * (sxx + syy);
  const double half_gap = 0.5 * (sxx - syy);
  const double radius = std::sqrt(half_gap * half_gap + sxy * sxy);
  summary.spread_major = std::sqrt(std::max(0.0, centre + radius));
  summary.spread_minor = std::sqrt(std::max(0.0, centre - radius));
  return summary;
}

}  // namespace animat
