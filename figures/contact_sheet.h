// A contact sheet: small pictures of several animats on a grid, all at the
// same scale, e.g. the best individual of every N-th generation.
//
// Each picture shows the body (springs and cells) at the start of motion
// and the path of its centre of mass over the motion, turned so that the
// net displacement points right; the scale fits the largest body, and a
// path is cut where it leaves its picture. An individual without a body
// (a failed evaluation) shows its caption only. Every text is broken into
// lines that fit its picture or the sheet. In the SVG each picture is a
// <g class="individual"> with one <circle class="cell"> per cell and at
// most one <polyline class="path">. Pure function; thread-safe.
#ifndef ANIMAT_FIGURES_CONTACT_SHEET_H_
#define ANIMAT_FIGURES_CONTACT_SHEET_H_

#include <string>
#include <utility>
#include <vector>

#include "common/base/vec2.h"

namespace animat::figures {

struct SheetEntry {
  std::string heading;      // First line, e.g. "generation 5".
  std::string caption;      // Second line, e.g. "id 10440, fitness 0.989".
  std::vector<Vec2> cells;  // Cell centres (radii); empty: no body.
  std::vector<std::pair<int, int>> springs;  // Indices into cells.
  std::vector<Vec2> path;  // Centre of mass over the motion (radii).
};

// The sheet as an SVG document, `columns` >= 1 pictures per row, in the
// order given.
std::string ContactSheetSvg(const std::string& title,
                            const std::vector<SheetEntry>& entries,
                            int columns);

}  // namespace animat::figures

#endif  // ANIMAT_FIGURES_CONTACT_SHEET_H_
