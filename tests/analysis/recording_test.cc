#include "analysis/recording.h"

#include <gtest/gtest.h>

#include <limits>

#include "tests/analysis/synthetic_swimmer.h"
#include "tests/test_util.h"

namespace animat::analysis {
namespace {

TEST(RecordingTest, ReadsOnlyTheMotionFrames) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 100;
  swimmer.stride = 10;
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->cells, 8);
  EXPECT_EQ(r->stride, 10);
  ASSERT_EQ(r->frames(), 11);
  EXPECT_EQ(r->steps.front(), 0);
  EXPECT_EQ(r->steps.back(), 100);
  EXPECT_EQ(r->springs.size(), 10u);  // 3 × 2 along rows, 4 across.
  EXPECT_DOUBLE_EQ(r->dt, 0.05);
  // Frame 0 is the swimmer at the origin, not an equilibration frame.
  EXPECT_NEAR(r->CentreOfMass(0).x, 0, 1e-12);
  // e − c is the synthetic actuation: A cos(0) at step 0.
  EXPECT_NEAR(r->actuation(0, 3), 0.3, 1e-12);
}

TEST(RecordingTest, DropsAnIrregularLastFrame) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 95;
  swimmer.stride = 10;
  v1::Trace trace = swimmer.Trace();
  v1::MotionFrame last = trace.frames(trace.frames_size() - 1);
  last.set_step(95);  // What the recorder writes at a phase's last step.
  *trace.add_frames() = last;
  Result<Recording> r = RecordingFromTrace(trace);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->steps.back(), 90);
}

TEST(RecordingTest, RejectsUnevenSpacing) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 100;
  swimmer.stride = 10;
  v1::Trace trace = swimmer.Trace();
  trace.mutable_frames(3 + 4)->set_step(45);
  Result<Recording> r = RecordingFromTrace(trace);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("spacing"), std::string::npos)
      << r.status().message();
}

TEST(RecordingTest, AFailedEvaluationSaysWhy) {
  v1::Trace trace;
  trace.mutable_result()->set_status(v1::EvaluationResult::NON_VIABLE);
  trace.mutable_result()->set_reason(
      "no path from an input to a DIVIDE output");
  Result<Recording> r = RecordingFromTrace(trace);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("no path from an input"),
            std::string::npos)
      << r.status().message();
}

TEST(RecordingTest, RejectsMissingActuationAndNonFiniteValues) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 20;
  v1::Trace missing = swimmer.Trace();
  missing.mutable_frames(5)->clear_contract();
  EXPECT_FALSE(RecordingFromTrace(missing).ok());

  testing::FpTrapsOff traps_off;
  v1::Trace nan = swimmer.Trace();
  nan.mutable_frames(6)->set_x(2, std::numeric_limits<double>::quiet_NaN());
  Result<Recording> r = RecordingFromTrace(nan);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("not finite"), std::string::npos);
}

TEST(RecordingTest, RejectsASpringToAMissingCell) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 20;
  v1::Trace trace = swimmer.Trace();
  trace.mutable_body()->mutable_springs(0)->set_b(8);
  EXPECT_FALSE(RecordingFromTrace(trace).ok());
}

// Each cell's radius is its body node's, 1 where the node has none.
TEST(RecordingTest, RadiiAreTheBodysOrOne) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 20;
  v1::Trace trace = swimmer.Trace();
  trace.mutable_body()->mutable_nodes(3)->set_radius(1.375);
  Result<Recording> r = RecordingFromTrace(trace);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->radius, (std::vector<double>{1, 1, 1, 1.375, 1, 1, 1, 1}));

  trace.mutable_body()->clear_nodes();
  r = RecordingFromTrace(trace);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->radius, std::vector<double>(8, 1.0));
}

TEST(RecordingTest, RejectsABodyThatDisagreesWithTheFrames) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 20;
  v1::Trace trace = swimmer.Trace();
  trace.mutable_body()->mutable_nodes(5)->set_radius(0);
  Result<Recording> r = RecordingFromTrace(trace);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "trace body: nodes[5].radius must be finite and > 0");

  trace = swimmer.Trace();
  trace.mutable_body()->add_nodes();
  r = RecordingFromTrace(trace);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "trace body: 9 nodes, the frames have 8 cells");
}

TEST(RecordingTest, FrameAtOrAfterSnapsToRecordedSteps) {
  testing::SyntheticSwimmer swimmer;
  swimmer.steps = 100;
  swimmer.stride = 10;
  Result<Recording> r = RecordingFromTrace(swimmer.Trace());
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(FrameAtOrAfter(*r, 0), 0);
  EXPECT_EQ(FrameAtOrAfter(*r, 31), 4);
  EXPECT_EQ(FrameAtOrAfter(*r, 40), 4);
  EXPECT_EQ(FrameAtOrAfter(*r, 101), 11);
}

}  // namespace
}  // namespace animat::analysis
