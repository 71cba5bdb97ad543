#include "bench/accuracy/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/svg/svg.h"

namespace animat::accuracy {
namespace {

// Canvas and plot area, in SVG user units.
constexpr double kWidth = 920, kHeight = 620;
constexpr double kLeft = 80, kTop = 50, kRight = 680, kBottom = 530;
constexpr double kFontSize = 10;
constexpr const char* kPalette[] = {"#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd",
                                    "#8c564b", "#e377c2", "#7f7f7f", "#17becf"};

std::string Num(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", v);
  return buffer;
}

bool Placeable(const PlotPoint& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && p.x > 0 && p.y > 0;
}

// A log10 axis range [lo, hi] covering the data with a margin.
struct Axis {
  double lo = 0, hi = 1;
  static Axis Covering(double min, double max) {
    Axis axis{std::log10(min), std::log10(max)};
    if (axis.hi - axis.lo < 0.3) {
      const double mid = (axis.lo + axis.hi) / 2;
      axis.lo = mid - 0.15;
      axis.hi = mid + 0.15;
    }
    const double pad = 0.06 * (axis.hi - axis.lo);
    axis.lo -= pad;
    axis.hi += pad;
    return axis;
  }
  double Fraction(double v) const { return (std::log10(v) - lo) / (hi - lo); }

  // Tick values inside the range: 1-2-5 (or finer) steps on short ranges,
  // decades (or every k-th decade) on long ones.
  std::vector<double> Ticks() const {
    const double span = hi - lo;
    std::vector<double> mantissas = {1};
    int decade_step = 1;
    if (span <= 1.2) {
      mantissas = {1, 1.5, 2, 3, 5, 7};
    } else if (span <= 2.5) {
      mantissas = {1, 2, 5};
    } else if (span > 10) {
      decade_step = static_cast<int>(std::ceil(span / 10));
    }
    std::vector<double> ticks;
    for (int k = static_cast<int>(std::floor(lo));
         k <= static_cast<int>(std::ceil(hi)); ++k) {
      if (k % decade_step != 0) continue;
      for (double m : mantissas) {
        const double v = m * std::pow(10.0, k);
        const double f = std::log10(v);
        if (f >= lo && f <= hi) ticks.push_back(v);
      }
    }
    return ticks;
  }
};

std::string TickLabel(double v) {
  char buffer[32];
  if (v >= 1e-3 && v < 1e5) {
    std::snprintf(buffer, sizeof buffer, "%g", v);
    return buffer;
  }
  const int k = static_cast<int>(std::floor(std::log10(v) + 1e-9));
  const double m = v / std::pow(10.0, k);
  if (std::abs(m - 1) < 1e-9) {
    std::snprintf(buffer, sizeof buffer, "1e%d", k);
  } else {
    std::snprintf(buffer, sizeof buffer, "%ge%d", m, k);
  }
  return buffer;
}

struct Box {
  double x0, y0, x1, y1;
  bool Overlaps(const Box& o) const {
    return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
  bool Inside(double left, double top, double right, double bottom) const {
    return x0 >= left && x1 <= right && y0 >= top && y1 <= bottom;
  }
};

std::string Text(double x, double y, const std::string& text,
                 const std::string& extra = "") {
  return "<text x=\"" + Num(x) + "\" y=\"" + Num(y) + "\"" +
         (extra.empty() ? "" : " " + extra) + ">" + svg::Escape(text) +
         "</text>\n";
}

}  // namespace

std::string PlotSvg(std::span<const PlotPoint> all,
                    const PlotOptions& options) {
  std::vector<PlotPoint> points;
  for (const PlotPoint& p : all) {
    if (Placeable(p)) points.push_back(p);
  }
  std::vector<std::string> groups;
  for (const PlotPoint& p : points) {
    if (std::find(groups.begin(), groups.end(), p.group) == groups.end()) {
      groups.push_back(p.group);
    }
  }
  auto colour = [&](const std::string& group) {
    const size_t i =
        std::find(groups.begin(), groups.end(), group) - groups.begin();
    return std::string(kPalette[i % std::size(kPalette)]);
  };

  Axis ax, ay;
  if (!points.empty()) {
    double x_min = points[0].x, x_max = points[0].x;
    double y_min = points[0].y, y_max = points[0].y;
    for (const PlotPoint& p : points) {
      x_min = std::min(x_min, p.x);
      x_max = std::max(x_max, p.x);
      y_min = std::min(y_min, p.y);
      y_max = std::max(y_max, p.y);
    }
    ax = Axis::Covering(x_min, x_max);
    ay = Axis::Covering(y_min, y_max);
  } else {
    ax = Axis::Covering(1, 10);
    ay = Axis::Covering(1, 10);
  }
  auto px = [&](double v) { return kLeft + ax.Fraction(v) * (kRight - kLeft); };
  auto py = [&](double v) {
    return kBottom - ay.Fraction(v) * (kBottom - kTop);
  };

  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + Num(kWidth) +
         "\" height=\"" + Num(kHeight) + "\" viewBox=\"0 0 " + Num(kWidth) +
         " " + Num(kHeight) + "\" font-family=\"sans-serif\" font-size=\"" +
         Num(kFontSize) + "\">\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + Num(kWidth) + "\" height=\"" +
         Num(kHeight) + "\" fill=\"white\"/>\n";
  svg +=
      Text(kLeft, 28, options.title, "font-size=\"15\" font-weight=\"bold\"");

  // Grid, ticks and tick labels.
  svg += "<g class=\"axes\" stroke=\"#dddddd\" stroke-width=\"1\">\n";
  for (double t : ax.Ticks()) {
    svg += "<line x1=\"" + Num(px(t)) + "\" y1=\"" + Num(kTop) + "\" x2=\"" +
           Num(px(t)) + "\" y2=\"" + Num(kBottom) + "\"/>\n";
  }
  for (double t : ay.Ticks()) {
    svg += "<line x1=\"" + Num(kLeft) + "\" y1=\"" + Num(py(t)) + "\" x2=\"" +
           Num(kRight) + "\" y2=\"" + Num(py(t)) + "\"/>\n";
  }
  svg += "</g>\n";
  svg += "<rect x=\"" + Num(kLeft) + "\" y=\"" + Num(kTop) + "\" width=\"" +
         Num(kRight - kLeft) + "\" height=\"" + Num(kBottom - kTop) +
         "\" fill=\"none\" stroke=\"black\"/>\n";
  for (double t : ax.Ticks()) {
    svg += "<line x1=\"" + Num(px(t)) + "\" y1=\"" + Num(kBottom) + "\" x2=\"" +
           Num(px(t)) + "\" y2=\"" + Num(kBottom + 5) +
           "\" stroke=\"black\"/>\n";
    svg += Text(px(t), kBottom + 17, TickLabel(t), "text-anchor=\"middle\"");
  }
  for (double t : ay.Ticks()) {
    svg += "<line x1=\"" + Num(kLeft - 5) + "\" y1=\"" + Num(py(t)) +
           "\" x2=\"" + Num(kLeft) + "\" y2=\"" + Num(py(t)) +
           "\" stroke=\"black\"/>\n";
    svg += Text(kLeft - 8, py(t) + 3.5, TickLabel(t), "text-anchor=\"end\"");
  }
  svg += Text((kLeft + kRight) / 2, kBottom + 38, options.x_label,
              "text-anchor=\"middle\" font-size=\"12\"");
  const double y_mid = (kTop + kBottom) / 2;
  svg +=
      Text(22, y_mid, options.y_label,
           "text-anchor=\"middle\" font-size=\"12\" transform=\"rotate(-90 " +
               Num(22) + " " + Num(y_mid) + ")\"");
  if (!options.note.empty()) {
    svg += Text(kLeft, kBottom + 60, options.note, "font-size=\"10\"");
  }

  // The front, under the points.
  std::vector<const PlotPoint*> front;
  for (const PlotPoint& p : points) {
    if (p.front) front.push_back(&p);
  }
  std::sort(front.begin(), front.end(),
            [](const PlotPoint* a, const PlotPoint* b) { return a->x < b->x; });
  if (!front.empty()) {
    svg +=
        "<polyline class=\"front\" fill=\"none\" stroke=\"black\" "
        "stroke-width=\"1.2\" points=\"";
    for (size_t i = 0; i < front.size(); ++i) {
      if (i > 0) svg += ' ';
      svg += Num(px(front[i]->x));
      svg += ',';
      svg += Num(py(front[i]->y));
    }
    svg += "\"/>\n";
  }

  // Points, then labels placed where they overlap nothing drawn so far.
  std::vector<Box> taken;
  for (const PlotPoint& p : points) {
    const double x = px(p.x), y = py(p.y);
    taken.push_back({x - 6, y - 6, x + 6, y + 6});
    const std::string c = colour(p.group);
    if (p.front) {
      svg += "<circle class=\"point front\" cx=\"" + Num(x) + "\" cy=\"" +
             Num(y) + "\" r=\"5.5\" fill=\"" + c +
             "\" stroke=\"black\" stroke-width=\"1.5\"/>\n";
    } else {
      svg += "<circle class=\"point\" cx=\"" + Num(x) + "\" cy=\"" + Num(y) +
             "\" r=\"4\" fill=\"" + c + "\" fill-opacity=\"0.35\" stroke=\"" +
             c + "\"/>\n";
    }
  }
  for (const PlotPoint& p : points) {
    const double x = px(p.x), y = py(p.y);
    const double w = svg::TextWidth(p.label, kFontSize);
    const double h = kFontSize;
    // Baseline-left corners to try, in order of preference.
    const double tries[][2] = {
        {x + 7, y + 3.5},    {x - 7 - w, y + 3.5}, {x - w / 2, y - 8},
        {x - w / 2, y + 15}, {x + 5, y - 6},       {x + 5, y + 13},
        {x - 5 - w, y - 6},  {x - 5 - w, y + 13},  {x + 7, y - 12},
        {x + 7, y + 19},     {x - 7 - w, y - 12},  {x - 7 - w, y + 19}};
    Box chosen{tries[0][0], tries[0][1] - h + 1, tries[0][0] + w,
               tries[0][1] + 2};
    for (const auto& t : tries) {
      const Box box{t[0], t[1] - h + 1, t[0] + w, t[1] + 2};
      if (!box.Inside(kLeft, kTop, kRight, kBottom)) continue;
      bool clear = true;
      for (const Box& other : taken) clear = clear && !box.Overlaps(other);
      if (clear) {
        chosen = box;
        break;
      }
    }
    taken.push_back(chosen);
    svg += Text(chosen.x0, chosen.y1 - 2, p.label, "class=\"label\"");
  }

  // Legend.
  double ly = kTop + 10;
  const double lx = kRight + 20;
  svg += Text(lx, ly, "Legend", "font-weight=\"bold\" font-size=\"12\"");
  ly += 20;
  for (const std::string& group : groups) {
    const std::string c = colour(group);
    svg += "<circle class=\"legend\" cx=\"" + Num(lx + 6) + "\" cy=\"" +
           Num(ly - 3.5) + "\" r=\"4\" fill=\"" + c +
           "\" fill-opacity=\"0.35\" stroke=\"" + c + "\"/>\n";
    svg += Text(lx + 18, ly, group);
    ly += 18;
  }
  svg += "<line x1=\"" + Num(lx - 2) + "\" y1=\"" + Num(ly - 3.5) + "\" x2=\"" +
         Num(lx + 14) + "\" y2=\"" + Num(ly - 3.5) +
         "\" stroke=\"black\" stroke-width=\"1.2\"/>\n";
  svg +=
      "<circle class=\"legend\" cx=\"" + Num(lx + 6) + "\" cy=\"" +
      Num(ly - 3.5) +
      "\" r=\"5.5\" fill=\"white\" stroke=\"black\" stroke-width=\"1.5\"/>\n";
  svg += Text(lx + 18, ly, "Pareto front");
  ly += 26;
  for (const std::string& line : options.legend_notes) {
    svg += Text(lx, ly, line, "font-size=\"9.5\"");
    ly += 14;
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace animat::accuracy
