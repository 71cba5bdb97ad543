// The paper's Fig. 4.2 and 4.3 as line charts (figures/line_plot.h), and
// fitness over generations.
//
// Pure functions; thread-safe.
#ifndef ANIMAT_FIGURES_ANALYSIS_PLOTS_H_
#define ANIMAT_FIGURES_ANALYSIS_PLOTS_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analyze.h"
#include "analysis/recording.h"
#include "common/base/status.h"
#include "figures/line_plot.h"

namespace animat::figures {

// Motion steps [from, to] to draw, both included.
struct StepRange {
  int64_t from = 0;
  int64_t to = 0;
};

// `cycles` dominant periods from the start of the analysis window, within
// the window; the whole window when there is no period or `cycles` <= 0.
StepRange DefaultStepRange(const analysis::Analysis& analysis, double cycles);

// Fig. 4.2: mean cell activity |Δ(e − c)| per step over time, one panel
// for the front–back axis (front solid, back dashed) and one for the
// left–right axis (left solid, right dashed); a side without cells has no
// series. Points outside the analysis window are not available.
LinePlot ActivityPlot(const analysis::Analysis& analysis, StepRange range);

// Fig. 4.3: the expansion (red) and contraction (blue) factors of each of
// `cells` over time, one panel per cell. kInvalidArgument for a cell
// index out of range or a range without recorded frames.
Result<LinePlot> CellsPlot(const analysis::Recording& recording,
                           const analysis::Analysis& analysis,
                           const std::vector<int>& cells, StepRange range);

// The cells Fig. 4.3 shows by default: the first `count` drivers, or the
// cells with the largest mean activity when there are fewer drivers.
std::vector<int> DefaultCells(const analysis::Analysis& analysis, int count);

// Best, mean and median fitness per generation of one run.
struct FitnessCurves {
  std::string label;  // E.g. "seed 1".
  // What the run's fitness measures, for the axis: e.g. "radii swum".
  std::string units;
  std::vector<int> generation;
  std::vector<std::optional<double>> best, mean, median;
};

// One panel: for each run (its own colour) best (solid), mean (dashed) and
// median (dotted) fitness against generation. The axis reads "fitness
// (units)" when every run has the same units, "fitness" otherwise.
LinePlot FitnessPlot(const std::vector<FitnessCurves>& runs);

}  // namespace animat::figures

#endif  // ANIMAT_FIGURES_ANALYSIS_PLOTS_H_
