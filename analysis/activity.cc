#include "analysis/activity.h"

#include <cmath>

namespace animat::analysis {

double Activity(const Recording& recording, int frame, int cell) {
  return std::abs(recording.actuation(frame, cell) -
                  recording.actuation(frame - 1, cell)) /
         recording.stride;
}

namespace {

// The mean of `values` over the cells of `side` in `sides`; appended to
// `series` unless the side has no cells.
void AppendMean(const std::vector<double>& values,
                const std::vector<Side>& sides, Side side,
                std::vector<double>* series) {
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    if (sides[i] != side) continue;
    sum += values[i];
    ++count;
  }
  if (count > 0) series->push_back(sum / count);
}

}  // namespace

ActivitySeries ActivityAlongAxes(const Recording& recording,
                                 const BodyAxes& axes, Window window) {
  ActivitySeries series;
  std::vector<double> activity(recording.cells);
  const int first = window.begin < 1 ? 1 : window.begin;
  for (int k = first; k < window.end; ++k) {
    double sum = 0;
    for (int i = 0; i < recording.cells; ++i) {
      activity[i] = Activity(recording, k, i);
      sum += activity[i];
    }
    series.steps.push_back(recording.steps[k]);
    series.all.push_back(sum / recording.cells);
    AppendMean(activity, axes.front_back, Side::kFront, &series.front);
    AppendMean(activity, axes.front_back, Side::kBack, &series.back);
    AppendMean(activity, axes.left_right, Side::kLeft, &series.left);
    AppendMean(activity, axes.left_right, Side::kRight, &series.right);
  }
  return series;
}

}  // namespace animat::analysis
