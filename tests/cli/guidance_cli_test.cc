// End-to-end tests of active guidance (docs/model.md §10.2) in the tool:
// `simulate --trial` and its trace, the replay page's source, and `figure
// guidance`. The real binary on a real genome.
#include <unistd.h>

#include <gtest/gtest.h>

#include <string>

#include "animat/v1/trace.pb.h"
#include "common/io/proto_file.h"
#include "tests/cli/run_animat.h"
#include "tests/svg/xml.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using ::animat::testing::Animat;
using ::animat::testing::Outcome;

std::string Temp(const std::string& name) {
  return ::testing::TempDir() + "/animat-guidance-" + std::to_string(getpid()) +
         "-" + name;
}

// seed-1203 grows a chain (no chamber); a short motion.
std::string Config(bool guidance) {
  const std::string path = Temp(guidance ? "on.txtpb" : "off.txtpb");
  EXPECT_TRUE(
      WriteFile(path,
                std::string("evaluation { motion_steps: 600 min_chambers: 0 "
                            "}\nguidance { enabled: ") +
                    (guidance ? "true" : "false") + " }\n")
          .ok());
  return path;
}

std::string Genome() { return testing::TestData("genomes/seed-1203.json"); }

TEST(GuidanceCliTest, SimulateRecordsTheSourcesAndTheChosenTrial) {
  const std::string trace_path = Temp("trial.binpb");
  const Outcome run =
      Animat("simulate --genome " + Genome() + " --config " + Config(true) +
             " --trace " + trace_path + " --every 100 --trial 2");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("source_distances: ["), std::string::npos)
      << run.output;
  v1::Trace trace;
  ASSERT_TRUE(ReadProtoFile(trace_path, &trace).ok());
  ASSERT_TRUE(trace.has_guidance());
  EXPECT_EQ(trace.guidance().trial(), 2);
  EXPECT_EQ(trace.guidance().source_x_size(), 4);
  EXPECT_EQ(trace.guidance().source_y_size(), 4);
  EXPECT_EQ(trace.guidance().decay_length(), 10.0);
  EXPECT_EQ(trace.result().source_distances_size(), 4);

  // The replay page carries the sources.
  const std::string page = Temp("page.html");
  const Outcome render = Animat("render --trace " + trace_path + " -o " + page);
  ASSERT_EQ(render.exit_code, 0) << render.output;
  Result<std::string> html = ReadFile(page);
  ASSERT_TRUE(html.ok());
  EXPECT_NE(html->find("\"guidance\":{\"trial\":2,"), std::string::npos);
}

TEST(GuidanceCliTest, ATrialOutOfRangeIsRefused) {
  Outcome run = Animat("simulate --genome " + Genome() + " --config " +
                       Config(true) + " --trial 4");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("4 guidance trials"), std::string::npos)
      << run.output;
  run = Animat("simulate --genome " + Genome() + " --config " + Config(false) +
               " --trial 1");
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("guidance is off"), std::string::npos)
      << run.output;
}

TEST(GuidanceCliTest, FigureDrawsEveryTrialAroundItsSource) {
  const std::string svg = Temp("trials.svg");
  const Outcome run =
      Animat("figure guidance --genome " + Genome() + " --config " +
             Config(true) + " --every 20 -o " + svg);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  Result<std::string> text = ReadFile(svg);
  ASSERT_TRUE(text.ok());
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(*text);
  ASSERT_TRUE(root.has_value()) << reader.error();
  EXPECT_EQ(root->FindAll("g", "trial").size(), 4u);
  EXPECT_EQ(root->FindAll("polyline", "path").size(), 4u);
  EXPECT_EQ(root->FindAll("circle", "source").size(), 4u);

  const Outcome off = Animat("figure guidance --genome " + Genome() +
                             " --config " + Config(false) + " -o " + svg);
  EXPECT_EQ(off.exit_code, 1) << off.output;
  EXPECT_NE(off.output.find("guidance { enabled: true }"), std::string::npos)
      << off.output;
}

}  // namespace
}  // namespace animat
