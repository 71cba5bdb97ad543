#include "figures/contact_sheet.h"

#include <algorithm>
#include <cmath>

#include "common/svg/svg.h"

namespace animat::figures {
namespace {

constexpr double kPicture = 180;   // Pixels, square, per individual.
constexpr double kMargin = 8;      // Left of the heading and the note.
constexpr double kTitleSize = 14;  // Font sizes, pixels.
constexpr double kHeadingSize = 12;
constexpr double kCaptionSize = 11;
constexpr double kNoteSize = 11;
constexpr double kLeading = 1.3;      // Line height over font size.
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

// Every entry placed; returns the reach (radii from the origin to the
// farthest cell, at least 1), which sets the common scale. Paths are cut
// where they leave the picture (a good swimmer goes many body lengths).
double PlaceAll(const std::vector<SheetEntry>& entries,
                std::vector<Placed>* placed) {
  double reach = 1;
  for (const SheetEntry& e : entries) {
    placed->push_back(Place(e));
    for (Vec2 c : placed->back().cells) {
      reach = std::max(reach, std::max(std::abs(c.x), std::abs(c.y)) + 1);
    }
  }
  for (Placed& p : *placed) {
    for (size_t k = 0; k < p.path.size(); ++k) {
      if (std::max(std::abs(p.path[k].x), std::abs(p.path[k].y)) > reach) {
        p.path.resize(k);
        break;
      }
    }
  }
  return reach;
}

// One picture: its frame, springs, cells and path, centred at `centre`,
// `scale` pixels per radius.
void DrawBody(const SheetEntry& e, const Placed& placed, Vec2 centre,
              double left, double picture_top, double scale,
              svg::SvgWriter* svg) {
  auto pixel = [&](Vec2 p) {
    return Vec2(centre.x + p.x * scale, centre.y - p.y * scale);
  };
  svg->Rect({left + 2, picture_top}, kPicture - 4, kPicture, "none", "#cccccc");
  for (const auto& [a, b] : e.springs) {
    if (a < 0 || b < 0 || a >= static_cast<int>(e.cells.size()) ||
        b >= static_cast<int>(e.cells.size())) {
      continue;
    }
    svg->Line(pixel(placed.cells[a]), pixel(placed.cells[b]), "#888888", 1,
              "spring");
  }
  for (Vec2 c : placed.cells) {
    svg->Circle(pixel(c), kCellRadius * scale, "#9ecae1", "black", "cell");
  }
  if (placed.path.size() >= 2) {
    std::vector<Vec2> points;
    for (Vec2 p : placed.path) points.push_back(pixel(p));
    svg->Polyline(points, "#d62728", 1.5, "", "path", "centre of mass");
  }
}

}  // namespace

std::string ContactSheetSvg(const std::string& title,
                            const std::vector<SheetEntry>& entries,
                            int columns) {
  columns = std::max(1, columns);
  const int count = static_cast<int>(entries.size());
  const int shown_columns = std::max(1, std::min(columns, count));
  const int rows = (count + columns - 1) / columns;
  // The scale fits the largest body.
  std::vector<Placed> placed;
  const double reach = PlaceAll(entries, &placed);
  const double scale = (kPicture / 2 - 8) / reach;  // Pixels per radius.

  // Every text is wrapped to fit: the title and the note to the sheet, a
  // picture's heading and caption to the picture.
  const double width = shown_columns * kPicture;
  const std::vector<std::string> title_lines =
      svg::WrapText(title, width - 2 * kMargin, kTitleSize);
  const std::string note =
      "Bodies at the start of motion, all at one scale (" +
      svg::Number(2 * reach, 1) +
      " radii across); red: the path of the centre of mass, turned to run "
      "right, up to the frame.";
  const std::vector<std::string> note_lines =
      svg::WrapText(note, width - 2 * kMargin, kNoteSize);
  std::vector<std::vector<std::string>> headings, captions;
  size_t heading_lines = 1, caption_lines = 1;
  for (const SheetEntry& e : entries) {
    headings.push_back(svg::WrapText(e.heading, kPicture - 8, kHeadingSize));
    captions.push_back(svg::WrapText(e.caption, kPicture - 8, kCaptionSize));
    heading_lines = std::max(heading_lines, headings.back().size());
    caption_lines = std::max(caption_lines, captions.back().size());
  }
  const double top = 8 + title_lines.size() * kLeading * kTitleSize;
  const double below = 4 + heading_lines * kLeading * kHeadingSize +
                       caption_lines * kLeading * kCaptionSize;
  const double notes_top = top + rows * (kPicture + below);
  svg::SvgWriter svg(width,
                     notes_top + note_lines.size() * kLeading * kNoteSize + 8);
  svg.Title(title);
  for (size_t l = 0; l < title_lines.size(); ++l) {
    svg.Text({kMargin, 4 + (l + 1) * kLeading * kTitleSize}, title_lines[l],
             kTitleSize);
  }
  for (int n = 0; n < count; ++n) {
    const double left = (n % columns) * kPicture;
    const double picture_top = top + (n / columns) * (kPicture + below);
    const Vec2 centre(left + kPicture / 2, picture_top + kPicture / 2);
    svg.BeginGroup("individual");
    DrawBody(entries[n], placed[n], centre, left, picture_top, scale, &svg);
    double y = picture_top + kPicture;
    for (const std::string& line : headings[n]) {
      y += kLeading * kHeadingSize;
      svg.Text({centre.x, y}, line, kHeadingSize, "middle");
    }
    y = picture_top + kPicture + heading_lines * kLeading * kHeadingSize;
    for (const std::string& line : captions[n]) {
      y += kLeading * kCaptionSize;
      svg.Text({centre.x, y}, line, kCaptionSize, "middle");
    }
    svg.EndGroup();
  }
  for (size_t l = 0; l < note_lines.size(); ++l) {
    svg.Text({kMargin, notes_top + (l + 1) * kLeading * kNoteSize},
             note_lines[l], kNoteSize, "start", 0, "note");
  }
  return svg.Finish();
}

}  // namespace animat::figures
