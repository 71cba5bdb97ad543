// The analysis of a swimming animat (docs/analysis.md): body axes from the
// direction of motion, activity along them, the dominant period and
// amplitude of actuation, phase lags front→back and left→right, the cells
// that drive the motion, and the swimming strategy. Pure function of the
// recording and the options; thread-safe.
#ifndef ANIMAT_ANALYSIS_ANALYZE_H_
#define ANIMAT_ANALYSIS_ANALYZE_H_

#include <cstdint>
#include <optional>
#include <vector>

#include "analysis/activity.h"
#include "analysis/body_axes.h"
#include "analysis/recording.h"
#include "analysis/spectrum.h"
#include "analysis/strategy.h"
#include "animat/v1/analysis.pb.h"
#include "common/base/status.h"

namespace animat::analysis {

struct AnalysisOptions {
  // The window of motion steps analysed, both ends included (snapped to
  // recorded frames). Defaults: the second half of the recording, where
  // the start of motion no longer shows.
  std::optional<int64_t> from_step;
  std::optional<int64_t> to_step;
};

struct SideSummary {
  int cells = 0;
  double mean_activity = 0;            // Per step.
  std::optional<Component> actuation;  // Mean e − c at the period.
};

struct CellSummary {
  double along_front = 0;  // Radii.
  double along_left = 0;
  double mean_activity = 0;
  double mean_expand = 0;
  double mean_contract = 0;
  std::optional<Component> actuation;
  std::optional<double> stroke;  // Radii.
  bool driver = false;
};

struct Lag {
  double radians = 0;  // (−π, π]; positive: the second side is later.
  double periods = 0;
  double steps = 0;
};

struct Analysis {
  Window window;
  int from_step = 0;
  int to_step = 0;
  int stride = 1;
  double dt = 0;
  BodyAxes axes;
  double speed = 0;  // Radii per model time.
  std::optional<double> period_steps;
  std::optional<double> periodic_fraction;
  std::optional<double> amplitude_mean;
  std::optional<double> amplitude_max;
  std::optional<double> distance_per_cycle;
  SideSummary front, back, left, right;
  double mean_activity = 0;
  std::optional<Lag> front_to_back;
  std::optional<Lag> left_to_right;
  std::vector<CellSummary> cells;
  std::vector<int> drivers;  // Largest stroke first.
  ActivitySeries activity;
  Strategy strategy;  // Turtle, shark, worm, jellyfish or other.
};

// The window for `options` (see AnalysisOptions). kInvalidArgument when it
// holds fewer than 2 frames.
Result<Window> ChooseWindow(const Recording& recording,
                            const AnalysisOptions& options);

// kInvalidArgument, saying why, for a window of fewer than 2 frames or a
// body that does not move.
Result<Analysis> Analyze(const Recording& recording,
                         const AnalysisOptions& options);

// As written by `animat analyze`; `fitness` is the evaluation's.
v1::Analysis AnalysisToProto(const Analysis& analysis,
                             std::optional<double> fitness);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_ANALYZE_H_
