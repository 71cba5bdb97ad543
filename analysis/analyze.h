// The analysis of a swimming animat (docs/analysis.md): body axes from the
// direction of motion, activity along them, the dominant period and
// amplitude of actuation, phase lags front→back and left→right, the cells
// that drive the motion, and the swimming strategy. Pure function of the
// recording and the options; thread-safe.
#ifndef ANIMAT_ANALYSIS_ANALYZE_H_
#define ANIMAT_ANALYSIS_ANALYZE_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/activity.h"
#include "analysis/body_axes.h"
#include "analysis/recording.h"
#include "analysis/spectrum.h"
#include "analysis/strategy.h"
#include "animat/v1/analysis.pb.h"
#include "common/base/status.h"

namespace animat::analysis {

// A cell actuates while its e − c changes faster than this per step: 1/1000
// of the fastest change possible (e and c each move by at most Δt = 0.05
// per step, docs/model.md §3.1), the replay page's neutral rate.
inline constexpr double kActuationRate = 2e-4;

struct AnalysisOptions {
  // The window of motion steps analysed, both ends included (snapped to
  // recorded frames). Without either: the second half of the recording,
  // where the start of motion no longer shows, unless no cell actuates
  // there; then the steps where some cell actuates (WindowRule).
  std::optional<int64_t> from_step;
  std::optional<int64_t> to_step;
};

// How the window was chosen.
enum class WindowRule {
  kGiven,       // From the options' from_step or to_step.
  kSecondHalf,  // The default.
  kActuating,   // No cell actuates in the second half: the actuation span.
};

// Motion steps, both ends included.
struct StepSpan {
  int from = 0;
  int to = 0;
};

// The span of frames over which some cell actuates: from the frame before
// the first change of a cell's e − c faster than kActuationRate per step to
// the frame after the last one, among frames [begin, end); nullopt when no
// cell does.
std::optional<StepSpan> ActuationSpan(const Recording& recording, int begin,
                                      int end);

struct WindowChoice {
  Window window;
  WindowRule rule = WindowRule::kSecondHalf;
  std::optional<StepSpan> actuation;  // Over the whole recording.
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
  WindowRule window_rule = WindowRule::kSecondHalf;
  std::optional<StepSpan> actuation;  // Over the whole recording.
  bool window_actuates = false;       // Some cell actuates in the window.
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
Result<WindowChoice> ChooseWindow(const Recording& recording,
                                  const AnalysisOptions& options);

// kInvalidArgument, saying why, for a window of fewer than 2 frames or a
// body that does not move (the message then names the window, as
// DescribeWindow does).
Result<Analysis> Analyze(const Recording& recording,
                         const AnalysisOptions& options);

// The window analysed and why, for people: "motion steps 3000 to 6000 (the
// second half of the motion)", with what the animat's actuation does
// there when that explains a result: "no cell actuates anywhere in the
// motion ...", "no cell actuates in it; the animat actuates in motion
// steps 0 to 455".
std::string DescribeWindow(const Analysis& analysis);

// As written by `animat analyze`; `fitness` is the evaluation's.
v1::Analysis AnalysisToProto(const Analysis& analysis,
                             std::optional<double> fitness);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_ANALYZE_H_
