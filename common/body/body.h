// The soft body built from the cell centres at the end of development
// (docs/model.md §6): springs on the Gabriel graph, pressurised chambers on its
// bounded faces, and the skin on its outer face.
//
// A Body is an immutable description (rest shape); the running state of a
// simulation lives in the physics layer. Safe to share between threads.
#ifndef ANIMAT_COMMON_BODY_BODY_H_
#define ANIMAT_COMMON_BODY_BODY_H_

#include <span>
#include <string>
#include <vector>

#include "common/base/status.h"
#include "common/base/vec2.h"
#include "common/geometry/gabriel.h"

namespace animat {

struct Spring {
  int a = 0;  // Node indices, a < b for built bodies.
  int b = 0;
  double rest_length = 0.0;  // L0 (radii).
};

struct Chamber {
  // Boundary walk, counter-clockwise at rest; walk[k] -> walk[k + 1]
  // (cyclically) are its edges. A dangling edge appears once each way.
  std::vector<int> walk;
  double rest_area = 0.0;  // S0 (radii^2), > 0.
};

struct Body {
  std::vector<Vec2> position;  // Rest position of each node.
  std::vector<double> radius;  // Cell radius of each node (contacts only).
  std::vector<Spring> springs;
  std::vector<Chamber> chambers;
  std::vector<IndexEdge> skin;  // Outer-face edges, each once, sorted.

  int nodes() const { return static_cast<int>(position.size()); }
};

// What kind of body a genome grew (the lineage store records it with every
// evaluation that got this far).
struct BodySummary {
  int cells = 0;
  int springs = 0;
  int chambers = 0;
  int skin_edges = 0;
  // Standard deviations (radii) of the rest cell centres along the two
  // principal axes of their covariance: spread_major >= spread_minor >= 0.
  // A straight chain has spread_minor 0 (up to rounding).
  double spread_major = 0.0;
  double spread_minor = 0.0;
};

BodySummary SummarizeBody(const Body& body);

// model §6.5 (v2): a body must enclose area. Returns "" when `summary` has at
// least `min_chambers` chambers, else the reason the evaluation fails
// ("no chamber: the body encloses no area" when it has none).
std::string ChamberShortfall(const BodySummary& summary, int min_chambers);

// Builds the body on `centres`, with the cells' `radii` (empty: all 1).
// Fails with kInvalidArgument, the message saying why, when two centres are
// closer than 1e-9 (coincident), there are fewer than 2 centres, or the
// spring graph is not a connected plane graph. Precondition: radii is empty
// or has one entry per centre.
Result<Body> BuildBody(std::span<const Vec2> centres,
                       std::span<const double> radii = {});

}  // namespace animat

#endif  // ANIMAT_COMMON_BODY_BODY_H_
