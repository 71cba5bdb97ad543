// Line charts: one or more panels stacked vertically over a shared x axis,
// each with its own y axis, series and legend. The activity, cell and
// fitness figures are line charts.
//
// In the SVG each panel is a <g class="panel"> and each series drawn a
// <polyline class="series" data-label="..."> (tests count them); a panel
// with nothing to draw says so in a <text class="empty">. Pure function;
// thread-safe.
#ifndef ANIMAT_FIGURES_LINE_PLOT_H_
#define ANIMAT_FIGURES_LINE_PLOT_H_

#include <optional>
#include <string>
#include <vector>

namespace animat::figures {

struct Series {
  std::string label;      // In the legend.
  std::string colour;     // SVG colour, e.g. "#d62728".
  std::string dash;       // stroke-dasharray, "" for solid.
  std::vector<double> x;  // Points; non-finite ones are left out.
  std::vector<double> y;  // Same length as x.
};

struct Panel {
  std::string title;
  std::string y_label;
  std::vector<Series> series;
  // The y range; by default the data's (from 0 when every value is >= 0).
  std::optional<double> y_min;
  std::optional<double> y_max;
  // Written across the panel when no series has a point to draw ("no
  // data" when empty).
  std::string empty_note = "";
};

struct LinePlot {
  std::string title;  // The document's <title> and heading.
  std::string x_label;
  std::vector<Panel> panels;
  double width = 760;         // Pixels.
  double panel_height = 200;  // Pixels, per panel.
};

// The chart as an SVG document. A series with no finite point is left out
// (and not drawn); a chart without points still has its axes.
std::string LinePlotSvg(const LinePlot& plot);

// "Nice" tick values (1, 2 or 5 × 10^k apart) covering [lo, hi], about
// `count` of them; [lo] alone when lo >= hi.
std::vector<double> Ticks(double lo, double hi, int count);

}  // namespace animat::figures

#endif  // ANIMAT_FIGURES_LINE_PLOT_H_
