#include "figures/line_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/svg/svg.h"

namespace animat::figures {
namespace {

constexpr double kLeft = 70;    // Room for the y ticks and label.
constexpr double kRight = 150;  // Room for the legend.
constexpr double kTop = 56;     // Room for the heading and a panel title.
constexpr double kGap = 30;     // Between panels (the panel title).
constexpr double kBottom = 46;  // Room for the x ticks and label.

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
  // Widens an empty or zero-width range so it can be drawn.
  void Settle() {
    if (empty()) {
      lo = 0;
      hi = 1;
    } else if (lo == hi) {
      const double pad = lo == 0 ? 1 : std::abs(lo) * 0.1;
      lo -= pad;
      hi += pad;
    }
  }
};

bool Usable(double x, double y) { return std::isfinite(x) && std::isfinite(y); }

// Enough decimals to tell ticks `step` apart.
int Decimals(double step) {
  if (!(step > 0)) return 0;
  const int d = static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  return std::clamp(d, 0, 9);
}

}  // namespace

std::vector<double> Ticks(double lo, double hi, int count) {
  if (!(hi > lo) || count < 1) return {lo};
  const double raw = (hi - lo) / count;
  const int exponent = static_cast<int>(std::floor(std::log10(raw)));
  const double magnitude = std::pow(10.0, exponent);
  double multiple = 10;
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * magnitude >= raw) {
      multiple = m;
      break;
    }
  }
  // Tick n is n·multiple·10^exponent, computed so that it is the double
  // nearest the decimal (0.6, not 0.6000000000000001).
  auto tick = [&](double n) {
    return exponent < 0 ? n * multiple / std::pow(10.0, -exponent)
                        : n * multiple * magnitude;
  };
  const double step = multiple * magnitude;
  std::vector<double> ticks;
  for (double n = std::ceil(lo / step - 1e-9); tick(n) <= hi + step * 1e-9;
       n += 1) {
    ticks.push_back(n == 0 ? 0.0 : tick(n));
    if (ticks.size() > 100) break;
  }
  return ticks;
}

namespace {

// The x values of every usable point of every panel.
Range XRange(const LinePlot& plot) {
  Range x_range;
  for (const Panel& panel : plot.panels) {
    for (const Series& s : panel.series) {
      for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (Usable(s.x[i], s.y[i])) x_range.Add(s.x[i]);
      }
    }
  }
  x_range.Settle();
  return x_range;
}

// A panel's y range: its usable points' (from 0 when none is negative),
// or its given bounds, out to whole ticks where the range is the data's.
Range YRange(const Panel& panel) {
  Range y_range;
  bool nonnegative = true;
  for (const Series& s : panel.series) {
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!Usable(s.x[i], s.y[i])) continue;
      y_range.Add(s.y[i]);
      nonnegative = nonnegative && s.y[i] >= 0;
    }
  }
  if (!y_range.empty() && nonnegative) y_range.lo = 0;
  if (panel.y_min) y_range.lo = *panel.y_min;
  if (panel.y_max) y_range.hi = *panel.y_max;
  y_range.Settle();
  const std::vector<double> rough = Ticks(y_range.lo, y_range.hi, 5);
  if (rough.size() > 1) {
    const double step = rough[1] - rough[0];
    if (!panel.y_min) y_range.lo = std::floor(y_range.lo / step) * step;
    if (!panel.y_max) y_range.hi = std::ceil(y_range.hi / step) * step;
  }
  return y_range;
}

}  // namespace

std::string LinePlotSvg(const LinePlot& plot) {
  const int panels = static_cast<int>(plot.panels.size());
  const double height = kTop + panels * plot.panel_height +
                        (panels > 0 ? panels - 1 : 0) * kGap + kBottom;
  const double plot_width = plot.width - kLeft - kRight;
  svg::SvgWriter svg(plot.width, height);
  svg.Title(plot.title);
  svg.Text({plot.width / 2, 20}, plot.title, 14, "middle");

  const Range x_range = XRange(plot);
  const std::vector<double> x_ticks = Ticks(x_range.lo, x_range.hi, 8);
  const int x_decimals =
      x_ticks.size() > 1 ? Decimals(x_ticks[1] - x_ticks[0]) : 2;
  auto px = [&](double x) {
    return kLeft + plot_width * (x - x_range.lo) / (x_range.hi - x_range.lo);
  };

  for (int p = 0; p < panels; ++p) {
    const Panel& panel = plot.panels[p];
    const double top = kTop + p * (plot.panel_height + kGap);
    const double bottom = top + plot.panel_height;
    const Range y_range = YRange(panel);
    auto py = [&](double y) {
      return bottom -
             plot.panel_height * (y - y_range.lo) / (y_range.hi - y_range.lo);
    };

    svg.BeginGroup("panel");
    svg.Text({kLeft, top - 8}, panel.title, 12);
    const std::vector<double> y_ticks = Ticks(y_range.lo, y_range.hi, 5);
    const int y_decimals =
        y_ticks.size() > 1 ? Decimals(y_ticks[1] - y_ticks[0]) : 2;
    for (double t : y_ticks) {
      svg.Line({kLeft, py(t)}, {kLeft + plot_width, py(t)}, "#e6e6e6", 1);
      svg.Text({kLeft - 6, py(t) + 4}, svg::Number(t, y_decimals), 11, "end");
    }
    for (double t : x_ticks) {
      svg.Line({px(t), bottom}, {px(t), bottom + 4}, "black", 1);
      if (p == panels - 1) {
        svg.Text({px(t), bottom + 17}, svg::Number(t, x_decimals), 11,
                 "middle");
      }
    }
    svg.Line({kLeft, bottom}, {kLeft + plot_width, bottom}, "black", 1);
    svg.Line({kLeft, top}, {kLeft, bottom}, "black", 1);
    svg.Text({18, (top + bottom) / 2}, panel.y_label, 12, "middle", -90);

    double legend_y = top + 8;
    int drawn = 0;
    for (const Series& s : panel.series) {
      std::vector<Vec2> points;
      for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (Usable(s.x[i], s.y[i])) points.push_back({px(s.x[i]), py(s.y[i])});
      }
      if (points.empty()) continue;
      ++drawn;
      svg.Polyline(points, s.colour, 1.5, s.dash, "series", s.label);
      const double lx = kLeft + plot_width + 12;
      svg.Line({lx, legend_y}, {lx + 26, legend_y}, s.colour, 1.5, "", s.dash);
      svg.Text({lx + 32, legend_y + 4}, s.label, 11);
      legend_y += 16;
    }
    if (drawn == 0) {
      svg.Text({kLeft + plot_width / 2, (top + bottom) / 2},
               panel.empty_note.empty() ? "no data" : panel.empty_note, 12,
               "middle", 0, "empty");
    }
    svg.EndGroup();
  }
  svg.Text({kLeft + plot_width / 2, height - 10}, plot.x_label, 12, "middle");
  return svg.Finish();
}

}  // namespace animat::figures
