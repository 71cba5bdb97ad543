#include "figures/guidance_plot.h"

#include <algorithm>
#include <cmath>

#include "common/svg/svg.h"

namespace animat::figures {
namespace {

constexpr double kPlot = 480;  // Pixels, square.
constexpr double kMargin = 12;
constexpr double kTitleSize = 14;
constexpr double kLegendSize = 11;
constexpr double kLeading = 1.3;
// One colour per trial, repeated beyond ten.
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                    "#ff7f0e", "#8c564b", "#e377c2", "#7f7f7f",
                                    "#bcbd22", "#17becf"};

const char* Colour(size_t k) {
  return kColours[k % (sizeof(kColours) / sizeof(kColours[0]))];
}

// The world box: every source with its ring, every finite path point and
// the start; its larger side with a 10% margin (at least 1.1 radii) and
// its middle.
struct WorldBox {
  double span = 0.0;
  Vec2 middle;
};

WorldBox BoxOf(const GuidancePicture& picture) {
  double lo_x = picture.start.x, hi_x = picture.start.x;
  double lo_y = picture.start.y, hi_y = picture.start.y;
  auto include = [&](Vec2 p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
    lo_x = std::min(lo_x, p.x);
    hi_x = std::max(hi_x, p.x);
    lo_y = std::min(lo_y, p.y);
    hi_y = std::max(hi_y, p.y);
  };
  const double ring = picture.decay_length;
  for (const GuidanceTrialPath& t : picture.trials) {
    include(t.source - Vec2(ring, ring));
    include(t.source + Vec2(ring, ring));
    for (Vec2 p : t.path) include(p);
  }
  return {std::max({hi_x - lo_x, hi_y - lo_y, 1.0}) * 1.1,
          Vec2((lo_x + hi_x) / 2, (lo_y + hi_y) / 2)};
}

}  // namespace

std::string GuidanceSvg(const GuidancePicture& picture) {
  const WorldBox box = BoxOf(picture);
  const double span = box.span;
  const Vec2 middle = box.middle;
  const double scale = (kPlot - 2 * kMargin) / span;  // Pixels per radius.

  const std::vector<std::string> title_lines =
      svg::WrapText(picture.title, kPlot - 2 * kMargin, kTitleSize);
  std::vector<std::string> legend;
  for (const GuidanceTrialPath& t : picture.trials) {
    legend.push_back(t.caption);
  }
  const std::string note =
      "Centre of mass in each trial (one colour per trial) from the start "
      "(black), towards its source (filled circle); the shaded disc around "
      "each source is one decay length (" +
      svg::Number(picture.decay_length, 2) +
      " radii), where the chemical reads 1/e. World axes, one scale (" +
      svg::Number(span, 1) + " radii across).";
  const std::vector<std::string> note_lines =
      svg::WrapText(note, kPlot - 2 * kMargin, kLegendSize);

  const double top = 8 + title_lines.size() * kLeading * kTitleSize;
  const double legend_top = top + kPlot;
  const double notes_top =
      legend_top + legend.size() * kLeading * kLegendSize + 4;
  svg::SvgWriter svg(
      kPlot, notes_top + note_lines.size() * kLeading * kLegendSize + 8);
  svg.Title(picture.title);
  for (size_t l = 0; l < title_lines.size(); ++l) {
    svg.Text({kMargin, 4 + (l + 1) * kLeading * kTitleSize}, title_lines[l],
             kTitleSize);
  }
  const Vec2 centre(kPlot / 2, top + kPlot / 2);
  auto pixel = [&](Vec2 p) {
    return Vec2(centre.x + (p.x - middle.x) * scale,
                centre.y - (p.y - middle.y) * scale);
  };
  svg.Rect({2, top}, kPlot - 4, kPlot, "none", "#cccccc");
  for (size_t k = 0; k < picture.trials.size(); ++k) {
    const GuidanceTrialPath& t = picture.trials[k];
    svg.BeginGroup("trial", "data-trial=\"" + std::to_string(k) + "\"");
    svg.Circle(pixel(t.source), picture.decay_length * scale, "#fff3e6",
               "#f0c8a0", "gradient");
    svg.Circle(pixel(t.source), 5, Colour(k), "black", "source");
    std::vector<Vec2> points;
    for (Vec2 p : t.path) {
      if (std::isfinite(p.x) && std::isfinite(p.y)) points.push_back(pixel(p));
    }
    if (points.size() >= 2) {
      svg.Polyline(points, Colour(k), 1.5, "", "path",
                   "trial " + std::to_string(k));
    }
    svg.EndGroup();
  }
  svg.Circle(pixel(picture.start), 3.5, "black", "black", "start");
  for (size_t l = 0; l < legend.size(); ++l) {
    const double y = legend_top + (l + 1) * kLeading * kLegendSize;
    svg.Line({kMargin, y - 4}, {kMargin + 16, y - 4}, Colour(l), 2.5);
    svg.Text({kMargin + 22, y}, legend[l], kLegendSize, "start", 0, "legend");
  }
  for (size_t l = 0; l < note_lines.size(); ++l) {
    svg.Text({kMargin, notes_top + (l + 1) * kLeading * kLegendSize},
             note_lines[l], kLegendSize, "start", 0, "note");
  }
  return svg.Finish();
}

}  // namespace animat::figures
