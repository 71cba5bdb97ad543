#include "analysis/strategy_rules.h"

#include <algorithm>
#include <cmath>

namespace animat::analysis {
namespace {

using Member = std::optional<double> StrategyFeatures::*;

struct NamedFeature {
  const char* name;
  Member member;
  double lo;  // The values it can take.
  double hi;
};

// Every feature, in the order they are printed.
constexpr NamedFeature kFeatures[] = {
    {"lr_symmetry", &StrategyFeatures::lr_symmetry, 0, 1},
    {"fb_symmetry", &StrategyFeatures::fb_symmetry, 0, 1},
    {"fb_lag", &StrategyFeatures::fb_lag, -0.5, 0.5},
    {"lr_lag", &StrategyFeatures::lr_lag, -0.5, 0.5},
    {"fb_amplitude_gradient", &StrategyFeatures::fb_amplitude_gradient, -1, 1},
    {"wave_across", &StrategyFeatures::wave_across, 0, 1},
    {"synchrony", &StrategyFeatures::synchrony, 0, 1},
    {"irregularity", &StrategyFeatures::irregularity, 0, 1},
    {"rise_fraction", &StrategyFeatures::rise_fraction, 0, 1},
    {"stroke_asymmetry", &StrategyFeatures::stroke_asymmetry, 0, 1},
    {"holding", &StrategyFeatures::holding, 0, 1},
    {"coasting", &StrategyFeatures::coasting, 0, 1},
    {"elongation", &StrategyFeatures::elongation, 0, 1},
    {"end_taper", &StrategyFeatures::end_taper, -1, 1},
    {"back_protrusion", &StrategyFeatures::back_protrusion, 0, 1},
    {"lr_symmetry_rectified", &StrategyFeatures::lr_symmetry_rectified, 0, 1},
    {"fb_symmetry_rectified", &StrategyFeatures::fb_symmetry_rectified, 0, 1},
    {"stroke_agreement", &StrategyFeatures::stroke_agreement, -1, 1},
};

// The traits the paper states of each whole class (docs/analysis.md,
// "Strategy", quotes each).
StrategyRuleSet MakeDefaultRules() {
  StrategyRuleSet set;
  // In kScoredLabels' order: turtle, shark, worm, jellyfish.
  set.required[0] = {
      {"lr_symmetry", 0.5, 0.8},    // Symmetric over the left–right axis,
      {"fb_symmetry", 0.9, 0.6},    // changing along front–back,
      {"irregularity", 0.3, 0.05},  // more or less regular.
  };
  set.required[1] = {
      {"back_protrusion", 0.55, 0.7},  // A back that swings more,
      {"fb_symmetry", 0.5, 0.8},       // front and back alike,
      {"lr_lag", 0.02, 0.1, true},     // a phase change left to right.
  };
  set.required[2] = {
      {"elongation", 0.3, 0.6},     // Elongated,
      {"wave_across", 0.5, 0.8},    // waves across the motion,
      {"lr_symmetry", 0.9, 0.6},    // asymmetric over left–right
      {"fb_symmetry", 0.9, 0.6},    // and front–back,
      {"irregularity", 0.05, 0.3},  // less regular.
  };
  set.required[3] = {
      {"synchrony", 0.6, 0.9},         // The whole body together,
      {"end_taper", 0.0, 0.3, true},   // a blunt and a pointed end,
      {"stroke_agreement", 0.1, 0.3},  // the fast stroke the end's.
  };
  return set;
}

// The traits of one analysed individual, or of most of a class.
const std::vector<StrategyRule>& Descriptors(StrategyLabel label) {
  static const std::vector<StrategyRule> kTurtle = {
      {"fb_lag", 0.0, -0.1},        // Most: a wave from back to front.
      {"fb_lag", 0.3, 0.45, true},  // One: front and back near antiphase.
  };
  static const std::vector<StrategyRule> kShark = {
      {"lr_lag", 0.02, 0.1},      // One: a wave from left to right,
      {"wave_across", 0.5, 0.8},  // across the motion.
  };
  static const std::vector<StrategyRule> kWorm = {
      {"lr_lag", 0.0, 0.1},         // From left to right (a mirror's choice).
      {"lr_lag", 0.3, 0.45, true},  // One: the sides near antiphase.
  };
  static const std::vector<StrategyRule> kJellyfish = {
      {"holding", 0.05, 0.2},       // One: the compacted state sustained,
      {"coasting", 0.05, 0.2},      // moving by inertia,
      {"rise_fraction", 0.5, 0.7},  // expanding slowly.
  };
  static const std::vector<StrategyRule> kNone;
  switch (label) {
    case StrategyLabel::kTurtle:
      return kTurtle;
    case StrategyLabel::kShark:
      return kShark;
    case StrategyLabel::kWorm:
      return kWorm;
    case StrategyLabel::kJellyfish:
      return kJellyfish;
    case StrategyLabel::kOther:
      break;
  }
  return kNone;
}

size_t IndexOf(StrategyLabel label) {
  for (size_t i = 0; i < kScoredLabels.size(); ++i) {
    if (kScoredLabels[i] == label) return i;
  }
  return kScoredLabels.size();
}

}  // namespace

const char* StrategyName(StrategyLabel label) {
  switch (label) {
    case StrategyLabel::kTurtle:
      return "turtle";
    case StrategyLabel::kShark:
      return "shark";
    case StrategyLabel::kWorm:
      return "worm";
    case StrategyLabel::kJellyfish:
      return "jellyfish";
    case StrategyLabel::kOther:
      break;
  }
  return "other";
}

const std::vector<std::string>& StrategyFeatureNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const NamedFeature& f : kFeatures) names.push_back(f.name);
    return names;
  }();
  return kNames;
}

std::optional<double> FeatureValue(const StrategyFeatures& features,
                                   const std::string& name) {
  for (const NamedFeature& f : kFeatures) {
    if (name == f.name) return features.*(f.member);
  }
  return std::nullopt;
}

std::optional<std::pair<double, double>> FeatureRange(const std::string& name,
                                                      bool magnitude) {
  for (const NamedFeature& f : kFeatures) {
    if (name != f.name) continue;
    if (!magnitude) return std::make_pair(f.lo, f.hi);
    return std::make_pair(0.0, std::max(std::abs(f.lo), std::abs(f.hi)));
  }
  return std::nullopt;
}

StrategyFeatures RectifiedReading(const StrategyFeatures& features) {
  StrategyFeatures f = features;
  f.lr_symmetry = features.lr_symmetry_rectified;
  f.fb_symmetry = features.fb_symmetry_rectified;
  return f;
}

double Membership(const StrategyRule& rule, double value) {
  const double x = rule.magnitude ? std::abs(value) : value;
  if (rule.to == rule.from) return x >= rule.to ? 1.0 : 0.0;
  const double m = (x - rule.from) / (rule.to - rule.from);
  return m > 0 ? std::min(m, 1.0) : 0.0;
}

const std::vector<StrategyRule>& StrategyRuleSet::Of(
    StrategyLabel label) const {
  static const std::vector<StrategyRule> kNone;
  const size_t i = IndexOf(label);
  return i < required.size() ? required[i] : kNone;
}

const StrategyRuleSet& DefaultStrategyRules() {
  static const StrategyRuleSet kDefault = MakeDefaultRules();
  return kDefault;
}

const std::vector<StrategyRule>& StrategyRules(StrategyLabel label) {
  return DefaultStrategyRules().Of(label);
}

const std::vector<StrategyRule>& StrategyDescriptors(StrategyLabel label) {
  return Descriptors(label);
}

}  // namespace animat::analysis
