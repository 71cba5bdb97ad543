// End-to-end tests of `animat render` (the page's behaviour in a browser is
// tests/viz/browser_test.cc): the real binary, real files, a real store.
#include <sys/wait.h>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "animat/v1/trace.pb.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "master/lineage/store.h"
#include "tests/cli/run_animat.h"
#include "tests/lineage/lineage_test_util.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using google::protobuf::Struct;
using google::protobuf::Value;

using ::animat::testing::Animat;
using ::animat::testing::Outcome;

std::string Temp(const std::string& name) {
  return ::testing::TempDir() + "/animat-render-" + name;
}

const char kShort[] =
    "evaluation { equilibration_steps: 40 motion_steps: 200 }";

std::string ShortConfig() {
  const std::string path = Temp("short.txtpb");
  EXPECT_TRUE(WriteFile(path, std::string(kShort) + "\n").ok());
  return path;
}

std::string Genome() { return testing::TestData("genomes/seed-1198.json"); }

// The page's data (ANIMAT_DATA), parsed.
Struct PageData(const std::string& page_path) {
  Result<std::string> page = ReadFile(page_path);
  EXPECT_TRUE(page.ok()) << page.status().message();
  if (!page.ok()) return {};
  const std::string start = "const ANIMAT_DATA = ";
  const size_t from = page->find(start);
  const size_t to = page->find(";</script>", from);
  EXPECT_NE(from, std::string::npos);
  Struct data;
  const auto status = google::protobuf::util::JsonStringToMessage(
      page->substr(from + start.size(), to - from - start.size()), &data);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return data;
}

const Value& Field(const Struct& s, const std::string& name) {
  static const Value kMissing;
  const auto it = s.fields().find(name);
  EXPECT_NE(it, s.fields().end()) << name;
  return it == s.fields().end() ? kMissing : it->second;
}

// (phase, step) of every frame, as the page lists them.
std::vector<std::pair<std::string, int>> PageFrames(const Struct& data) {
  std::vector<std::pair<std::string, int>> frames;
  for (const Value& f : Field(data, "frames").list_value().values()) {
    frames.emplace_back(
        Field(f.struct_value(), "phase").string_value(),
        static_cast<int>(Field(f.struct_value(), "step").number_value()));
  }
  return frames;
}

std::vector<std::pair<std::string, int>> TraceFrames(const v1::Trace& trace) {
  std::vector<std::pair<std::string, int>> frames;
  for (const v1::DevelopmentSnapshot& s : trace.development()) {
    frames.emplace_back("development", s.step());
  }
  for (const v1::MotionFrame& f : trace.frames()) {
    frames.emplace_back(f.phase() == v1::MotionFrame::EQUILIBRATION
                            ? "equilibration"
                            : "motion",
                        f.step());
  }
  return frames;
}

TEST(RenderTest, AGenomesPageHoldsEveryFrameOfItsTrace) {
  const std::string config = ShortConfig();
  ASSERT_EQ(Animat("simulate --genome " + Genome() + " --config " + config +
                   " --every 20 --trace " + Temp("trace.binpb"))
                .exit_code,
            0);
  const Outcome run = Animat("render --genome " + Genome() + " --config " +
                             config + " --every 20 -o " + Temp("g.html"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("21 development snapshots, 14 motion frames"),
            std::string::npos)
      << run.output;
  v1::Trace trace;
  ASSERT_TRUE(ReadProtoFile(Temp("trace.binpb"), &trace).ok());
  const Struct data = PageData(Temp("g.html"));
  EXPECT_EQ(PageFrames(data), TraceFrames(trace));
  const Struct& result = Field(data, "result").struct_value();
  EXPECT_EQ(Field(result, "status").string_value(), "ok");
  EXPECT_EQ(Field(result, "fitness").number_value(), trace.result().fitness());
  EXPECT_EQ(
      Field(Field(data, "lengths").struct_value(), "motion").number_value(),
      200);
  // The genome's file name, not its path.
  EXPECT_EQ(Field(data, "title").string_value(), "seed-1198.json");
  EXPECT_EQ(Field(data, "dt").number_value(), 0.05);
}

TEST(RenderTest, AStoredIndividualIsSimulatedUnderItsRunsConfiguration) {
  testing::TempStorePath db("render");
  v1::Genome genome;
  ASSERT_TRUE(ReadProtoFile(Genome(), &genome).ok());
  {
    Result<std::unique_ptr<lineage::Store>> store =
        lineage::Store::Open(db.path());
    ASSERT_TRUE(store.ok()) << store.status().message();
    v1::RunConfig config;
    ASSERT_TRUE(
        ParseProto(kShort, ProtoFormat::kText, config.mutable_model()).ok());
    Result<int64_t> run = (*store)->CreateRun(1, config, "test");
    ASSERT_TRUE(run.ok());
    lineage::NewIndividual individual = testing::MakeIndividual(7, 3);
    individual.genome = genome;
    ASSERT_TRUE((*store)->AddIndividuals(*run, {individual}).ok());
    // Not what this build computes: render says so.
    ASSERT_TRUE((*store)
                    ->RecordEvaluations(*run, {testing::OkEvaluation(7, 1.5)})
                    .ok());
  }
  const Outcome run =
      Animat("render --db " + db.path() + " --individual 7 --every 20 -o " +
             Temp("db.html"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("note: the store's fitness of individual 7 of "
                            "run 1 is 1.5, this build gives "),
            std::string::npos)
      << run.output;

  ModelConfig config;
  v1::Config message;
  ASSERT_TRUE(ParseProto(kShort, ProtoFormat::kText, &message).ok());
  ASSERT_TRUE(ConfigFromProto(message, &config).ok());
  const EvaluationResult expected = Evaluate(*GenomeFromProto(genome), config);
  ASSERT_TRUE(expected.fitness.has_value());
  const Struct data = PageData(Temp("db.html"));
  EXPECT_EQ(Field(data, "title").string_value(),
            "individual 7 of run 1 (generation 3) of " +
                std::filesystem::path(db.path()).filename().string());
  EXPECT_EQ(
      Field(Field(data, "result").struct_value(), "fitness").number_value(),
      *expected.fitness);
  EXPECT_EQ(
      Field(Field(data, "lengths").struct_value(), "motion").number_value(),
      200);

  const Outcome unknown = Animat("render --db " + db.path() +
                                 " --individual 8 -o " + Temp("no.html"));
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.output.find(db.path()), std::string::npos)
      << unknown.output;
}

TEST(RenderTest, WhatCannotBeShownIsAnErrorSayingWhy) {
  const Outcome nonviable = Animat(
      "render --genome " + testing::TestData("genomes/seed-1-nonviable.json") +
      " -o " + Temp("nv.html"));
  EXPECT_EQ(nonviable.exit_code, 1);
  EXPECT_NE(nonviable.output.find("nothing to show (status non_viable: "),
            std::string::npos)
      << nonviable.output;
  const Outcome missing =
      Animat("render --trace " + Temp("absent.json") + " -o " + Temp("x.html"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.output.find("absent.json"), std::string::npos)
      << missing.output;
}

TEST(RenderTest, UsageErrorsExitWithTwo) {
  const std::string out = " -o " + Temp("u.html");
  for (const std::string& arguments :
       {"render" + out, "render --genome a.json --trace b.json" + out,
        "render --db a.db" + out, "render --individual 3" + out,
        "render --trace b.json --config c.txtpb" + out,
        "render --genome a.json --every 0" + out}) {
    const Outcome run = Animat(arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments << "\n" << run.output;
  }
}

}  // namespace
}  // namespace animat
