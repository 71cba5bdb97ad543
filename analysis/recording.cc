#include "analysis/recording.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace animat::analysis {

Vec2 Recording::CentreOfMass(int frame) const {
  Vec2 sum;
  for (int i = 0; i < cells; ++i) sum += at(frame, i);
  return sum / static_cast<double>(cells);
}

namespace {

Status FrameError(int index, const std::string& what) {
  return Status::InvalidArgument("trace frames[" + std::to_string(index) +
                                 "]: " + what);
}

// Each cell's radius: its body node's, 1 where the node has none or the
// trace has no body nodes.
Status ReadRadii(const v1::Body& body, Recording* r) {
  const int nodes = body.nodes_size();
  if (nodes != 0 && nodes != r->cells) {
    return Status::InvalidArgument("trace body: " + std::to_string(nodes) +
                                   " nodes, the frames have " +
                                   std::to_string(r->cells) + " cells");
  }
  for (int i = 0; i < r->cells; ++i) {
    const bool given = i < nodes && body.nodes(i).has_radius();
    const double radius = given ? body.nodes(i).radius() : 1.0;
    if (!(std::isfinite(radius) && radius > 0)) {
      return Status::InvalidArgument("trace body: nodes[" + std::to_string(i) +
                                     "].radius must be finite and > 0");
    }
    r->radius.push_back(radius);
  }
  return Status::Ok();
}

}  // namespace

Result<Recording> RecordingFromTrace(const v1::Trace& trace) {
  std::vector<int> motion;  // Indices of the MOTION frames.
  for (int k = 0; k < trace.frames_size(); ++k) {
    if (trace.frames(k).phase() == v1::MotionFrame::MOTION) motion.push_back(k);
  }
  if (motion.size() < 2) {
    std::string why = "the trace has fewer than 2 motion frames";
    if (trace.has_result() && !trace.result().reason().empty()) {
      why += " (the evaluation failed: " + trace.result().reason() + ")";
    }
    return Status::InvalidArgument(why);
  }
  Recording r;
  if (trace.has_config() && trace.config().has_physics()) {
    const v1::PhysicsConfig& physics = trace.config().physics();
    if (physics.has_dt()) r.dt = physics.dt();
    if (physics.has_actuation_max()) r.actuation_max = physics.actuation_max();
  }
  if (!(r.dt > 0) || !std::isfinite(r.dt) || !std::isfinite(r.actuation_max)) {
    return Status::InvalidArgument("trace config: physics dt must be > 0");
  }
  const v1::MotionFrame& first = trace.frames(motion[0]);
  const v1::MotionFrame& second = trace.frames(motion[1]);
  r.cells = first.x_size();
  r.stride = second.step() - first.step();
  if (r.cells < 1) return FrameError(motion[0], "no cells");
  if (r.stride < 1) return FrameError(motion[1], "steps do not increase");
  for (size_t m = 0; m < motion.size(); ++m) {
    const int index = motion[m];
    const v1::MotionFrame& f = trace.frames(index);
    const int64_t expected =
        static_cast<int64_t>(first.step()) + static_cast<int64_t>(m) * r.stride;
    if (f.step() != expected) {
      // Only the last frame may break the spacing (the phase's last step).
      if (m + 1 == motion.size() && f.step() > r.steps.back()) break;
      return FrameError(index, "step " + std::to_string(f.step()) +
                                   " breaks the spacing of " +
                                   std::to_string(r.stride) + " steps");
    }
    if (f.x_size() != r.cells || f.y_size() != r.cells) {
      return FrameError(
          index, "x and y must have " + std::to_string(r.cells) + " values");
    }
    if (f.expand_size() != r.cells || f.contract_size() != r.cells) {
      return FrameError(index, "expand and contract must have " +
                                   std::to_string(r.cells) + " values");
    }
    for (int i = 0; i < r.cells; ++i) {
      const Vec2 p(f.x(i), f.y(i));
      if (!IsFinite(p) || !std::isfinite(f.expand(i)) ||
          !std::isfinite(f.contract(i))) {
        return FrameError(
            index, "cell " + std::to_string(i) + ": a value is not finite");
      }
      r.position.push_back(p);
      r.expand.push_back(f.expand(i));
      r.contract.push_back(f.contract(i));
    }
    r.steps.push_back(f.step());
  }
  for (int s = 0; s < trace.body().springs_size(); ++s) {
    const v1::Spring& spring = trace.body().springs(s);
    if (spring.a() >= static_cast<uint32_t>(r.cells) ||
        spring.b() >= static_cast<uint32_t>(r.cells) ||
        !std::isfinite(spring.rest_length())) {
      return Status::InvalidArgument(
          "trace body: springs[" + std::to_string(s) +
          "]: a node index is out of range or the rest "
          "length is not finite");
    }
    r.springs.push_back({static_cast<int>(spring.a()),
                         static_cast<int>(spring.b()), spring.rest_length()});
  }
  Status radii = ReadRadii(trace.body(), &r);
  if (!radii.ok()) return radii;
  if (r.frames() < 2) {
    return Status::InvalidArgument("the trace has fewer than 2 motion frames");
  }
  return r;
}

int FrameAtOrAfter(const Recording& recording, int64_t step) {
  const auto it =
      std::lower_bound(recording.steps.begin(), recording.steps.end(), step);
  return static_cast<int>(it - recording.steps.begin());
}

}  // namespace animat::analysis
