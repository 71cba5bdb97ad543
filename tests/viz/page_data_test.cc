#include "viz/page_data.h"

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <utility>

#include "tests/test_util.h"
#include "tests/viz/trace_builder.h"

namespace animat::viz {
namespace {

using google::protobuf::Struct;
using google::protobuf::Value;

// Parses the page data; fails the test when it is not JSON.
Struct Parse(const std::string& json) {
  Struct data;
  const auto status = google::protobuf::util::JsonStringToMessage(json, &data);
  EXPECT_TRUE(status.ok()) << status.ToString() << "\n" << json;
  return data;
}

const Value& Field(const Struct& s, const std::string& name) {
  static const Value kMissing;
  const auto it = s.fields().find(name);
  EXPECT_NE(it, s.fields().end()) << name;
  return it == s.fields().end() ? kMissing : it->second;
}

Struct Data(const v1::Trace& trace, const PageOptions& options = {}) {
  Result<std::string> json = PageDataJson(trace, options);
  EXPECT_TRUE(json.ok()) << json.status().message();
  return json.ok() ? Parse(*json) : Struct();
}

std::string Error(const v1::Trace& trace, const PageOptions& options = {}) {
  Result<std::string> json = PageDataJson(trace, options);
  EXPECT_FALSE(json.ok());
  EXPECT_EQ(json.status().code(), StatusCode::kInvalidArgument);
  return json.status().message();
}

TEST(PageDataTest, FramesAreDevelopmentThenEquilibrationThenMotion) {
  const Struct data = Data(testing::TriangleTrace());
  const auto& frames = Field(data, "frames").list_value().values();
  ASSERT_EQ(frames.size(), 8);
  const char* phases[] = {"development",   "development",   "equilibration",
                          "equilibration", "equilibration", "motion",
                          "motion",        "motion"};
  const int steps[] = {0, 9, 0, 10, 20, 0, 10, 20};
  for (int k = 0; k < 8; ++k) {
    const Struct& frame = frames[k].struct_value();
    EXPECT_EQ(Field(frame, "phase").string_value(), phases[k]) << k;
    EXPECT_EQ(Field(frame, "step").number_value(), steps[k]) << k;
  }
  // Development snapshots carry radii; body frames carry actuation.
  EXPECT_EQ(Field(frames[1].struct_value(), "r").list_value().values_size(), 3);
  EXPECT_EQ(frames[1].struct_value().fields().count("act"), 0u);
  EXPECT_EQ(frames[5].struct_value().fields().count("r"), 0u);
}

TEST(PageDataTest, ActuationFollowsTheChangeOfExpandMinusContract) {
  const Struct data = Data(testing::TriangleTrace());
  const auto& frames = Field(data, "frames").list_value().values();
  // Equilibration is frozen, and motion step 0 has not changed anything.
  for (int k = 2; k <= 5; ++k) {
    EXPECT_EQ(Field(frames[k].struct_value(), "act").string_value(), "nnn")
        << k;
  }
  EXPECT_EQ(Field(frames[6].struct_value(), "act").string_value(), "ecn");
  EXPECT_EQ(Field(frames[7].struct_value(), "act").string_value(), "ecn");
  // 0.05 per 10 steps is 5e-3 per step: neutral above that threshold.
  PageOptions slow;
  slow.neutral_rate = 6e-3;
  const Struct quiet = Data(testing::TriangleTrace(), slow);
  EXPECT_EQ(
      Field(Field(quiet, "frames").list_value().values(7).struct_value(), "act")
          .string_value(),
      "nnn");
  EXPECT_EQ(Field(quiet, "neutral_rate").number_value(), 6e-3);
}

TEST(PageDataTest, PositionsAreRoundedToFourDecimals) {
  v1::Trace trace = testing::TriangleTrace();
  trace.mutable_frames(0)->set_x(0, 1.23456789);
  trace.mutable_frames(0)->set_y(0, -0.00001);
  Result<std::string> json = PageDataJson(trace, {});
  ASSERT_TRUE(json.ok());
  // -0.00001 rounds to 0, not -0.
  EXPECT_NE(json->find("\"x\":[1.2346,2,1],\"y\":[0,0,1.5],\"act\""),
            std::string::npos)
      << *json;
}

TEST(PageDataTest, BodyEdgesAreFlatIndexPairs) {
  const Struct data = Data(testing::TriangleTrace());
  const auto& springs = Field(data, "springs").list_value().values();
  ASSERT_EQ(springs.size(), 6);
  const int expected[] = {0, 1, 0, 2, 1, 2};
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(springs[i].number_value(), expected[i]);
  }
  EXPECT_EQ(Field(data, "skin").list_value().values_size(), 6);
}

TEST(PageDataTest, ResultAndPhaseLengthsComeFromTheTrace) {
  const Struct data = Data(testing::TriangleTrace());
  const Struct& result = Field(data, "result").struct_value();
  EXPECT_EQ(Field(result, "status").string_value(), "ok");
  EXPECT_EQ(Field(result, "fitness").number_value(), 0.30000000000000004);
  EXPECT_EQ(Field(result, "cells").number_value(), 3);
  const Struct& lengths = Field(data, "lengths").struct_value();
  EXPECT_EQ(Field(lengths, "development").number_value(), 10);
  EXPECT_EQ(Field(lengths, "equilibration").number_value(), 20);
  EXPECT_EQ(Field(lengths, "motion").number_value(), 20);
}

// The body's radii, for the page's discs: exact, 1 where a node has none.
TEST(PageDataTest, RadiiAreTheBodysOnePerNode) {
  v1::Trace trace = testing::TriangleTrace();
  trace.mutable_body()->mutable_nodes(1)->set_radius(1.23456789);
  const Struct data = Data(trace);
  const auto& radii = Field(data, "radii").list_value().values();
  ASSERT_EQ(radii.size(), 3);
  EXPECT_EQ(radii[0].number_value(), 1);
  EXPECT_EQ(radii[1].number_value(), 1.23456789);
  EXPECT_EQ(radii[2].number_value(), 1);
  // Without a body (development only) there are none.
  trace.clear_body();
  trace.clear_frames();
  EXPECT_EQ(Field(Data(trace), "radii").list_value().values_size(), 0);
}

// The deepest unjoined overlap of the run (model v3): exact, null in a
// trace made before it.
TEST(PageDataTest, TheDeepestOverlapIsTheResultsOrNull) {
  const Struct folding = Data(testing::FoldingTrace());
  EXPECT_EQ(Field(Field(folding, "result").struct_value(), "max_overlap")
                .number_value(),
            0.083);
  const Struct older = Data(testing::TriangleTrace());
  EXPECT_EQ(
      Field(Field(older, "result").struct_value(), "max_overlap").kind_case(),
      Value::kNullValue);
}

// The model time per equilibration and motion step: the configuration's
// physics.dt, else its default.
TEST(PageDataTest, TheTimeStepIsTheConfigurationsOrTheDefault) {
  v1::Trace trace = testing::TriangleTrace();
  EXPECT_EQ(Field(Data(trace), "dt").number_value(), 0.05);
  trace.mutable_config()->mutable_physics()->set_dt(0.01);
  EXPECT_EQ(Field(Data(trace), "dt").number_value(), 0.01);
}

TEST(PageDataTest, WithoutAConfigurationTheLastStepsAreTheLengths) {
  v1::Trace trace = testing::TriangleTrace();
  trace.clear_config();
  trace.mutable_result()->set_status(v1::EvaluationResult::NUMERICAL_FAILURE);
  trace.mutable_result()->clear_fitness();
  trace.mutable_result()->set_reason("non-finite position");
  const Struct data = Data(trace);
  const Struct& lengths = Field(data, "lengths").struct_value();
  EXPECT_EQ(Field(lengths, "development").number_value(), 10);  // 0..9.
  EXPECT_EQ(Field(lengths, "equilibration").number_value(), 20);
  EXPECT_EQ(Field(lengths, "motion").number_value(), 20);
  const Struct& result = Field(data, "result").struct_value();
  EXPECT_EQ(Field(result, "status").string_value(), "numerical_failure");
  EXPECT_EQ(Field(result, "reason").string_value(), "non-finite position");
  EXPECT_EQ(Field(result, "fitness").kind_case(), Value::kNullValue);
}

TEST(PageDataTest, NonFiniteValuesBecomeNull) {
  testing::FpTrapsOff traps;
  v1::Trace trace = testing::TriangleTrace();
  trace.mutable_frames(5)->set_x(1, std::numeric_limits<double>::infinity());
  trace.mutable_frames(5)->set_y(2, std::numeric_limits<double>::quiet_NaN());
  const Struct data = Data(trace);
  const Struct& last =
      Field(data, "frames").list_value().values(7).struct_value();
  EXPECT_EQ(Field(last, "x").list_value().values(1).kind_case(),
            Value::kNullValue);
  EXPECT_EQ(Field(last, "y").list_value().values(2).kind_case(),
            Value::kNullValue);
}

TEST(PageDataTest, TitleIsEscapedForAScriptElement) {
  PageOptions options;
  options.title = "a \"b\" </script><b>&\\\n";
  Result<std::string> json = PageDataJson(testing::TriangleTrace(), options);
  ASSERT_TRUE(json.ok());
  EXPECT_EQ(json->find('<'), std::string::npos);
  EXPECT_EQ(json->find('>'), std::string::npos);
  EXPECT_EQ(json->find('&'), std::string::npos);
  EXPECT_EQ(Field(Parse(*json), "title").string_value(), options.title);
}

TEST(PageDataTest, ATraceWithNothingToShowNamesTheStatus) {
  v1::Trace trace;
  trace.mutable_result()->set_status(v1::EvaluationResult::NON_VIABLE);
  trace.mutable_result()->set_reason("no path from an input to a DIVIDE");
  EXPECT_EQ(Error(trace),
            "the trace has nothing to show (status non_viable: no path from "
            "an input to a DIVIDE)");
}

TEST(PageDataTest, LateDivisionShowsItsDevelopment) {
  v1::Trace trace = testing::TriangleTrace();
  trace.clear_body();
  trace.clear_frames();
  trace.mutable_result()->set_status(v1::EvaluationResult::LATE_DIVISION);
  const Struct data = Data(trace);
  EXPECT_EQ(Field(data, "frames").list_value().values_size(), 2);
  EXPECT_EQ(Field(data, "springs").list_value().values_size(), 0);
}

// Guidance (docs/model.md §10.2): the page holds every source and the
// recorded trial, for the page to draw the source and its gradient.
v1::Trace GuidanceTrace() {
  v1::Trace trace = testing::TriangleTrace();
  v1::GuidanceTrace* g = trace.mutable_guidance();
  g->set_trial(1);
  g->set_decay_length(10.0);
  for (const auto& [x, y] : {std::pair{21.25, 21.5},
                             {-21.25, 21.5},
                             {-21.25, -21.5},
                             {21.25, -21.5}}) {
    g->add_source_x(x);
    g->add_source_y(y);
  }
  return trace;
}

TEST(PageDataTest, TheSourcesAndTheRecordedTrialComeFromTheTrace) {
  const Struct data = Data(GuidanceTrace());
  const Struct& g = Field(data, "guidance").struct_value();
  EXPECT_EQ(Field(g, "trial").number_value(), 1);
  EXPECT_EQ(Field(g, "decay_length").number_value(), 10.0);
  const auto& sources = Field(g, "sources").list_value().values();
  ASSERT_EQ(sources.size(), 8);
  EXPECT_EQ(sources[2].number_value(), -21.25);
  EXPECT_EQ(sources[3].number_value(), 21.5);
  // Without guidance there is no such field.
  EXPECT_EQ(Data(testing::TriangleTrace()).fields().count("guidance"), 0u);
}

TEST(PageDataTest, BadGuidanceIsRejectedSayingWhy) {
  v1::Trace trace = GuidanceTrace();
  trace.mutable_guidance()->add_source_x(1.0);
  EXPECT_EQ(Error(trace),
            "guidance: source_x and source_y have 5 and 4 values (one per "
            "trial, at least one)");
  trace = GuidanceTrace();
  trace.mutable_guidance()->set_trial(4);
  EXPECT_EQ(Error(trace), "guidance: trial 4 of 4 sources");
  trace = GuidanceTrace();
  trace.mutable_guidance()->set_decay_length(0.0);
  EXPECT_EQ(Error(trace), "guidance: decay_length must be finite and > 0");
  trace = GuidanceTrace();
  {
    testing::FpTrapsOff traps_off;
    trace.mutable_guidance()->set_source_y(
        2, std::numeric_limits<double>::infinity());
    EXPECT_EQ(Error(trace), "guidance: sources[2] is not finite");
  }
}

TEST(PageDataTest, InconsistentTracesAreRejectedSayingWhere) {
  v1::Trace trace = testing::TriangleTrace();
  trace.mutable_development(1)->add_y(0);
  EXPECT_EQ(Error(trace),
            "development[1]: x, y and radius have 3, 4 and 3 values");

  trace = testing::TriangleTrace();
  trace.mutable_development(1)->set_step(0);
  EXPECT_EQ(Error(trace), "development[1]: step 0 does not follow step 0");

  trace = testing::TriangleTrace();
  trace.mutable_frames(3)->add_expand(1);
  EXPECT_EQ(Error(trace),
            "frames[3]: expand and contract need one value per node (3) or "
            "none, got 4");

  trace = testing::TriangleTrace();
  trace.mutable_frames(4)->add_x(1);
  trace.mutable_frames(4)->add_y(1);
  trace.mutable_frames(4)->clear_expand();
  trace.mutable_frames(4)->clear_contract();
  EXPECT_EQ(Error(trace), "frames[4]: 4 nodes, the body has 3");

  trace = testing::TriangleTrace();
  trace.mutable_frames(2)->set_phase(v1::MotionFrame::PHASE_UNSPECIFIED);
  EXPECT_EQ(Error(trace), "frames[2]: phase is unspecified");

  trace = testing::TriangleTrace();
  trace.mutable_frames(5)->set_step(10);
  EXPECT_EQ(Error(trace),
            "frames[5]: motion step 10 does not follow motion step 10");

  trace = testing::TriangleTrace();
  for (int k : {3, 4, 5}) {
    trace.mutable_frames(k)->set_phase(v1::MotionFrame::EQUILIBRATION);
  }
  trace.mutable_frames(2)->set_phase(v1::MotionFrame::MOTION);
  EXPECT_EQ(Error(trace),
            "frames[3]: equilibration step 0 does not follow motion step 20");

  trace = testing::TriangleTrace();
  trace.mutable_body()->mutable_springs(1)->set_b(3);
  EXPECT_EQ(Error(trace), "body.springs[1]: nodes 0 and 3, the body has 3");

  trace = testing::TriangleTrace();
  trace.mutable_body()->mutable_nodes(2)->set_radius(0);
  EXPECT_EQ(Error(trace), "body.nodes[2].radius must be finite and > 0");
  {
    testing::FpTrapsOff traps_off;
    trace.mutable_body()->mutable_nodes(2)->set_radius(
        std::numeric_limits<double>::quiet_NaN());
    EXPECT_EQ(Error(trace), "body.nodes[2].radius must be finite and > 0");
  }

  trace = testing::FoldingTrace();
  trace.mutable_result()->set_max_overlap(1.5);
  EXPECT_EQ(Error(trace), "result.max_overlap is 1.5, not in [0, 1]");
  trace.mutable_result()->set_max_overlap(-0.25);
  EXPECT_EQ(Error(trace), "result.max_overlap is -0.25, not in [0, 1]");
  {
    testing::FpTrapsOff traps_off;
    trace.mutable_result()->set_max_overlap(
        std::numeric_limits<double>::infinity());
    EXPECT_EQ(Error(trace), "result.max_overlap is not finite");
  }

  PageOptions negative;
  negative.neutral_rate = -1;
  EXPECT_EQ(Error(testing::TriangleTrace(), negative),
            "the neutral rate must be finite and >= 0");
}

}  // namespace
}  // namespace animat::viz
