// What a swimming strategy is judged on (docs/analysis.md, "Strategy"):
// the labels, the features measured of a recording, and each label's
// rules, which map a feature to a membership in [0, 1] by a linear ramp.
//
// A label's rules are of two kinds, after how the paper (Brainless Bodies,
// "Results and Analysis") states the trait: required rules are the traits
// it gives for the whole class, and make the label's score; descriptors
// are the traits it reports of one individual analysed in detail, or of
// "most" of the class, and are measured and shown but never scored.
// Static tables and pure functions; deterministic; thread-safe.
#ifndef ANIMAT_ANALYSIS_STRATEGY_RULES_H_
#define ANIMAT_ANALYSIS_STRATEGY_RULES_H_

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace animat::analysis {

enum class StrategyLabel { kOther, kTurtle, kShark, kWorm, kJellyfish };

// The four labels that have a score, in the order ties are broken.
inline constexpr std::array<StrategyLabel, 4> kScoredLabels = {
    StrategyLabel::kTurtle, StrategyLabel::kShark, StrategyLabel::kWorm,
    StrategyLabel::kJellyfish};

// The least score that names a label rather than other.
inline constexpr double kStrategyThreshold = 0.5;

// "turtle", "shark", "worm", "jellyfish" or "other".
const char* StrategyName(StrategyLabel label);

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
  // steps in which it holds still. Absent unless the actuation is periodic
  // (irregularity at most 0.5): a drift is no stroke.
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
  // The symmetries again, of the sides' mean activity |Δ(e − c)| per step
  // (the paper's Fig. 4.2; rectified, so sides in antiphase look alike):
  // 1 − ‖x_1 − x_2‖ / (‖x_1‖ + ‖x_2‖) of the curves less their means.
  std::optional<double> lr_symmetry_rectified;
  std::optional<double> fb_symmetry_rectified;
  // sign(end_taper) × (falling − rising) / changing steps of the cells'
  // mean e − c, in [−1, 1]: > 0 when the fast half of the stroke is the
  // one the paper pairs with the pointed end (a pointed front expands
  // fast, a pointed back contracts fast); 0 for ends alike. Absent with
  // the stroke.
  std::optional<double> stroke_agreement;
};

// Every feature's name, in the order they are printed and stored.
const std::vector<std::string>& StrategyFeatureNames();

// The value of the feature called `name` (nullopt if absent or unknown).
std::optional<double> FeatureValue(const StrategyFeatures& features,
                                   const std::string& name);

// The values the feature called `name` can take, or its magnitude can
// (nullopt for an unknown name).
std::optional<std::pair<double, double>> FeatureRange(const std::string& name,
                                                      bool magnitude);

// The features with the symmetries of the rectified reading
// (lr_symmetry_rectified, fb_symmetry_rectified) in place of
// lr_symmetry and fb_symmetry.
StrategyFeatures RectifiedReading(const StrategyFeatures& features);

// How one feature counts for one label: membership rises linearly from 0
// at `from` to 1 at `to` (falls if `to` < `from`), of the feature's value
// or of its magnitude.
struct StrategyRule {
  const char* feature;  // A StrategyFeatures member's name.
  double from;
  double to;
  bool magnitude = false;
};

// The membership `rule` gives `value`, in [0, 1]. With `from` == `to` a
// step: 1 from `to` on (rising when no direction can be told).
double Membership(const StrategyRule& rule, double value);

// The rules a label is scored by, and the threshold a score must reach.
struct StrategyRuleSet {
  std::array<std::vector<StrategyRule>, 4> required;  // kScoredLabels' order.
  double threshold = kStrategyThreshold;

  // The rules of `label` (empty for kOther).
  const std::vector<StrategyRule>& Of(StrategyLabel label) const;
};

// The rules of docs/analysis.md; static storage.
const StrategyRuleSet& DefaultStrategyRules();

// The required rules of `label` in the default set (empty for kOther).
const std::vector<StrategyRule>& StrategyRules(StrategyLabel label);

// The descriptors of `label` (empty for kOther); static storage.
const std::vector<StrategyRule>& StrategyDescriptors(StrategyLabel label);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_STRATEGY_RULES_H_
