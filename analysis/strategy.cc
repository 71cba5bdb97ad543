#include "analysis/strategy.h"

#include <cmath>
#include <cstdio>

namespace animat::analysis {
namespace {

v1::ThresholdShift::End EndToProto(ThresholdShift::End end) {
  switch (end) {
    case ThresholdShift::End::kFrom:
      return v1::ThresholdShift::FROM;
    case ThresholdShift::End::kTo:
      return v1::ThresholdShift::TO;
    case ThresholdShift::End::kThreshold:
      break;
  }
  return v1::ThresholdShift::THRESHOLD;
}

void TermToProto(const StrategyTerm& term, v1::StrategyTerm* t) {
  t->set_feature(term.feature);
  if (term.value) t->set_value(*term.value);
  t->set_membership(term.membership);
  t->set_magnitude(term.magnitude);
}

}  // namespace

v1::StrategyAnalysis::Label StrategyLabelToProto(StrategyLabel label) {
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

void StrategyFeaturesToProto(const StrategyFeatures& in,
                             v1::StrategyFeatures* f) {
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
  if (in.lr_symmetry_rectified)
    f->set_lr_symmetry_rectified(*in.lr_symmetry_rectified);
  if (in.fb_symmetry_rectified)
    f->set_fb_symmetry_rectified(*in.fb_symmetry_rectified);
  if (in.stroke_agreement) f->set_stroke_agreement(*in.stroke_agreement);
}

std::vector<ThresholdShift> Strategy::Sensitive() const {
  std::vector<ThresholdShift> sensitive;
  for (const ThresholdShift& shift : shifts) {
    if (shift.label != label) sensitive.push_back(shift);
  }
  return sensitive;
}

Strategy ClassifyStrategy(const StrategyFeatures& features) {
  const StrategyRuleSet& rules = DefaultStrategyRules();
  const StrategyVerdict verdict = ScoreStrategy(features, rules);
  Strategy s;
  s.label = verdict.label;
  s.margin = verdict.margin;
  s.scores = verdict.scores;
  s.features = features;
  const StrategyVerdict rectified =
      ScoreStrategy(RectifiedReading(features), rules);
  s.rectified_label = rectified.label;
  s.rectified_margin = rectified.margin;
  s.shifts = ShiftThresholds(features, rules);
  return s;
}

void StrategyToProto(const Strategy& s, v1::StrategyAnalysis* out) {
  out->set_label(StrategyLabelToProto(s.label));
  out->set_margin(s.margin);
  out->set_threshold(DefaultStrategyRules().threshold);
  for (const StrategyScore& score : s.scores) {
    v1::StrategyScore* p = out->add_score();
    p->set_label(StrategyLabelToProto(score.label));
    p->set_score(score.score);
    for (const StrategyTerm& term : score.terms) {
      TermToProto(term, p->add_term());
    }
    for (const StrategyTerm& term : score.descriptors) {
      TermToProto(term, p->add_descriptor_term());
    }
  }
  StrategyFeaturesToProto(s.features, out->mutable_features());
  out->set_rectified_label(StrategyLabelToProto(s.rectified_label));
  out->set_rectified_margin(s.rectified_margin);
  out->set_shift_fraction(kThresholdShift);
  for (const ThresholdShift& shift : s.shifts) {
    v1::ThresholdShift* p = out->add_shift();
    p->set_rule_label(StrategyLabelToProto(shift.rule_label));
    p->set_feature(shift.feature);
    p->set_magnitude(shift.magnitude);
    p->set_end(EndToProto(shift.end));
    p->set_original(shift.original);
    p->set_moved(shift.moved);
    p->set_label(StrategyLabelToProto(shift.label));
    p->set_survives(shift.label == s.label);
  }
  out->set_stable(s.Sensitive().empty());
}

namespace {

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, value);
  return buffer;
}

std::string TermsText(const std::vector<StrategyTerm>& terms) {
  std::string text;
  for (const StrategyTerm& term : terms) {
    // A magnitude as it is read; its sign is in the features.
    if (term.magnitude) {
      text += std::string(" |") + term.feature + "| ";
      text += term.value ? Format("%.3f", std::abs(*term.value)) : "absent";
    } else {
      text += std::string(" ") + term.feature + " ";
      text += term.value ? Format("%+.3f", *term.value) : "absent";
    }
    text += Format(" (%.2f)", term.membership);
  }
  return text;
}

std::string LabelLine(const Strategy& s) {
  std::string text = std::string("strategy: ") + StrategyName(s.label);
  if (s.label == StrategyLabel::kOther) {
    text +=
        Format(" (no label reaches %.2f;", DefaultStrategyRules().threshold);
    text += Format(" the best is %.3f below)", s.margin);
  } else {
    text += Format(" (margin %.3f over the next label)", s.margin);
  }
  return text + "\n";
}

std::string StabilityLine(const Strategy& s) {
  const std::vector<ThresholdShift> sensitive = s.Sensitive();
  const std::string moved = Format("±%.0f%%", 100 * kThresholdShift);
  if (sensitive.empty()) {
    return "  stable: the label survives each of the " +
           std::to_string(s.shifts.size() / 2) + " thresholds moved by " +
           moved + "\n";
  }
  std::string text = "  sensitive to " + std::to_string(sensitive.size()) +
                     " of " + std::to_string(s.shifts.size()) +
                     " threshold moves by " + moved + ":";
  for (size_t i = 0; i < sensitive.size(); ++i) {
    text += (i == 0 ? " " : "; ") + DescribeShift(sensitive[i]) + " (" +
            StrategyName(sensitive[i].label) + ")";
  }
  return text + "\n";
}

}  // namespace

std::string StrategyHeadline(const Strategy& s) {
  return LabelLine(s) + StabilityLine(s);
}

std::string StrategySummary(const Strategy& s) {
  std::string text = StrategyHeadline(s);
  for (const StrategyScore& score : s.scores) {
    char head[64];
    std::snprintf(head, sizeof(head),
                  "  %-10s %.3f:", StrategyName(score.label), score.score);
    text += head + TermsText(score.terms);
    if (!score.descriptors.empty()) {
      text += "; descriptors:" + TermsText(score.descriptors);
    }
    text += "\n";
  }
  text += std::string("  rectified reading (not deciding): ") +
          StrategyName(s.rectified_label) +
          Format(" (margin %.3f)\n", s.rectified_margin);
  text += "  features:";
  for (const std::string& name : StrategyFeatureNames()) {
    const std::optional<double> value = FeatureValue(s.features, name);
    text += " " + name + " ";
    text += value ? Format("%+.3f", *value) : "absent";
  }
  text += "\n";
  return text;
}

}  // namespace animat::analysis
