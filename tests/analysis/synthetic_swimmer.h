// A made-up swimmer with known answers, for the analysis and figure tests:
// a grid of cells that glides at a constant speed (optionally turning at a
// constant rate) while each cell's e − c oscillates as A·cos(2π·step/T −
// φ) with an amplitude A and phase φ chosen per cell. The grid also
// breathes (scales about its centre), which changes no axis.
//
// Cell i sits in row i / columns, column i % columns; in the body frame
// column c is at x = (c − (columns − 1)/2)·spacing (larger x: further
// front) and row r at y = (r − (rows − 1)/2)·spacing (larger y: further
// left). Springs join grid neighbours.
#ifndef ANIMAT_TESTS_ANALYSIS_SYNTHETIC_SWIMMER_H_
#define ANIMAT_TESTS_ANALYSIS_SYNTHETIC_SWIMMER_H_

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "animat/v1/trace.pb.h"

namespace animat::testing {

struct SyntheticSwimmer {
  int columns = 4;
  int rows = 2;
  double spacing = 2;             // Radii.
  double heading = 0;             // Direction of motion at step 0 (radians).
  double speed = 1e-3;            // Radii per step, along the body's front.
  double turn_rate = 0;           // Radians per step, counter-clockwise.
  double period = 80;             // Steps.
  double breathing = 0.05;        // Relative size change, at the same period.
  std::vector<double> amplitude;  // Per cell; default 0.3 each.
  std::vector<double> phase;      // Per cell; default 0 each.
  int still_after = -1;  // From this step on e − c holds (-1: never).
  int steps = 4000;      // Motion steps; frames at 0, stride, ..., steps.
  int stride = 1;
  double dt = 0.05;
  double actuation_max = 0.2;

  int cells() const { return columns * rows; }
  double BodyX(int i) const {
    return ((i % columns) - (columns - 1) / 2.0) * spacing;
  }
  double BodyY(int i) const {
    return ((i / columns) - (rows - 1) / 2.0) * spacing;
  }
  double Amplitude(int i) const {
    return amplitude.empty() ? 0.3 : amplitude[i];
  }
  double Phase(int i) const { return phase.empty() ? 0.0 : phase[i]; }

  // A trace as `animat simulate --trace --every stride` would write it,
  // with a few equilibration frames before the motion.
  v1::Trace Trace() const {
    constexpr double kTwoPi = 2 * std::numbers::pi;
    v1::Trace trace;
    trace.mutable_config()->mutable_physics()->set_dt(dt);
    trace.mutable_config()->mutable_physics()->set_actuation_max(actuation_max);
    for (int i = 0; i < cells(); ++i) {
      v1::Node* node = trace.mutable_body()->add_nodes();
      node->set_x(BodyX(i));
      node->set_y(BodyY(i));
    }
    for (int i = 0; i < cells(); ++i) {
      const int column = i % columns;
      const int row = i / columns;
      if (column + 1 < columns) AddSpring(&trace, i, i + 1);
      if (row + 1 < rows) AddSpring(&trace, i, i + columns);
    }
    for (int step = 0; step < 3; ++step) {
      v1::MotionFrame* frame = trace.add_frames();
      frame->set_phase(v1::MotionFrame::EQUILIBRATION);
      frame->set_step(step);
      for (int i = 0; i < cells(); ++i) {
        frame->add_x(100.0 + i);  // Anything: the analysis ignores it.
        frame->add_y(0);
        frame->add_expand(0.5);
        frame->add_contract(0.5);
      }
    }
    double cx = 0;
    double cy = 0;
    for (int step = 0; step <= steps; ++step) {
      const double angle = heading + turn_rate * step;
      if (step > 0) {
        // Move along the heading halfway through the step.
        const double mid = heading + turn_rate * (step - 0.5);
        cx += speed * std::cos(mid);
        cy += speed * std::sin(mid);
      }
      if (step % stride != 0) continue;
      v1::MotionFrame* frame = trace.add_frames();
      frame->set_phase(v1::MotionFrame::MOTION);
      frame->set_step(step);
      const double size = 1 + breathing * std::cos(kTwoPi * step / period);
      for (int i = 0; i < cells(); ++i) {
        const double bx = BodyX(i) * size;
        const double by = BodyY(i) * size;
        frame->add_x(cx + std::cos(angle) * bx - std::sin(angle) * by);
        frame->add_y(cy + std::sin(angle) * bx + std::cos(angle) * by);
        frame->add_vx(0);
        frame->add_vy(0);
        const int acting =
            still_after >= 0 ? std::min(step, still_after) : step;
        const double a =
            Amplitude(i) * std::cos(kTwoPi * acting / period - Phase(i));
        frame->add_expand(0.5 + a / 2);
        frame->add_contract(0.5 - a / 2);
      }
    }
    trace.mutable_result()->set_status(v1::EvaluationResult::OK);
    return trace;
  }

 private:
  static void AddSpring(v1::Trace* trace, int a, int b) {
    v1::Spring* s = trace->mutable_body()->add_springs();
    s->set_a(a);
    s->set_b(b);
    s->set_rest_length(2);
  }
};

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_ANALYSIS_SYNTHETIC_SWIMMER_H_
