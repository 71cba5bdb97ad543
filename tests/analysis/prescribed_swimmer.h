// A hand-made swimmer whose body, actuation and motion are all prescribed,
// for the strategy tests: cells at fixed places of the body frame (x
// towards the front, y to the left, radii), each displaced by
// offset(cell, step) in that frame and driven by actuation(cell, step)
// (e − c, in [−1, 1]), while the centre of mass moves speed(step) radii per
// step along `heading`. The displacements are taken relative to their mean
// over the cells, so the centre of mass follows the prescribed path
// exactly. Springs join cells at most `link` radii apart.
#ifndef ANIMAT_TESTS_ANALYSIS_PRESCRIBED_SWIMMER_H_
#define ANIMAT_TESTS_ANALYSIS_PRESCRIBED_SWIMMER_H_

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include "animat/v1/trace.pb.h"
#include "common/base/vec2.h"

namespace animat::testing {

struct PrescribedSwimmer {
  std::vector<Vec2> body;  // Body-frame places of the cells (radii).
  std::function<double(int cell, int step)> actuation;
  std::function<Vec2(int cell, int step)> offset;  // None if empty.
  std::function<double(int step)> speed;           // 0.01 if empty.
  double heading = 0.7;  // Direction of motion (radians).
  double link = 2.5;     // Radii.
  int steps = 4000;      // Motion steps; frames at 0, stride, ..., steps.
  int stride = 1;
  double dt = 0.05;
  double actuation_max = 0.2;

  int cells() const { return static_cast<int>(body.size()); }

  // A trace as `animat simulate --trace --every stride` would write it.
  v1::Trace Trace() const {
    v1::Trace trace;
    trace.mutable_config()->mutable_physics()->set_dt(dt);
    trace.mutable_config()->mutable_physics()->set_actuation_max(actuation_max);
    for (int i = 0; i < cells(); ++i) {
      v1::Node* node = trace.mutable_body()->add_nodes();
      node->set_x(body[i].x);
      node->set_y(body[i].y);
      for (int j = i + 1; j < cells(); ++j) {
        const double length = Length(body[j] - body[i]);
        if (length > link) continue;
        v1::Spring* s = trace.mutable_body()->add_springs();
        s->set_a(i);
        s->set_b(j);
        s->set_rest_length(length);
      }
    }
    Vec2 mean_body;
    for (const Vec2& b : body) mean_body += b / static_cast<double>(cells());
    const Vec2 front(std::cos(heading), std::sin(heading));
    const Vec2 left(-front.y, front.x);
    Vec2 centre;
    std::vector<Vec2> place(cells());
    for (int step = 0; step <= steps; ++step) {
      if (step > 0) centre += front * (speed ? speed(step) : 0.01);
      if (step % stride != 0) continue;
      Vec2 mean_offset;
      for (int i = 0; i < cells(); ++i) {
        place[i] = body[i] - mean_body;
        if (offset) {
          const Vec2 o = offset(i, step);
          place[i] += o;
          mean_offset += o / static_cast<double>(cells());
        }
      }
      v1::MotionFrame* frame = trace.add_frames();
      frame->set_phase(v1::MotionFrame::MOTION);
      frame->set_step(step);
      for (int i = 0; i < cells(); ++i) {
        const Vec2 q = place[i] - mean_offset;
        const Vec2 p = centre + front * q.x + left * q.y;
        frame->add_x(p.x);
        frame->add_y(p.y);
        frame->add_vx(0);
        frame->add_vy(0);
        const double a = actuation(i, step);
        frame->add_expand(0.5 + a / 2);
        frame->add_contract(0.5 - a / 2);
      }
    }
    trace.mutable_result()->set_status(v1::EvaluationResult::OK);
    return trace;
  }
};

// The cells of a grid of `columns` × `rows`, `spacing` apart, centred on
// the origin; row-major from the back right.
inline std::vector<Vec2> GridBody(int columns, int rows, double spacing) {
  std::vector<Vec2> cells;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      cells.push_back(Vec2((c - (columns - 1) / 2.0) * spacing,
                           (r - (rows - 1) / 2.0) * spacing));
    }
  }
  return cells;
}

// Uniform deviates in [0, 1) from a fixed seed (SplitMix64): the same on
// every machine.
class TestRandom {
 public:
  explicit TestRandom(uint64_t seed) : state_(seed) {}
  double Uniform() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }

 private:
  uint64_t state_;
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_ANALYSIS_PRESCRIBED_SWIMMER_H_
