#include "common/evaluation/trace_recorder.h"

#include "common/physics/scene.h"

namespace animat {

void AppendFrame(MotionPhase phase, int step, const MotionState& state,
                 std::span<const double> expand,
                 std::span<const double> contract, v1::Trace* trace) {
  v1::MotionFrame* frame = trace->add_frames();
  frame->set_phase(phase == MotionPhase::kEquilibration
                       ? v1::MotionFrame::EQUILIBRATION
                       : v1::MotionFrame::MOTION);
  frame->set_step(step);
  for (size_t i = 0; i < state.position.size(); ++i) {
    frame->add_x(state.position[i].x);
    frame->add_y(state.position[i].y);
    frame->add_vx(state.velocity[i].x);
    frame->add_vy(state.velocity[i].y);
  }
  for (double e : expand) frame->add_expand(e);
  for (double c : contract) frame->add_contract(c);
}

TraceRecorder::TraceRecorder(const ModelConfig& config, int every)
    : config_(config), every_(every < 1 ? 1 : every) {}

void TraceRecorder::OnDevelopmentStep(int step, const Embryo& embryo) {
  if (step % every_ != 0 && step != config_.development.steps - 1) return;
  v1::DevelopmentSnapshot* snapshot = trace_.add_development();
  snapshot->set_step(step);
  for (int cell = 0; cell < embryo.cells(); ++cell) {
    snapshot->add_x(embryo.position[cell].x);
    snapshot->add_y(embryo.position[cell].y);
    snapshot->add_radius(embryo.radius[cell]);
    snapshot->add_angle(embryo.angle[cell]);
  }
}

void TraceRecorder::OnBody(const Body& body, std::span<const double> expand,
                           std::span<const double> contract) {
  *trace_.mutable_body() = BodyToProto(body, expand, contract);
}

void TraceRecorder::OnGuidanceTrial(int trial, std::span<const Vec2> sources) {
  v1::GuidanceTrace* g = trace_.mutable_guidance();
  g->Clear();
  g->set_trial(trial);
  for (const Vec2& s : sources) {
    g->add_source_x(s.x);
    g->add_source_y(s.y);
  }
  g->set_decay_length(config_.guidance.decay_length);
}

void TraceRecorder::OnMotionStep(MotionPhase phase, int step,
                                 const MotionState& state,
                                 std::span<const double> expand,
                                 std::span<const double> contract) {
  const int last = phase == MotionPhase::kEquilibration
                       ? config_.evaluation.equilibration_steps
                       : config_.evaluation.motion_steps;
  if (step % every_ != 0 && step != last) return;
  AppendFrame(phase, step, state, expand, contract, &trace_);
}

}  // namespace animat
