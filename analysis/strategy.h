// The swimming strategy of an animat, named after the paper's four
// (Brainless Bodies, "Results and Analysis"): turtle, shark, worm and
// jellyfish, or other (docs/analysis.md, "Strategy").
//
// Each label is scored from the features of its description in the paper:
// every feature is mapped to a membership in [0, 1] by a linear ramp, and
// the label's score is the geometric mean of its memberships, so a label
// one of whose descriptions is clearly absent scores 0. The label is the
// best score if it reaches kStrategyThreshold, else other. Pure functions
// of their arguments; deterministic; thread-safe.
#ifndef ANIMAT_ANALYSIS_STRATEGY_H_
#define ANIMAT_ANALYSIS_STRATEGY_H_

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "animat/v1/analysis.pb.h"

namespace animat::analysis {

enum class StrategyLabel { kOther, kTurtle, kShark, kWorm, kJellyfish };

// The four labels that have a score, in the order ties are broken.
inline constexpr std::array<StrategyLabel, 4> kScoredLabels = {
    StrategyLabel::kTurtle, StrategyLabel::kShark, StrategyLabel::kWorm,
    StrategyLabel::kJellyfish};

// The least score that names a label rather than other.
inline constexpr double kStrategyThreshold = 0.5;

// What the labels are scored on (docs/analysis.md defines each). A feature
// is absent when it is undefined for the recording, e.g. left–right
// features of a body with no cell off the front–back axis, or actuation
// features without a dominant period. Angles of phase are in periods.
struct StrategyFeatures {
  // Actuation at the dominant period (each side's mean e − c, as Z =
  // A·e^{iφ}).
  std::optional<double> lr_symmetry;  // 1 − |Z_L − Z_R| / (|Z_L| + |Z_R|).
  std::optional<double> fb_symmetry;  // 1 − |Z_F − Z_B| / (|Z_F| + |Z_B|).
  std::optional<double> fb_lag;       // Back's phase − front's, (−½, ½].
  std::optional<double> lr_lag;       // Right's phase − left's, (−½, ½].
  // (A_B − A_F) / (A_B + A_F), in [−1, 1]; > 0: the back actuates more.
  std::optional<double> fb_amplitude_gradient;
  // |lr_lag| / (|lr_lag| + |fb_lag|), in [0, 1]: 1 for a wave across the
  // motion, 0 along it. Absent when the lags sum to < 0.02 periods.
  std::optional<double> wave_across;
  // Share of the variance of the cells' e − c that is their common mean,
  // in [0, 1]: 1 when every cell does the same.
  std::optional<double> synchrony;
  // Share of the variance of the cells' e − c that the dominant period and
  // its first 8 harmonics leave unexplained, [0, 1]: 0 for any periodic
  // waveform, towards 1 for noise.
  std::optional<double> irregularity;
  // The cells' mean e − c, step by step: the share of its changing steps
  // in which it rises, |rising − falling| / changing, and the share of
  // steps in which it holds still.
  std::optional<double> rise_fraction;
  std::optional<double> stroke_asymmetry;
  std::optional<double> holding;
  // Share of the window's steps whose forward speed is below half the
  // mean: a pulsed motion that coasts between strokes, in [0, 1].
  std::optional<double> coasting;
  // Shape of the mean body (cell centres in the body frame):
  // 1 − minor / major principal spread, in [0, 1]: 0 round, 1 a line.
  std::optional<double> elongation;
  // (W_B − W_F) / (W_B + W_F), in [−1, 1], W the left–right spread of
  // each end's quarter of the body length: > 0 a pointed front, < 0 a
  // pointed back, 0 both ends alike.
  std::optional<double> end_taper;
  // How far the back quarter's cells move in the body frame against the
  // front quarter's: mean root-mean-square displacement from their mean
  // places, U_B / (U_B + U_F), in [0, 1]: 0.5 when both ends move alike,
  // towards 1 for a tail that swings. Absent for a rigid body.
  std::optional<double> back_protrusion;
};

// How one feature counts for one label: membership rises linearly from 0
// at `from` to 1 at `to` (falls if `to` < `from`), of the feature's value
// or of its magnitude.
struct StrategyRule {
  const char* feature;  // A StrategyFeatures member's name.
  double from;
  double to;
  bool magnitude = false;
};

struct StrategyTerm {
  const char* feature = "";
  std::optional<double> value;  // Signed, as measured.
  double membership = 0;        // 0 when the feature is absent.
};

struct StrategyScore {
  StrategyLabel label = StrategyLabel::kOther;
  double score = 0;  // Geometric mean of the memberships, [0, 1].
  std::vector<StrategyTerm> terms;
};

struct Strategy {
  StrategyLabel label = StrategyLabel::kOther;
  // Best − second best score when labelled; threshold − best for other.
  double margin = 0;
  std::array<StrategyScore, 4> scores;  // In kScoredLabels' order.
  StrategyFeatures features;
};

// The rules of `label` (empty for kOther); static storage.
const std::vector<StrategyRule>& StrategyRules(StrategyLabel label);

// "turtle", "shark", "worm", "jellyfish" or "other".
const char* StrategyName(StrategyLabel label);

// The value of the feature called `name` (nullopt if absent or unknown).
std::optional<double> FeatureValue(const StrategyFeatures& features,
                                   const std::string& name);

// Scores every label and picks one.
Strategy ClassifyStrategy(const StrategyFeatures& features);

void StrategyToProto(const Strategy& strategy, v1::StrategyAnalysis* out);

// A few lines for people: the label, margin, each label's score with its
// terms (value → membership).
std::string StrategySummary(const Strategy& strategy);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_STRATEGY_H_
