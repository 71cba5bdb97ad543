#include "figures/cluster_plot.h"

#include <algorithm>
#include <cmath>

#include "common/svg/svg.h"
#include "figures/line_plot.h"

namespace animat::figures {
namespace {

using analysis::ClusteredAnimat;
using analysis::StrategyLabel;

constexpr double kPlot = 480;   // Pixels, square.
constexpr double kLeft = 56;    // Room for the y axis.
constexpr double kRight = 250;  // Room for the legend and the key.
constexpr double kBottom = 44;
constexpr double kTitleSize = 14;
constexpr double kSize = 11;
constexpr double kMarker = 6;  // Half a marker's width, pixels.
// One colour per cluster, repeated beyond ten.
constexpr const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                    "#ff7f0e", "#8c564b", "#e377c2", "#7f7f7f",
                                    "#bcbd22", "#17becf"};

const char* Colour(int k) {
  const int n = sizeof(kColours) / sizeof(kColours[0]);
  return kColours[((k % n) + n) % n];
}

void Marker(svg::SvgWriter& svg, Vec2 at, StrategyLabel label,
            const char* colour) {
  const double r = kMarker;
  switch (label) {
    case StrategyLabel::kTurtle:
      svg.Polygon({at + Vec2(-r, -r), at + Vec2(r, -r), at + Vec2(r, r),
                   at + Vec2(-r, r)},
                  colour, "black", 0.8, "marker");
      return;
    case StrategyLabel::kShark:
      svg.Polygon({at + Vec2(0, -1.2 * r), at + Vec2(1.1 * r, 0.8 * r),
                   at + Vec2(-1.1 * r, 0.8 * r)},
                  colour, "black", 0.8, "marker");
      return;
    case StrategyLabel::kWorm:
      svg.Polygon({at + Vec2(0, -1.3 * r), at + Vec2(1.3 * r, 0),
                   at + Vec2(0, 1.3 * r), at + Vec2(-1.3 * r, 0)},
                  colour, "black", 0.8, "marker");
      return;
    case StrategyLabel::kJellyfish:
      svg.Circle(at, r, colour, "black", "marker");
      return;
    case StrategyLabel::kOther:
      break;
  }
  svg.Circle(at, 0.8 * r, "white", colour, "marker");
}

struct Range {
  double lo = -1;
  double hi = 1;
};

Range RangeOf(const std::vector<ClusteredAnimat>& animats, int c) {
  Range r{0, 0};
  for (const ClusteredAnimat& a : animats) {
    r.lo = std::min(r.lo, a.position[c]);
    r.hi = std::max(r.hi, a.position[c]);
  }
  const double pad = std::max(0.1 * (r.hi - r.lo), 0.5);
  return {r.lo - pad, r.hi + pad};
}

// Axes, ticks and their labels around the plot at (left, top).
void Axes(svg::SvgWriter& svg, double left, double top, Range x, Range y,
          const std::string& x_label, const std::string& y_label) {
  svg.Rect({left, top}, kPlot, kPlot, "none", "#888888");
  for (double t : Ticks(x.lo, x.hi, 6)) {
    const double px = left + (t - x.lo) / (x.hi - x.lo) * kPlot;
    svg.Line({px, top + kPlot}, {px, top + kPlot + 4}, "#888888", 1);
    svg.Text({px, top + kPlot + 16}, svg::Number(t, 2), kSize, "middle");
  }
  for (double t : Ticks(y.lo, y.hi, 6)) {
    const double py = top + kPlot - (t - y.lo) / (y.hi - y.lo) * kPlot;
    svg.Line({left - 4, py}, {left, py}, "#888888", 1);
    svg.Text({left - 6, py + 4}, svg::Number(t, 2), kSize, "end");
  }
  svg.Text({left + kPlot / 2, top + kPlot + 34}, x_label, kSize, "middle");
  svg.Text({16, top + kPlot / 2}, y_label, kSize, "middle", -90);
}

// The legend of colours and shapes from `top` (LegendHeight tall).
void Legend(svg::SvgWriter& svg, double left, double top, int clusters) {
  svg.BeginGroup("legend");
  double y = top + 8;
  svg.Text({left, y}, "colour: cluster", kSize);
  for (int k = 0; k < clusters; ++k) {
    y += 18;
    svg.Rect({left, y - 9}, 12, 12, Colour(k), "black");
    svg.Text({left + 18, y + 1}, "cluster " + std::to_string(k), kSize);
  }
  y += 30;
  svg.Text({left, y}, "shape: label", kSize);
  for (StrategyLabel label :
       {StrategyLabel::kTurtle, StrategyLabel::kShark, StrategyLabel::kWorm,
        StrategyLabel::kJellyfish, StrategyLabel::kOther}) {
    y += 18;
    Marker(svg, {left + 6, y - 3}, label, "#bbbbbb");
    svg.Text({left + 18, y + 1}, analysis::StrategyName(label), kSize);
  }
  svg.EndGroup();
}

constexpr int kLabels = 5;

double LegendHeight(int clusters) {
  return 8 + 18 * clusters + 30 + 18 * kLabels + 12;
}

constexpr double kKeyLine = 1.3 * kSize;

// Each animat's number and name, from `top`.
void Key(svg::SvgWriter& svg, double left, double top,
         const std::vector<ClusteredAnimat>& animats) {
  svg.BeginGroup("key");
  for (size_t i = 0; i < animats.size(); ++i) {
    svg.Text({left, top + (i + 1) * kKeyLine},
             std::to_string(i + 1) + "  " + animats[i].name, kSize, "start", 0,
             "key");
  }
  svg.EndGroup();
}

// Where the key starts below the legend, for `clusters` clusters.
double KeyTop(double top, int clusters) {
  return top + LegendHeight(clusters) + 8;
}

std::string Percent(double share) {
  return svg::Number(100 * share, 0) + "% of the variance";
}

}  // namespace

std::string ClusterPlotSvg(const analysis::StrategyClustering& c,
                           const std::string& title) {
  const double width = kLeft + kPlot + kRight;
  const std::vector<std::string> lines =
      svg::WrapText(title, width - 24, kTitleSize);
  const double top = 12 + lines.size() * 1.3 * kTitleSize;
  const double key_end =
      KeyTop(top, c.clusters) + (c.animats.size() + 1) * kKeyLine;
  svg::SvgWriter svg(width, std::max(top + kPlot + kBottom, key_end));
  svg.Title(title);
  for (size_t l = 0; l < lines.size(); ++l) {
    svg.Text({12, 8 + (l + 1) * 1.3 * kTitleSize}, lines[l], kTitleSize);
  }
  const Range x = RangeOf(c.animats, 0);
  const Range y = RangeOf(c.animats, 1);
  Axes(svg, kLeft, top, x, y,
       "first principal component (" + Percent(c.projection.explained[0]) + ")",
       "second principal component (" + Percent(c.projection.explained[1]) +
           ")");
  for (size_t i = 0; i < c.animats.size(); ++i) {
    const ClusteredAnimat& a = c.animats[i];
    const Vec2 at(kLeft + (a.position[0] - x.lo) / (x.hi - x.lo) * kPlot,
                  top + kPlot - (a.position[1] - y.lo) / (y.hi - y.lo) * kPlot);
    svg.BeginGroup("animat",
                   "data-name=\"" + svg::Escape(a.name) + "\" data-label=\"" +
                       analysis::StrategyName(a.label) + "\" data-cluster=\"" +
                       std::to_string(a.cluster) + "\"");
    Marker(svg, at, a.label, Colour(a.cluster));
    svg.Text(at + Vec2(kMarker + 2, -kMarker + 2), std::to_string(i + 1), 9,
             "start", 0, "number");
    svg.EndGroup();
  }
  Legend(svg, kLeft + kPlot + 16, top, c.clusters);
  Key(svg, kLeft + kPlot + 16, KeyTop(top, c.clusters), c.animats);
  return svg.Finish();
}

}  // namespace animat::figures
