// Records an evaluation as an animat.v1.Trace (docs/formats.md): every
// `every`-th development step and motion step, always the first and last
// of each phase, and the body; with guidance, the sources and the observed
// trial (observe one trial: EvaluateOptions::observed_trial).
//
// Not thread-safe; one recorder per evaluation.
#ifndef ANIMAT_COMMON_EVALUATION_TRACE_RECORDER_H_
#define ANIMAT_COMMON_EVALUATION_TRACE_RECORDER_H_

#include "animat/v1/trace.pb.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"

namespace animat {

// Appends a frame of `state` and actuation to `trace`.
void AppendFrame(MotionPhase phase, int step, const MotionState& state,
                 std::span<const double> expand,
                 std::span<const double> contract, v1::Trace* trace);

class TraceRecorder : public EvaluationObserver {
 public:
  // `every` >= 1. The config gives the phases' lengths.
  TraceRecorder(const ModelConfig& config, int every);

  void OnDevelopmentStep(int step, const Embryo& embryo) override;
  void OnBody(const Body& body, std::span<const double> expand,
              std::span<const double> contract) override;
  void OnGuidanceTrial(int trial, std::span<const Vec2> sources) override;
  void OnMotionStep(MotionPhase phase, int step, const MotionState& state,
                    std::span<const double> expand,
                    std::span<const double> contract) override;

  // The trace so far; the caller adds config, genome and result.
  v1::Trace& trace() { return trace_; }

 private:
  ModelConfig config_;
  int every_;
  v1::Trace trace_;
};

}  // namespace animat

#endif  // ANIMAT_COMMON_EVALUATION_TRACE_RECORDER_H_
