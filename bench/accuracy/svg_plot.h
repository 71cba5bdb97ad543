// An SVG scatter plot of cost against error on log-log axes, with the
// Pareto front drawn as a line through its points. Text is escaped and
// measured as figures/ does (common/svg); the layout is the plot's own.
#ifndef ANIMAT_BENCH_ACCURACY_SVG_PLOT_H_
#define ANIMAT_BENCH_ACCURACY_SVG_PLOT_H_

#include <span>
#include <string>
#include <vector>

namespace animat::accuracy {

struct PlotPoint {
  std::string label;  // Short, drawn beside the point.
  std::string group;  // Points of one group share a colour and legend entry.
  double x = 0.0;     // > 0 (log axis).
  double y = 0.0;     // > 0 (log axis).
  bool front = false;
};

struct PlotOptions {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::string note;  // A line under the plot (may be empty).
  // Lines of text under the legend's markers (e.g. how labels read).
  std::vector<std::string> legend_notes;
};

// The plot as a standalone SVG document (well-formed XML). Every point with
// positive finite coordinates is one <circle class="point"> (class "point
// front" on the front); the front is one <polyline class="front"> through
// its points in order of x. Points that cannot be placed on log axes are
// left out. Legend markers are <circle class="legend"> elements.
std::string PlotSvg(std::span<const PlotPoint> points,
                    const PlotOptions& options);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_SVG_PLOT_H_
