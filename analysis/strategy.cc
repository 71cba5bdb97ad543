#include "analysis/strategy.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace animat::analysis {
namespace {

using Member = std::optional<double> StrategyFeatures::*;

struct NamedFeature {
  const char* name;
  Member member;
};

// Every feature, in the order they are printed.
constexpr NamedFeature kFeatures[] = {
    {"lr_symmetry", &StrategyFeatures::lr_symmetry},
    {"fb_symmetry", &StrategyFeatures::fb_symmetry},
    {"fb_lag", &StrategyFeatures::fb_lag},
    {"lr_lag", &StrategyFeatures::lr_lag},
    {"fb_amplitude_gradient", &StrategyFeatures::fb_amplitude_gradient},
    {"wave_across", &StrategyFeatures::wave_across},
    {"synchrony", &StrategyFeatures::synchrony},
    {"irregularity", &StrategyFeatures::irregularity},
    {"rise_fraction", &StrategyFeatures::rise_fraction},
    {"stroke_asymmetry", &StrategyFeatures::stroke_asymmetry},
    {"holding", &StrategyFeatures::holding},
    {"coasting", &StrategyFeatures::coasting},
    {"elongation", &StrategyFeatures::elongation},
    {"end_taper", &StrategyFeatures::end_taper},
    {"back_protrusion", &StrategyFeatures::back_protrusion},
};

double Membership(const StrategyRule& rule, double value) {
  const double x = rule.magnitude ? std::abs(value) : value;
  const double m = (x - rule.from) / (rule.to - rule.from);
  return m > 0 ? std::min(m, 1.0) : 0.0;
}

// p^(1/n) for p in (0, 1] by Newton's method from 1, which only
// decreases (converged for any p above 1e-200 with n <= 5): +, * and /
// alone, so the same bits on every machine, unlike libm's pow, exp, log.
double Root(double p, int n) {
  double x = 1;
  for (int iteration = 0; iteration < 500; ++iteration) {
    double power = 1;  // x^(n−1).
    for (int k = 1; k < n; ++k) power *= x;
    const double next = ((n - 1) * x + p / power) / n;
    if (!(next < x)) break;
    x = next;
  }
  return x;
}

StrategyScore Score(StrategyLabel label, const StrategyFeatures& features) {
  StrategyScore score;
  score.label = label;
  const std::vector<StrategyRule>& rules = StrategyRules(label);
  double product = rules.empty() ? 0.0 : 1.0;
  for (const StrategyRule& rule : rules) {
    StrategyTerm term;
    term.feature = rule.feature;
    term.value = FeatureValue(features, rule.feature);
    if (term.value) term.membership = Membership(rule, *term.value);
    product *= term.membership;
    score.terms.push_back(term);
  }
  score.score =
      product > 0 ? Root(product, static_cast<int>(rules.size())) : 0.0;
  return score;
}

v1::StrategyAnalysis::Label LabelToProto(StrategyLabel label) {
  switch (label) {
    case StrategyLabel::kTurtle:
      return v1::StrategyAnalysis::TURTLE;
    case StrategyLabel::kShark:
      return v1::StrategyAnalysis::SHARK;
    case StrategyLabel::kWorm:
      return v1::StrategyAnalysis::WORM;
    case StrategyLabel::kJellyfish:
      return v1::StrategyAnalysis::JELLYFISH;
    case StrategyLabel::kOther:
      break;
  }
  return v1::StrategyAnalysis::OTHER;
}

}  // namespace

const std::vector<StrategyRule>& StrategyRules(StrategyLabel label) {
  // Thresholds are documented in docs/analysis.md, "Strategy".
  static const std::vector<StrategyRule> kTurtle = {
      {"lr_symmetry", 0.5, 0.8},  // Symmetric over the left–right axis,
      {"fb_symmetry", 0.9, 0.6},  // changing along front–back,
      {"fb_lag", 0.0, -0.1},      // as a wave from the back to the front.
  };
  static const std::vector<StrategyRule> kShark = {
      {"back_protrusion", 0.55, 0.7},  // A back that swings more,
      {"fb_symmetry", 0.5, 0.8},       // front and back alike,
      {"lr_lag", 0.02, 0.1, true},     // a phase change left to right.
  };
  static const std::vector<StrategyRule> kWorm = {
      {"elongation", 0.3, 0.6},     // Elongated,
      {"wave_across", 0.5, 0.8},    // waves across the motion,
      {"lr_symmetry", 0.9, 0.6},    // asymmetric over left–right
      {"fb_symmetry", 0.9, 0.6},    // and front–back,
      {"irregularity", 0.05, 0.3},  // less regular.
  };
  static const std::vector<StrategyRule> kJellyfish = {
      {"synchrony", 0.6, 0.9},         // The whole body together,
      {"stroke_asymmetry", 0.1, 0.3},  // a fast stroke, slow recovery,
      {"holding", 0.05, 0.2},          // a state sustained
      {"coasting", 0.05, 0.2},         // while the body coasts,
      {"end_taper", 0.0, 0.3, true},   // a blunt and a pointed end.
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

std::optional<double> FeatureValue(const StrategyFeatures& features,
                                   const std::string& name) {
  for (const NamedFeature& f : kFeatures) {
    if (name == f.name) return features.*(f.member);
  }
  return std::nullopt;
}

Strategy ClassifyStrategy(const StrategyFeatures& features) {
  Strategy s;
  s.features = features;
  for (size_t i = 0; i < kScoredLabels.size(); ++i) {
    s.scores[i] = Score(kScoredLabels[i], features);
  }
  // Best and second best; ties go to the earlier label.
  size_t best = 0;
  for (size_t i = 1; i < s.scores.size(); ++i) {
    if (s.scores[i].score > s.scores[best].score) best = i;
  }
  double second = 0;
  for (size_t i = 0; i < s.scores.size(); ++i) {
    if (i != best) second = std::max(second, s.scores[i].score);
  }
  const double top = s.scores[best].score;
  if (top >= kStrategyThreshold) {
    s.label = s.scores[best].label;
    s.margin = top - second;
  } else {
    s.label = StrategyLabel::kOther;
    s.margin = kStrategyThreshold - top;
  }
  return s;
}

void StrategyToProto(const Strategy& s, v1::StrategyAnalysis* out) {
  out->set_label(LabelToProto(s.label));
  out->set_margin(s.margin);
  out->set_threshold(kStrategyThreshold);
  for (const StrategyScore& score : s.scores) {
    v1::StrategyScore* p = out->add_score();
    p->set_label(LabelToProto(score.label));
    p->set_score(score.score);
    for (const StrategyTerm& term : score.terms) {
      v1::StrategyTerm* t = p->add_term();
      t->set_feature(term.feature);
      if (term.value) t->set_value(*term.value);
      t->set_membership(term.membership);
    }
  }
  const StrategyFeatures& in = s.features;
  v1::StrategyFeatures* f = out->mutable_features();
  if (in.lr_symmetry) f->set_lr_symmetry(*in.lr_symmetry);
  if (in.fb_symmetry) f->set_fb_symmetry(*in.fb_symmetry);
  if (in.fb_lag) f->set_fb_lag(*in.fb_lag);
  if (in.lr_lag) f->set_lr_lag(*in.lr_lag);
  if (in.fb_amplitude_gradient)
    f->set_fb_amplitude_gradient(*in.fb_amplitude_gradient);
  if (in.wave_across) f->set_wave_across(*in.wave_across);
  if (in.synchrony) f->set_synchrony(*in.synchrony);
  if (in.irregularity) f->set_irregularity(*in.irregularity);
  if (in.rise_fraction) f->set_rise_fraction(*in.rise_fraction);
  if (in.stroke_asymmetry) f->set_stroke_asymmetry(*in.stroke_asymmetry);
  if (in.holding) f->set_holding(*in.holding);
  if (in.coasting) f->set_coasting(*in.coasting);
  if (in.elongation) f->set_elongation(*in.elongation);
  if (in.end_taper) f->set_end_taper(*in.end_taper);
  if (in.back_protrusion) f->set_back_protrusion(*in.back_protrusion);
}

namespace {

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

}  // namespace

std::string StrategySummary(const Strategy& s) {
  std::string text = std::string("strategy: ") + StrategyName(s.label);
  if (s.label == StrategyLabel::kOther) {
    text += Format(" (no label reaches %.2f;", kStrategyThreshold);
    text += Format(" the best is %.3f below)", s.margin);
  } else {
    text += Format(" (margin %.3f over the next label)", s.margin);
  }
  text += "\n";
  for (const StrategyScore& score : s.scores) {
    char head[64];
    std::snprintf(head, sizeof(head),
                  "  %-10s %.3f:", StrategyName(score.label), score.score);
    text += head;
    for (const StrategyTerm& term : score.terms) {
      text += std::string(" ") + term.feature + " ";
      text += term.value ? Format("%+.3f", *term.value) : "absent";
      text += Format(" (%.2f)", term.membership);
    }
    text += "\n";
  }
  text += "  features:";
  for (const NamedFeature& named : kFeatures) {
    const std::optional<double> value = s.features.*(named.member);
    text += std::string(" ") + named.name + " ";
    text += value ? Format("%+.3f", *value) : "absent";
  }
  text += "\n";
  return text;
}

}  // namespace animat::analysis
