#include "figures/contact_sheet.h"

#include <algorithm>
#include <cmath>

#include "figures/svg.h"

namespace animat::figures {
namespace {

constexpr double kPicture = 180;      // Pixels, square, per individual.
constexpr double kCaption = 36;       // Below each picture.
constexpr double kTop = 30;           // Heading.
constexpr double kCellRadius = 0.45;  // Radii, as drawn.

// The entry's points relative to the path's start (or the body's centre),
// turned so the path's net displacement points right.
struct Placed {
  std::vector<Vec2> cells;
  std::vector<Vec2> path;
};

Placed Place(const SheetEntry& e) {
  Vec2 origin;
  if (!e.path.empty()) {
    origin = e.path.front();
  } else if (!e.cells.empty()) {
    for (Vec2 c : e.cells) origin += c;
    origin = origin / static_cast<double>(e.cells.size());
  }
  Vec2 direction(1, 0);
  if (e.path.size() >= 2) {
    const Vec2 d = e.path.back() - e.path.front();
    if (Length(d) > 0) direction = d / Length(d);
  }
  // Rotation by −heading: (x, y) → (x·cos + y·sin, −x·sin + y·cos).
  auto turn = [&](Vec2 p) {
    const Vec2 q = p - origin;
    return Vec2(q.x * direction.x + q.y * direction.y,
                -q.x * direction.y + q.y * direction.x);
  };
  Placed placed;
  for (Vec2 c : e.cells) placed.cells.push_back(turn(c));
  for (Vec2 p : e.path) placed.path.push_back(turn(p));
  return placed;
}

}  // namespace

std::string ContactSheetSvg(const std::string& title,
                            const std::vector<SheetEntry>& entries,
                            int columns) {
  columns = std::max(1, columns);
  const int count = static_cast<int>(entries.size());
  const int shown_columns = std::max(1, std::min(columns, count));
  const int rows = (count + columns - 1) / columns;
  // The scale fits the largest body; paths are cut where they leave the
  // picture (a good swimmer goes many body lengths).
  std::vector<Placed> placed;
  double reach = 1;  // Radii from the origin to the farthest cell.
  for (const SheetEntry& e : entries) {
    placed.push_back(Place(e));
    for (Vec2 c : placed.back().cells) {
      reach = std::max(reach, std::max(std::abs(c.x), std::abs(c.y)) + 1);
    }
  }
  for (Placed& p : placed) {
    for (size_t k = 0; k < p.path.size(); ++k) {
      if (std::max(std::abs(p.path[k].x), std::abs(p.path[k].y)) > reach) {
        p.path.resize(k);
        break;
      }
    }
  }
  const double scale = (kPicture / 2 - 8) / reach;  // Pixels per radius.

  SvgWriter svg(shown_columns * kPicture,
                kTop + rows * (kPicture + kCaption) + 24);
  svg.Title(title);
  svg.Text({8, 20}, title, 14);
  for (int n = 0; n < count; ++n) {
    const double left = (n % columns) * kPicture;
    const double top = kTop + (n / columns) * (kPicture + kCaption);
    const Vec2 centre(left + kPicture / 2, top + kPicture / 2);
    auto pixel = [&](Vec2 p) {
      return Vec2(centre.x + p.x * scale, centre.y - p.y * scale);
    };
    const SheetEntry& e = entries[n];
    svg.BeginGroup("individual");
    svg.Rect({left + 2, top}, kPicture - 4, kPicture, "none", "#cccccc");
    for (const auto& [a, b] : e.springs) {
      if (a < 0 || b < 0 || a >= static_cast<int>(e.cells.size()) ||
          b >= static_cast<int>(e.cells.size())) {
        continue;
      }
      svg.Line(pixel(placed[n].cells[a]), pixel(placed[n].cells[b]), "#888888",
               1, "spring");
    }
    for (Vec2 c : placed[n].cells) {
      svg.Circle(pixel(c), kCellRadius * scale, "#9ecae1", "black", "cell");
    }
    if (placed[n].path.size() >= 2) {
      std::vector<Vec2> points;
      for (Vec2 p : placed[n].path) points.push_back(pixel(p));
      svg.Polyline(points, "#d62728", 1.5, "", "path", "centre of mass");
    }
    svg.Text({centre.x, top + kPicture + 14}, e.heading, 12, "middle");
    svg.Text({centre.x, top + kPicture + 29}, e.caption, 11, "middle");
    svg.EndGroup();
  }
  svg.Text({8, kTop + rows * (kPicture + kCaption) + 14},
           "Bodies at the start of motion, all at one scale (" +
               Number(2 * reach, 1) +
               " radii across); red: the path of the centre of mass, turned "
               "to run right, up to the frame.",
           11);
  return svg.Finish();
}

}  // namespace animat::figures
