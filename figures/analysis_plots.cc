#include "figures/analysis_plots.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "common/svg/svg.h"

namespace animat::figures {
namespace {

constexpr const char* kRed = "#d62728";
constexpr const char* kBlue = "#1f77b4";
constexpr const char* kLongDash = "6,3";
constexpr const char* kDots = "2,3";
constexpr const char* kRunColours[] = {"#1b9e77", "#d95f02", "#7570b3",
                                       "#e7298a", "#66a61e", "#e6ab02"};

Series Pick(const std::string& label, const std::string& colour,
            const std::string& dash, const std::vector<int>& steps,
            const std::vector<double>& values, StepRange range) {
  Series s{label, colour, dash, {}, {}};
  for (size_t k = 0; k < steps.size() && k < values.size(); ++k) {
    if (steps[k] < range.from || steps[k] > range.to) continue;
    s.x.push_back(steps[k]);
    s.y.push_back(values[k]);
  }
  return s;
}

std::string Title(const analysis::Analysis& analysis, StepRange range) {
  std::string title = "motion steps " + std::to_string(range.from) + " to " +
                      std::to_string(range.to);
  if (analysis.period_steps) {
    title += " (period " + svg::Number(*analysis.period_steps, 1) + " steps)";
  }
  return title;
}

}  // namespace

StepRange DefaultStepRange(const analysis::Analysis& analysis, double cycles) {
  StepRange range{analysis.from_step, analysis.to_step};
  if (analysis.period_steps && cycles > 0) {
    range.to = std::min<int64_t>(
        analysis.to_step,
        analysis.from_step + std::llround(cycles * *analysis.period_steps));
  }
  return range;
}

LinePlot ActivityPlot(const analysis::Analysis& analysis, StepRange range) {
  const analysis::ActivitySeries& a = analysis.activity;
  LinePlot plot;
  plot.title =
      "Mean cell activity |Δ(e − c)| per step, " + Title(analysis, range);
  plot.x_label = "motion step";
  Panel front_back{"front–back axis", "activity per step", {}, {}, {}};
  Panel left_right{"left–right axis", "activity per step", {}, {}, {}};
  auto add = [&](Panel& panel, const char* label, const char* colour,
                 const char* dash, const std::vector<double>& values) {
    if (values.empty()) return;
    panel.series.push_back(Pick(label, colour, dash, a.steps, values, range));
  };
  add(front_back, "front", kRed, "", a.front);
  add(front_back, "back", kBlue, kLongDash, a.back);
  add(left_right, "left", kRed, "", a.left);
  add(left_right, "right", kBlue, kLongDash, a.right);
  // A side without cells has no series: say so (docs/analysis.md, "Sides").
  auto missing = [](Panel& panel, const std::vector<double>& first,
                    const char* first_name, const std::vector<double>& second,
                    const char* second_name, const char* axis) {
    if (first.empty() && second.empty()) {
      panel.empty_note = std::string("no cell is ") + first_name + " or " +
                         second_name + ": every cell lies on the " + axis +
                         " axis";
    } else if (first.empty() || second.empty()) {
      panel.title += std::string(" (no cell is ") +
                     (first.empty() ? first_name : second_name) + ")";
    }
  };
  missing(front_back, a.front, "in front", a.back, "behind", "left–right");
  missing(left_right, a.left, "on the left", a.right, "on the right",
          "front–back");
  plot.panels = {front_back, left_right};
  return plot;
}

Result<LinePlot> CellsPlot(const analysis::Recording& recording,
                           const analysis::Analysis& analysis,
                           const std::vector<int>& cells, StepRange range) {
  const int first = analysis::FrameAtOrAfter(recording, range.from);
  const int end = analysis::FrameAtOrAfter(recording, range.to + 1);
  if (range.from > range.to || end - first < 1) {
    return Status::InvalidArgument("no frame recorded in motion steps " +
                                   std::to_string(range.from) + " to " +
                                   std::to_string(range.to));
  }
  LinePlot plot;
  plot.title =
      "Expansion (e) and contraction (c) factors, " + Title(analysis, range);
  plot.x_label = "motion step";
  for (int cell : cells) {
    if (cell < 0 || cell >= recording.cells) {
      return Status::InvalidArgument(
          "cell " + std::to_string(cell) + " does not exist (the body has " +
          std::to_string(recording.cells) + " cells)");
    }
    const analysis::CellSummary& summary = analysis.cells[cell];
    // The cell's sides, as the activity figure counts them.
    auto side = [&](const std::vector<analysis::Side>& sides,
                    const char* axis) -> std::string {
      if (static_cast<size_t>(cell) >= sides.size()) return "";
      switch (sides[cell]) {
        case analysis::Side::kFront:
          return "front";
        case analysis::Side::kBack:
          return "back";
        case analysis::Side::kLeft:
          return "left";
        case analysis::Side::kRight:
          return "right";
        case analysis::Side::kNone:
          break;
      }
      return std::string("on the ") + axis + " axis";
    };
    std::string where = side(analysis.axes.front_back, "left–right") + ", " +
                        side(analysis.axes.left_right, "front–back");
    if (summary.driver) where += ", driver";
    Panel panel{"cell " + std::to_string(cell) + " (" + where + ")",
                "factor level",
                {},
                0.0,
                1.0};
    Series e{"expansion e", kRed, "", {}, {}};
    Series c{"contraction c", kBlue, "", {}, {}};
    for (int k = first; k < end; ++k) {
      const size_t index = static_cast<size_t>(k) * recording.cells + cell;
      e.x.push_back(recording.steps[k]);
      e.y.push_back(recording.expand[index]);
      c.x.push_back(recording.steps[k]);
      c.y.push_back(recording.contract[index]);
    }
    panel.series = {e, c};
    plot.panels.push_back(panel);
  }
  plot.panel_height = 150;
  return plot;
}

std::vector<int> DefaultCells(const analysis::Analysis& analysis, int count) {
  std::vector<int> chosen;
  for (int d : analysis.drivers) {
    if (static_cast<int>(chosen.size()) >= count) return chosen;
    chosen.push_back(d);
  }
  std::vector<int> order(analysis.cells.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return analysis.cells[x].mean_activity > analysis.cells[y].mean_activity;
  });
  for (int i : order) {
    if (static_cast<int>(chosen.size()) >= count) break;
    if (std::find(chosen.begin(), chosen.end(), i) == chosen.end()) {
      chosen.push_back(i);
    }
  }
  return chosen;
}

LinePlot FitnessPlot(const std::vector<FitnessCurves>& runs) {
  LinePlot plot;
  plot.title = "Fitness over generations";
  plot.x_label = "generation";
  std::string axis = "fitness";
  if (!runs.empty() &&
      std::all_of(runs.begin(), runs.end(),
                  [&](const FitnessCurves& run) {
                    return run.units == runs.front().units;
                  }) &&
      !runs.front().units.empty()) {
    axis += " (" + runs.front().units + ")";
  }
  Panel panel{
      "best (solid), mean (dashed) and median (dotted)", axis, {}, {}, {}};
  for (size_t r = 0; r < runs.size(); ++r) {
    const FitnessCurves& run = runs[r];
    const std::string colour = kRunColours[r % std::size(kRunColours)];
    auto series = [&](const char* what, const char* dash,
                      const std::vector<std::optional<double>>& values) {
      Series s{run.label + " " + what, colour, dash, {}, {}};
      for (size_t g = 0; g < run.generation.size() && g < values.size(); ++g) {
        s.x.push_back(run.generation[g]);
        s.y.push_back(
            values[g].value_or(std::numeric_limits<double>::quiet_NaN()));
      }
      return s;
    };
    panel.series.push_back(series("best", "", run.best));
    panel.series.push_back(series("mean", kLongDash, run.mean));
    panel.series.push_back(series("median", kDots, run.median));
  }
  plot.panels = {panel};
  plot.panel_height = 320;
  return plot;
}

}  // namespace animat::figures
