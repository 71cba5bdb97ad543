#include "analysis/analyze.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "analysis/strategy_features.h"

namespace animat::analysis {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// The mean e − c of the cells on `side`, per frame of the window; empty
// when the side has no cells.
std::vector<double> SideActuation(const Recording& r, Window window,
                                  const std::vector<Side>& sides, Side side) {
  std::vector<double> mean;
  int count = 0;
  for (Side s : sides) count += s == side ? 1 : 0;
  if (count == 0) return mean;
  for (int k = window.begin; k < window.end; ++k) {
    double sum = 0;
    for (int i = 0; i < r.cells; ++i) {
      if (sides[i] == side) sum += r.actuation(k, i);
    }
    mean.push_back(sum / count);
  }
  return mean;
}

SideSummary Summarise(const Recording& r, Window window,
                      const std::vector<Side>& sides, Side side,
                      const std::vector<double>& activity,
                      std::optional<double> frequency) {
  SideSummary summary;
  double sum = 0;
  for (size_t i = 0; i < sides.size(); ++i) {
    if (sides[i] != side) continue;
    ++summary.cells;
    sum += activity[i];
  }
  if (summary.cells == 0) return summary;
  summary.mean_activity = sum / summary.cells;
  if (frequency) {
    summary.actuation =
        ComponentAt(SideActuation(r, window, sides, side), *frequency);
  }
  return summary;
}

// How much later `second` peaks than `first`; undefined unless both have
// an amplitude.
std::optional<Lag> LagBetween(const SideSummary& first,
                              const SideSummary& second,
                              std::optional<double> period_steps) {
  if (!period_steps || !first.actuation || !second.actuation ||
      !(first.actuation->amplitude > 0) || !(second.actuation->amplitude > 0)) {
    return std::nullopt;
  }
  Lag lag;
  lag.radians = WrapAngle(second.actuation->phase - first.actuation->phase);
  lag.periods = lag.radians / kTwoPi;
  lag.steps = lag.periods * *period_steps;
  return lag;
}

}  // namespace

std::optional<StepSpan> ActuationSpan(const Recording& recording, int begin,
                                      int end) {
  std::optional<StepSpan> span;
  for (int k = std::max(begin + 1, 1); k < end; ++k) {
    const double steps = recording.steps[k] - recording.steps[k - 1];
    for (int i = 0; i < recording.cells; ++i) {
      const double change =
          recording.actuation(k, i) - recording.actuation(k - 1, i);
      if (std::abs(change) > kActuationRate * steps) {
        if (!span) span = StepSpan{recording.steps[k - 1], 0};
        span->to = recording.steps[k];
        break;
      }
    }
  }
  return span;
}

Result<WindowChoice> ChooseWindow(const Recording& recording,
                                  const AnalysisOptions& options) {
  const int64_t first = recording.steps.front();
  const int64_t last = recording.steps.back();
  const int64_t from = options.from_step.value_or(first + (last - first) / 2);
  const int64_t to = options.to_step.value_or(last);
  // `to` beyond the last frame means the last (and cannot overflow).
  WindowChoice choice;
  choice.window = Window{FrameAtOrAfter(recording, from),
                         FrameAtOrAfter(recording, std::min(to, last) + 1)};
  choice.rule = options.from_step || options.to_step ? WindowRule::kGiven
                                                     : WindowRule::kSecondHalf;
  choice.actuation = ActuationSpan(recording, 0, recording.frames());
  if (from > to || choice.window.size() < 2) {
    return Status::InvalidArgument(
        "the window of steps [" + std::to_string(from) + ", " +
        std::to_string(to) + "] holds fewer than 2 of the frames recorded " +
        "(steps " + std::to_string(first) + " to " + std::to_string(last) +
        " every " + std::to_string(recording.stride) + ")");
  }
  if (choice.rule == WindowRule::kSecondHalf && choice.actuation &&
      !ActuationSpan(recording, choice.window.begin, choice.window.end)) {
    // The animat stopped actuating before the second half: the window is
    // where it actuates.
    choice.rule = WindowRule::kActuating;
    choice.window = Window{FrameAtOrAfter(recording, choice.actuation->from),
                           FrameAtOrAfter(recording, choice.actuation->to + 1)};
  }
  return choice;
}

std::string DescribeWindow(const Analysis& a) {
  const auto steps = [](int64_t from, int64_t to) {
    return "motion steps " + std::to_string(from) + " to " + std::to_string(to);
  };
  std::string text = steps(a.from_step, a.to_step);
  switch (a.window_rule) {
    case WindowRule::kGiven:
      text += " (as asked)";
      break;
    case WindowRule::kSecondHalf:
      text += " (the second half of the motion)";
      break;
    case WindowRule::kActuating:
      text +=
          " (where the animat actuates: no cell does in the second half "
          "of the motion)";
      break;
  }
  if (!a.actuation) {
    char rate[32];
    std::snprintf(rate, sizeof(rate), "%g", kActuationRate);
    text +=
        "; no cell actuates anywhere in the motion (no e − c changes by "
        "more than " +
        std::string(rate) + " per step)";
  } else if (!a.window_actuates) {
    text += "; no cell actuates in it: the animat actuates in " +
            steps(a.actuation->from, a.actuation->to) + " (--from " +
            std::to_string(a.actuation->from) + " --to " +
            std::to_string(a.actuation->to) + ")";
  } else {
    // Say so when the actuation covers less than half of the window.
    const int covered = std::min(a.actuation->to, a.to_step) -
                        std::max(a.actuation->from, a.from_step);
    if (2 * covered < a.to_step - a.from_step) {
      text += "; the animat actuates in " +
              steps(a.actuation->from, a.actuation->to) + " only";
    }
  }
  return text;
}

namespace {

// Per cell: its means over the window, its e − c as a signal (into
// `signals`), and its mean activity (into `activity` and the analysis).
void SummariseCells(const Recording& recording, const Window& window,
                    Analysis* a, std::vector<std::vector<double>>* signals,
                    std::vector<double>* activity) {
  const int n = window.size();
  const int cells = recording.cells;
  signals->assign(cells, std::vector<double>(n));
  activity->assign(cells, 0.0);
  a->cells.resize(cells);
  const int first_activity = std::max(window.begin, 1);
  for (int i = 0; i < cells; ++i) {
    CellSummary& cell = a->cells[i];
    cell.along_front = a->axes.along_front[i];
    cell.along_left = a->axes.along_left[i];
    for (int k = window.begin; k < window.end; ++k) {
      const size_t index = static_cast<size_t>(k) * cells + i;
      cell.mean_expand += recording.expand[index];
      cell.mean_contract += recording.contract[index];
      (*signals)[i][k - window.begin] = recording.actuation(k, i);
      if (k >= first_activity) (*activity)[i] += Activity(recording, k, i);
    }
    cell.mean_expand /= n;
    cell.mean_contract /= n;
    if (window.end > first_activity) {
      (*activity)[i] /= window.end - first_activity;
    }
    cell.mean_activity = (*activity)[i];
    a->mean_activity += (*activity)[i] / cells;
  }
}

// Each cell's stroke at `frequency` (A_max × amplitude × its summed rest
// lengths), the amplitudes' mean and largest, and the drivers: the fewest
// cells, largest stroke first (ties: lower index), whose strokes make up
// half of the total.
void MeasureStrokes(const Recording& recording,
                    const std::vector<std::vector<double>>& signals,
                    double frequency, Analysis* a) {
  const int cells = recording.cells;
  std::vector<double> rest_sum(cells, 0.0);
  for (const Spring& s : recording.springs) {
    rest_sum[s.a] += s.rest_length;
    rest_sum[s.b] += s.rest_length;
  }
  double amplitude_sum = 0;
  double amplitude_max = 0;
  double stroke_total = 0;
  for (int i = 0; i < cells; ++i) {
    CellSummary& cell = a->cells[i];
    cell.actuation = ComponentAt(signals[i], frequency);
    cell.stroke =
        recording.actuation_max * cell.actuation->amplitude * rest_sum[i];
    amplitude_sum += cell.actuation->amplitude;
    amplitude_max = std::max(amplitude_max, cell.actuation->amplitude);
    stroke_total += *cell.stroke;
  }
  a->amplitude_mean = amplitude_sum / cells;
  a->amplitude_max = amplitude_max;
  std::vector<int> order(cells);
  for (int i = 0; i < cells; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return *a->cells[x].stroke > *a->cells[y].stroke;
  });
  double held = 0;
  for (int i : order) {
    if (!(stroke_total > 0) || held >= 0.5 * stroke_total) break;
    a->drivers.push_back(i);
    a->cells[i].driver = true;
    held += *a->cells[i].stroke;
  }
}

}  // namespace

Result<Analysis> Analyze(const Recording& recording,
                         const AnalysisOptions& options) {
  Result<WindowChoice> choice = ChooseWindow(recording, options);
  if (!choice.ok()) return choice.status();
  const Window* window = &choice->window;
  Analysis a;
  a.window = *window;
  a.window_rule = choice->rule;
  a.actuation = choice->actuation;
  a.window_actuates =
      ActuationSpan(recording, window->begin, window->end).has_value();
  a.from_step = recording.steps[window->begin];
  a.to_step = recording.steps[window->end - 1];
  Result<BodyAxes> axes = FindBodyAxes(recording, *window);
  if (!axes.ok()) {
    return Status::InvalidArgument(axes.status().message() +
                                   "; window: " + DescribeWindow(a) +
                                   "; --from and --to choose another");
  }

  a.stride = recording.stride;
  a.dt = recording.dt;
  a.axes = std::move(axes).value();
  const double window_steps = a.to_step - a.from_step;
  a.speed = a.axes.body_frame_distance / (window_steps * a.dt);
  a.activity = ActivityAlongAxes(recording, a.axes, *window);

  std::vector<std::vector<double>> signals;
  std::vector<double> activity;
  SummariseCells(recording, *window, &a, &signals, &activity);
  const int n = window->size();

  // The dominant period: at least two cycles in the window.
  std::optional<double> frequency;
  const std::optional<DominantFrequency> dominant =
      FindDominantFrequency(signals, 2.0 / n);
  if (dominant) {
    frequency = dominant->frequency;
    a.period_steps = recording.stride / dominant->frequency;
    a.periodic_fraction = dominant->periodic_fraction;
    a.distance_per_cycle =
        a.axes.body_frame_distance * *a.period_steps / window_steps;
    MeasureStrokes(recording, signals, *frequency, &a);
  }

  a.front = Summarise(recording, *window, a.axes.front_back, Side::kFront,
                      activity, frequency);
  a.back = Summarise(recording, *window, a.axes.front_back, Side::kBack,
                     activity, frequency);
  a.left = Summarise(recording, *window, a.axes.left_right, Side::kLeft,
                     activity, frequency);
  a.right = Summarise(recording, *window, a.axes.left_right, Side::kRight,
                      activity, frequency);
  a.front_to_back = LagBetween(a.front, a.back, a.period_steps);
  a.left_to_right = LagBetween(a.left, a.right, a.period_steps);
  a.strategy = ClassifyStrategy(MeasureStrategyFeatures(recording, a));
  return a;
}

namespace {

void SideToProto(const SideSummary& side, v1::SideAnalysis* out) {
  out->set_cells(side.cells);
  out->set_mean_activity(side.mean_activity);
  if (side.actuation) {
    out->set_amplitude(side.actuation->amplitude);
    out->set_phase(side.actuation->phase);
  }
}

void LagToProto(const std::optional<Lag>& lag, v1::PhaseLag* out) {
  out->set_radians(lag->radians);
  out->set_periods(lag->periods);
  out->set_steps(lag->steps);
}

}  // namespace

v1::Analysis AnalysisToProto(const Analysis& a, std::optional<double> fitness) {
  v1::Analysis out;
  out.set_from_step(a.from_step);
  out.set_to_step(a.to_step);
  switch (a.window_rule) {
    case WindowRule::kGiven:
      out.set_window_rule(v1::Analysis::GIVEN);
      break;
    case WindowRule::kSecondHalf:
      out.set_window_rule(v1::Analysis::SECOND_HALF);
      break;
    case WindowRule::kActuating:
      out.set_window_rule(v1::Analysis::ACTUATING);
      break;
  }
  if (a.actuation) {
    out.set_actuation_from_step(a.actuation->from);
    out.set_actuation_to_step(a.actuation->to);
  }
  out.set_stride(a.stride);
  out.set_dt(a.dt);
  out.set_cells(static_cast<int>(a.cells.size()));
  if (fitness) out.set_fitness(*fitness);
  out.set_front_x(a.axes.front.x);
  out.set_front_y(a.axes.front.y);
  out.set_left_x(a.axes.left.x);
  out.set_left_y(a.axes.left.y);
  out.set_displacement(a.axes.displacement);
  out.set_distance(a.axes.body_frame_distance);
  out.set_turning(a.axes.rotation.back());
  out.set_speed(a.speed);
  if (a.period_steps) {
    out.set_period_steps(*a.period_steps);
    out.set_period_time(*a.period_steps * a.dt);
    out.set_periodic_fraction(*a.periodic_fraction);
    out.set_amplitude_mean(*a.amplitude_mean);
    out.set_amplitude_max(*a.amplitude_max);
    out.set_distance_per_cycle(*a.distance_per_cycle);
  }
  SideToProto(a.front, out.mutable_front());
  SideToProto(a.back, out.mutable_back());
  SideToProto(a.left, out.mutable_left());
  SideToProto(a.right, out.mutable_right());
  out.set_mean_activity(a.mean_activity);
  if (a.front_to_back) LagToProto(a.front_to_back, out.mutable_front_to_back());
  if (a.left_to_right) LagToProto(a.left_to_right, out.mutable_left_to_right());
  for (int d : a.drivers) out.add_drivers(d);
  for (size_t i = 0; i < a.cells.size(); ++i) {
    const CellSummary& c = a.cells[i];
    v1::CellAnalysis* cell = out.add_cell();
    cell->set_cell(static_cast<int>(i));
    cell->set_along_front(c.along_front);
    cell->set_along_left(c.along_left);
    cell->set_mean_activity(c.mean_activity);
    cell->set_mean_expand(c.mean_expand);
    cell->set_mean_contract(c.mean_contract);
    if (c.actuation) {
      cell->set_amplitude(c.actuation->amplitude);
      cell->set_phase(c.actuation->phase);
    }
    if (c.stroke) cell->set_stroke(*c.stroke);
    cell->set_driver(c.driver);
  }
  StrategyToProto(a.strategy, out.mutable_strategy());
  return out;
}

}  // namespace animat::analysis
