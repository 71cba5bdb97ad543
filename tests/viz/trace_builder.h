// Hand-made traces for the viz tests.
#ifndef ANIMAT_TESTS_VIZ_TRACE_BUILDER_H_
#define ANIMAT_TESTS_VIZ_TRACE_BUILDER_H_

#include <vector>

#include "animat/v1/trace.pb.h"

namespace animat::testing {

// A triangle body (nodes 0, 1, 2; three springs, all skin), two
// development snapshots (steps 0 and 9; one cell, then three), and motion
// frames at steps 0, 10 and 20 of equilibration then motion, each node
// shifted right by 0.1 per frame. Node 0's e - c rises by 0.05 between
// motion frames, node 1's falls, node 2's stays; equilibration is frozen.
inline v1::Trace TriangleTrace() {
  v1::Trace trace;
  trace.mutable_config()->mutable_development()->set_steps(10);
  trace.mutable_config()->mutable_evaluation()->set_equilibration_steps(20);
  trace.mutable_config()->mutable_evaluation()->set_motion_steps(20);
  v1::DevelopmentSnapshot* zygote = trace.add_development();
  zygote->set_step(0);
  zygote->add_x(0);
  zygote->add_y(0);
  zygote->add_radius(1);
  zygote->add_angle(0);
  v1::DevelopmentSnapshot* embryo = trace.add_development();
  embryo->set_step(9);
  const double xs[] = {0, 2, 1}, ys[] = {0, 0, 1.5};
  for (int i = 0; i < 3; ++i) {
    embryo->add_x(xs[i]);
    embryo->add_y(ys[i]);
    embryo->add_radius(1.25);
    embryo->add_angle(0);
    v1::Node* node = trace.mutable_body()->add_nodes();
    node->set_x(xs[i]);
    node->set_y(ys[i]);
  }
  const int edges[][2] = {{0, 1}, {0, 2}, {1, 2}};
  for (const auto& e : edges) {
    v1::Spring* spring = trace.mutable_body()->add_springs();
    spring->set_a(e[0]);
    spring->set_b(e[1]);
    v1::Edge* skin = trace.mutable_body()->add_skin();
    skin->set_a(e[0]);
    skin->set_b(e[1]);
  }
  int k = 0;
  for (const v1::MotionFrame::Phase phase :
       {v1::MotionFrame::EQUILIBRATION, v1::MotionFrame::MOTION}) {
    for (const int step : {0, 10, 20}) {
      v1::MotionFrame* frame = trace.add_frames();
      frame->set_phase(phase);
      frame->set_step(step);
      const double change =
          phase == v1::MotionFrame::MOTION ? 0.005 * step : 0.0;
      const double expand[] = {0.3 + change, 0.3, 0.3};
      const double contract[] = {0.2, 0.2 + change, 0.2};
      for (int i = 0; i < 3; ++i) {
        frame->add_x(xs[i] + 0.1 * k);
        frame->add_y(ys[i]);
        frame->add_vx(0);
        frame->add_vy(0);
        frame->add_expand(expand[i]);
        frame->add_contract(contract[i]);
      }
      ++k;
    }
  }
  trace.mutable_result()->set_status(v1::EvaluationResult::OK);
  trace.mutable_result()->set_fitness(0.30000000000000004);
  trace.mutable_result()->set_cells(3);
  trace.mutable_result()->set_steps(40);
  return trace;
}

// Four nodes in a ring joined by springs 0-1, 1-2, 2-3 and 3-0 (no
// diagonal; all skin), radii 1, 0.5, 1 and 0.5, no development, and frames
// at equilibration step 0 and motion steps 0 and 10. Joined nodes 0 and 1
// are 1.2 apart in every frame: their discs overlap by (1.5 - 1.2) / 1.5 =
// 20%. The unjoined pairs (0, 2) and (1, 3) do not overlap until motion
// step 10, where the ring folds and nodes 0 and 2 come 1.854 apart: an
// overlap of (2 - 1.854) / 2 = 7.3%. The result records a deepest unjoined
// overlap of 8.3% (max_overlap 0.083, as a v3 build would).
inline v1::Trace FoldingTrace() {
  v1::Trace trace;
  trace.mutable_config()->mutable_development()->set_steps(10);
  trace.mutable_config()->mutable_evaluation()->set_equilibration_steps(0);
  trace.mutable_config()->mutable_evaluation()->set_motion_steps(10);
  const double radii[] = {1, 0.5, 1, 0.5};
  const double open_x[] = {0, 1.2, 1.2, 0}, open_y[] = {0, 0, 2, 1.6};
  const double folded_x[] = {0, 1.2, 0, -1.2}, folded_y[] = {0, 0, 1.854, 0.9};
  for (int i = 0; i < 4; ++i) {
    v1::Node* node = trace.mutable_body()->add_nodes();
    node->set_x(open_x[i]);
    node->set_y(open_y[i]);
    node->set_radius(radii[i]);
    v1::Spring* spring = trace.mutable_body()->add_springs();
    spring->set_a(i);
    spring->set_b((i + 1) % 4);
    v1::Edge* skin = trace.mutable_body()->add_skin();
    skin->set_a(i);
    skin->set_b((i + 1) % 4);
  }
  struct Shown {
    v1::MotionFrame::Phase phase;
    int step;
    const double* x;
    const double* y;
  };
  for (const Shown& shown :
       {Shown{v1::MotionFrame::EQUILIBRATION, 0, open_x, open_y},
        Shown{v1::MotionFrame::MOTION, 0, open_x, open_y},
        Shown{v1::MotionFrame::MOTION, 10, folded_x, folded_y}}) {
    v1::MotionFrame* frame = trace.add_frames();
    frame->set_phase(shown.phase);
    frame->set_step(shown.step);
    for (int i = 0; i < 4; ++i) {
      frame->add_x(shown.x[i]);
      frame->add_y(shown.y[i]);
    }
  }
  trace.mutable_result()->set_status(v1::EvaluationResult::OK);
  trace.mutable_result()->set_fitness(0.5);
  trace.mutable_result()->set_cells(4);
  trace.mutable_result()->set_steps(10);
  trace.mutable_result()->set_max_overlap(0.083);
  return trace;
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_VIZ_TRACE_BUILDER_H_
