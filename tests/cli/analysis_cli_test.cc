// End-to-end tests of `animat analyze` and `animat figure`: the real
// binary, real genomes, a real lineage store; figures checked as XML.
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "animat/v1/analysis.pb.h"
#include "animat/v1/trace.pb.h"
#include "common/base/text.h"
#include "common/io/proto_file.h"
#include "master/lineage/store.h"
#include "tests/cli/run_animat.h"
#include "tests/svg/xml.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using ::animat::testing::Animat;
using ::animat::testing::Outcome;

std::string Temp(const std::string& name) {
  return ::testing::TempDir() + "/animat-analysis-" + std::to_string(getpid()) +
         "-" + name;
}

// 1200 motion steps: several periods of the sample swimmer, quickly.
constexpr char kShortModel[] = "evaluation { motion_steps: 1200 }\n";

std::string ShortConfig() {
  const std::string path = Temp("short.txtpb");
  EXPECT_TRUE(WriteFile(path, kShortModel).ok());
  return path;
}

std::string Swimmer() { return testing::TestData("genomes/seed-1198.json"); }

testing::XmlElement ParseSvg(const std::string& path) {
  Result<std::string> text = ReadFile(path);
  EXPECT_TRUE(text.ok()) << path;
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root =
      reader.Parse(text.ok() ? *text : "");
  EXPECT_TRUE(root.has_value()) << path << ": " << reader.error();
  EXPECT_EQ(root.has_value() ? root->name : "", "svg");
  return root.value_or(testing::XmlElement{});
}

v1::Analysis ReadAnalysis(const std::string& path) {
  v1::Analysis analysis;
  Status status = ReadProtoFile(path, &analysis);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return analysis;
}

TEST(AnalysisCliTest, AnalyzeOfAGenomeMatchesAnalyzeOfItsTrace) {
  const std::string config = ShortConfig();
  const Outcome simulate =
      Animat("simulate --genome " + Swimmer() + " --config " + config +
             " --trace " + Temp("trace.binpb") + " --every 1");
  ASSERT_EQ(simulate.exit_code, 0) << simulate.output;
  const Outcome from_genome =
      Animat("analyze --genome " + Swimmer() + " --config " + config + " -o " +
             Temp("genome.json"));
  ASSERT_EQ(from_genome.exit_code, 0) << from_genome.output;
  const Outcome from_trace = Animat("analyze --trace " + Temp("trace.binpb") +
                                    " -o " + Temp("trace.json"));
  ASSERT_EQ(from_trace.exit_code, 0) << from_trace.output;
  EXPECT_EQ(*ReadFile(Temp("genome.json")), *ReadFile(Temp("trace.json")));

  const v1::Analysis a = ReadAnalysis(Temp("genome.json"));
  EXPECT_EQ(a.from_step(), 600);  // The second half by default.
  EXPECT_EQ(a.to_step(), 1200);
  EXPECT_EQ(a.window_rule(), v1::Analysis::SECOND_HALF);
  EXPECT_EQ(a.stride(), 1);
  EXPECT_EQ(a.cells(), 32);
  EXPECT_EQ(a.cell_size(), 32);
  EXPECT_TRUE(a.has_fitness());
  EXPECT_TRUE(a.has_period_steps());
  EXPECT_EQ(a.front().cells() + a.back().cells(), 32);
  EXPECT_FALSE(a.drivers().empty());
  // The fitness is the simulation's.
  const std::string fitness_line =
      simulate.output.substr(simulate.output.find("fitness: ") + 9);
  EXPECT_EQ(a.fitness(), std::stod(fitness_line));
}

TEST(AnalysisCliTest, TheLabelItsMarginAndStabilityArePrintedAndWritten) {
  const Outcome to_file =
      Animat("analyze --genome " + Swimmer() + " --config " + ShortConfig() +
             " -o " + Temp("stability.json"));
  ASSERT_EQ(to_file.exit_code, 0) << to_file.output;
  const v1::Analysis a = ReadAnalysis(Temp("stability.json"));
  const v1::StrategyAnalysis& s = a.strategy();
  EXPECT_NE(to_file.output.find("strategy: "), std::string::npos)
      << to_file.output;
  // Either stable, or the moves that change the label are listed.
  const bool stable = s.stable();
  EXPECT_NE(to_file.output.find(stable ? "  stable: " : "  sensitive to "),
            std::string::npos)
      << to_file.output;
  EXPECT_EQ(s.shift_fraction(), 0.2);
  EXPECT_GT(s.shift_size(), 0);
  int changed = 0;
  for (const v1::ThresholdShift& shift : s.shift()) {
    EXPECT_EQ(shift.survives(), shift.label() == s.label());
    changed += shift.survives() ? 0 : 1;
  }
  EXPECT_EQ(stable, changed == 0);
  EXPECT_TRUE(s.features().has_lr_symmetry_rectified());
  EXPECT_NE(s.rectified_label(), v1::StrategyAnalysis::LABEL_UNSPECIFIED);
  ASSERT_EQ(s.score_size(), 4);
  EXPECT_GT(s.score(3).descriptor_term_size(), 0);
  // JSON on standard output: the label and stability on standard error
  // (RunTool reads both).
  const Outcome to_stdout = Animat("analyze --genome " + Swimmer() +
                                   " --config " + ShortConfig() + " -o -");
  ASSERT_EQ(to_stdout.exit_code, 0) << to_stdout.output;
  EXPECT_NE(to_stdout.output.find("strategy: "), std::string::npos);
  EXPECT_NE(to_stdout.output.find(stable ? "  stable: " : "  sensitive to "),
            std::string::npos);
}

TEST(AnalysisCliTest, ClusterAnalysesEachGenomeAndWritesTheClustering) {
  const std::string a = Swimmer();
  const std::string b =
      testing::TestData("genomes/evolved-stops-actuating.json");
  const Outcome run =
      Animat("cluster --genome " + a + " --genome " + b + " --genome " + a +
             " --config " + ShortConfig() + " -o " + Temp("clusters.json") +
             " --svg " + Temp("clusters.svg"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("seed-1198  "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("adjusted Rand index against the labels"),
            std::string::npos)
      << run.output;
  v1::StrategyClustering c;
  ASSERT_TRUE(ReadProtoFile(Temp("clusters.json"), &c).ok());
  ASSERT_EQ(c.animat_size(), 3);
  EXPECT_EQ(c.animat(0).name(), "seed-1198");
  // The same genome twice: the same features, the same cluster.
  EXPECT_EQ(c.animat(0).pc1(), c.animat(2).pc1());
  EXPECT_EQ(c.animat(0).cluster(), c.animat(2).cluster());
  EXPECT_TRUE(c.animat(0).has_fitness());
  EXPECT_EQ(ParseSvg(Temp("clusters.svg")).FindAll("g", "animat").size(), 3u);

  const Outcome both =
      Animat("cluster --genome " + a + " --db " + Temp("x.db"));
  EXPECT_EQ(both.exit_code, 1) << both.output;
  const Outcome store_config =
      Animat("cluster --db " + Temp("x.db") + " --config " + ShortConfig());
  EXPECT_EQ(store_config.exit_code, 1) << store_config.output;
  EXPECT_NE(store_config.output.find("--config goes with --genome"),
            std::string::npos)
      << store_config.output;
  const Outcome configs =
      Animat("cluster --genome " + a + " --genome " + b + " --genome " + a +
             " --config " + ShortConfig() + " --config " + ShortConfig());
  EXPECT_EQ(configs.exit_code, 1) << configs.output;
  EXPECT_NE(configs.output.find("one per --genome"), std::string::npos)
      << configs.output;
}

TEST(AnalysisCliTest, TheWindowAndSpacingAreChosen) {
  const Outcome run =
      Animat("analyze --genome " + Swimmer() + " --config " + ShortConfig() +
             " --every 4 --from 100 --to 1000 -o " + Temp("window.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const v1::Analysis a = ReadAnalysis(Temp("window.json"));
  EXPECT_EQ(a.from_step(), 100);
  EXPECT_EQ(a.to_step(), 1000);
  EXPECT_EQ(a.stride(), 4);
  EXPECT_EQ(a.window_rule(), v1::Analysis::GIVEN);
  EXPECT_EQ(
      run.output.rfind("window: motion steps 100 to 1000 (as asked)\n", 0), 0u)
      << run.output;
}

// An evolved animat whose actuation dies away within ~540 motion steps
// (bench/data/accuracy's evolved-dn10-g039-38539, under its drag): with
// 1200 motion steps the second half holds no actuation.
TEST(AnalysisCliTest, AnAnimatThatStopsActuatingIsAnalysedWhereItActuates) {
  const std::string config = Temp("stops.txtpb");
  ASSERT_TRUE(
      WriteFile(config, "physics { drag_normal: 10 drag_tangential: 0.05 }\n" +
                            std::string(kShortModel))
          .ok());
  const std::string source =
      "--genome " + testing::TestData("genomes/evolved-stops-actuating.json") +
      " --config " + config;
  const Outcome analyze =
      Animat("analyze " + source + " -o " + Temp("stops.json"));
  ASSERT_EQ(analyze.exit_code, 0) << analyze.output;
  const v1::Analysis a = ReadAnalysis(Temp("stops.json"));
  EXPECT_EQ(a.window_rule(), v1::Analysis::ACTUATING);
  EXPECT_EQ(a.from_step(), 0);
  EXPECT_LT(a.to_step(), 600);
  EXPECT_EQ(a.actuation_to_step(), a.to_step());
  EXPECT_TRUE(a.has_period_steps());
  EXPECT_GT(a.mean_activity(), 0);
  const std::string window =
      "window: motion steps 0 to " + std::to_string(a.to_step()) +
      " (where the animat actuates: no cell does in the second half of the "
      "motion)\n";
  EXPECT_EQ(analyze.output.rfind(window, 0), 0u) << analyze.output;

  // The README's strip of such an animat: a cycle where it actuates.
  const Outcome strip =
      Animat("figure strip " + source + " -o " + Temp("stops.svg"));
  ASSERT_EQ(strip.exit_code, 0) << strip.output;
  EXPECT_EQ(strip.output, window);
  EXPECT_EQ(ParseSvg(Temp("stops.svg")).FindAll("g", "snapshot").size(), 6u);

  // A window without actuation (what is left is slower than 2e-4 per step)
  // says where the actuation is.
  const Outcome late =
      Animat("analyze " + source + " --from 600 -o " + Temp("late.json"));
  ASSERT_EQ(late.exit_code, 0) << late.output;
  EXPECT_EQ(late.output.rfind(
                "window: motion steps 600 to 1200 (as asked); no cell "
                "actuates in it: the animat actuates in motion steps 0 to " +
                    std::to_string(a.to_step()) + " (--from 0 --to " +
                    std::to_string(a.to_step()) + ")\n",
                0),
            0u)
      << late.output;
}

// A quickstart individual that swam 3.4 radii in its run without ever
// actuating (its e − c is constant through the motion): zero activity, and
// why.
TEST(AnalysisCliTest, AnAnimatThatNeverActuatesIsSaidToBeSo) {
  const std::string source =
      "--genome " + testing::TestData("genomes/quickstart-no-actuation.json") +
      " --config " + ShortConfig();
  const Outcome analyze =
      Animat("analyze " + source + " -o " + Temp("still.json"));
  ASSERT_EQ(analyze.exit_code, 0) << analyze.output;
  const std::string window =
      "window: motion steps 600 to 1200 (the second half of the motion); no "
      "cell actuates anywhere in the motion (no e − c changes by more than "
      "0.0002 per step)\n";
  EXPECT_EQ(analyze.output.rfind(window, 0), 0u) << analyze.output;
  const v1::Analysis a = ReadAnalysis(Temp("still.json"));
  EXPECT_EQ(a.window_rule(), v1::Analysis::SECOND_HALF);
  EXPECT_FALSE(a.has_actuation_from_step());
  EXPECT_EQ(a.mean_activity(), 0);

  const Outcome strip =
      Animat("figure strip " + source + " -o " + Temp("still.svg"));
  EXPECT_EQ(strip.exit_code, 1);
  EXPECT_EQ(strip.output,
            "animat: the actuation has no dominant period in motion steps 600 "
            "to 1200 (the second half of the motion); no cell actuates "
            "anywhere in the motion (no e − c changes by more than 0.0002 per "
            "step), so there is no cycle to show\n");
}

TEST(AnalysisCliTest, BadInputIsAClearError) {
  const Outcome none = Animat("analyze");
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.output.find("exactly one of --genome"), std::string::npos)
      << none.output;
  const Outcome two = Animat("analyze --genome " + Swimmer() + " --trace " +
                             Temp("trace.binpb"));
  EXPECT_EQ(two.exit_code, 1);
  const Outcome failed = Animat(
      "analyze --genome " + testing::TestData("genomes/seed-1-nonviable.json"));
  EXPECT_EQ(failed.exit_code, 1);
  EXPECT_NE(failed.output.find("no path from an input"), std::string::npos)
      << failed.output;
  const Outcome window = Animat("analyze --genome " + Swimmer() + " --config " +
                                ShortConfig() + " --from 5000");
  EXPECT_EQ(window.exit_code, 1);
  EXPECT_NE(window.output.find("window"), std::string::npos) << window.output;
  const Outcome missing = Animat("analyze --trace " + Temp("nowhere.json"));
  EXPECT_EQ(missing.exit_code, 1);
  const Outcome no_id = Animat("analyze --db " + Temp("nowhere.db"));
  EXPECT_EQ(no_id.exit_code, 1);
  const Outcome not_svg = Animat("figure activity --genome " + Swimmer() +
                                 " -o " + Temp("activity.png"));
  EXPECT_EQ(not_svg.exit_code, 1);
  EXPECT_NE(not_svg.output.find(".svg"), std::string::npos);
}

// Knock-outs (docs/analysis.md): a genome of a guidance run's initial
// population, with a CHEMICAL input and five morphogens that motion uses.
std::string GuidedGenome() {
  return testing::TestData("genomes/guidance-seed1-103991.json");
}

std::string GuidanceConfig() {
  const std::string path = Temp("guidance.txtpb");
  EXPECT_TRUE(WriteFile(path,
                        "guidance { enabled: true trials: 3 }\n"
                        "evaluation { motion_steps: 600 }\n")
                  .ok());
  return path;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  for (size_t end; (end = text.find('\n', start)) != std::string::npos;
       start = end + 1) {
    lines.push_back(text.substr(start, end - start));
  }
  return lines;
}

bool StartsWith(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

TEST(AnalysisCliTest, KnockoutsPrintATableAndWriteTheFile) {
  const std::string source =
      "analyze --genome " + GuidedGenome() + " --config " + GuidanceConfig();
  const Outcome run =
      Animat(source + " --knockouts --threads 2 -o " + Temp("ko.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  v1::KnockoutAnalysis k;
  ASSERT_TRUE(ReadProtoFile(Temp("ko.json"), &k).ok());
  EXPECT_TRUE(k.guidance());
  EXPECT_EQ(k.intact().kind(), v1::Knockout::NONE);
  EXPECT_FALSE(k.intact().has_node());
  ASSERT_EQ(k.intact().result().status(), v1::EvaluationResult::OK);
  EXPECT_EQ(k.intact().result().source_distances_size(), 3);
  ASSERT_EQ(k.knockout_size(), 6);  // CHEMICAL and five morphogens.
  EXPECT_EQ(k.knockout(0).kind(), v1::Knockout::CHEMICAL);
  for (int i = 1; i < k.knockout_size(); ++i) {
    EXPECT_EQ(k.knockout(i).kind(), v1::Knockout::MORPHOGEN);
    EXPECT_TRUE(k.knockout(i).has_chemical_path());
    EXPECT_TRUE(k.knockout(i).has_actuator_path());
    if (k.knockout(i).result().has_fitness()) {
      EXPECT_EQ(
          k.knockout(i).fitness_change(),
          k.knockout(i).result().fitness() - k.intact().result().fitness());
    }
  }
  // The intact evaluation is simulate's.
  const Outcome simulate = Animat("simulate --genome " + GuidedGenome() +
                                  " --config " + GuidanceConfig() + " --json");
  ASSERT_EQ(simulate.exit_code, 0) << simulate.output;
  EXPECT_NE(simulate.output.find("\"fitness\": " +
                                 ShortestDouble(k.intact().result().fitness())),
            std::string::npos)
      << simulate.output;

  // The table: a header, the intact row, one row per knock-out.
  const std::vector<std::string> lines = Lines(run.output);
  ASSERT_EQ(lines.size(), 8u) << run.output;
  EXPECT_TRUE(StartsWith(lines[0], "silenced  ")) << lines[0];
  for (const char* column :
       {"status", "fitness", "change", "distance", "from CHEMICAL",
        "to actuators", "source distances"}) {
    EXPECT_NE(lines[0].find(column), std::string::npos) << column;
  }
  EXPECT_TRUE(StartsWith(lines[1], "nothing (intact)  ")) << lines[1];
  EXPECT_NE(lines[1].find("  ok  "), std::string::npos) << lines[1];
  EXPECT_TRUE(StartsWith(lines[2], "CHEMICAL  ")) << lines[2];
  for (int i = 1; i < k.knockout_size(); ++i) {
    // Named as animat grn names the unit, and by node.
    const std::string name =
        "M of unit_" + std::to_string(k.knockout(i).unit_element()) +
        " (node " + std::to_string(k.knockout(i).node()) + ")  ";
    EXPECT_TRUE(StartsWith(lines[2 + i], name)) << lines[2 + i];
  }

  // The same bits whatever the threads, in any format.
  const Outcome one =
      Animat(source + " --knockouts --threads 1 -o " + Temp("ko.txtpb"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_EQ(one.output, run.output);
  v1::KnockoutAnalysis text;
  ASSERT_TRUE(ReadProtoFile(Temp("ko.txtpb"), &text).ok());
  EXPECT_EQ(text.SerializeAsString(), k.SerializeAsString());

  // -o -: the JSON on standard output instead of the table.
  const Outcome json = Animat(source + " --knockouts -o -");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  EXPECT_EQ(json.output.rfind("{", 0), 0u) << json.output;
  EXPECT_EQ(json.output.find("nothing (intact)"), std::string::npos);
  EXPECT_NE(json.output.find("\"MORPHOGEN\""), std::string::npos);
}

TEST(AnalysisCliTest, KnockoutsWithoutGuidanceMeasureTheSwimming) {
  const Outcome run = Animat("analyze --genome " + GuidedGenome() +
                             " --config " + ShortConfig() + " --knockouts");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> lines = Lines(run.output);
  ASSERT_EQ(lines.size(), 7u) << run.output;  // No CHEMICAL row.
  EXPECT_EQ(lines[0].find("source distances"), std::string::npos);
  EXPECT_EQ(run.output.find("\nCHEMICAL "), std::string::npos);
  EXPECT_TRUE(StartsWith(lines[2], "M of unit_")) << lines[2];
}

TEST(AnalysisCliTest, KnockoutsRefuseWhatTheyCannotUse) {
  const std::string source =
      "analyze --genome " + GuidedGenome() + " --config " + ShortConfig();
  // The motion analysis's window and spacing are not theirs: usage errors.
  for (const char* extra : {" --from 10", " --to 100", " --every 2"}) {
    const Outcome run = Animat(source + " --knockouts" + extra);
    EXPECT_EQ(run.exit_code, 2) << extra << ": " << run.output;
    EXPECT_NE(run.output.find("--knockouts"), std::string::npos) << run.output;
  }
  const Outcome threads = Animat(source + " --threads 2");
  EXPECT_EQ(threads.exit_code, 2) << threads.output;
  for (const char* bad : {" --threads 0", " --threads 257", " --threads x"}) {
    EXPECT_EQ(Animat(source + " --knockouts" + bad).exit_code, 2) << bad;
  }
  const Outcome format =
      Animat(source + " --knockouts -o " + Temp("knockouts.csv"));
  EXPECT_EQ(format.exit_code, 1) << format.output;
  EXPECT_NE(format.output.find(".csv"), std::string::npos) << format.output;
  const Outcome none = Animat("analyze --knockouts");
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.output.find("exactly one of --genome"), std::string::npos)
      << none.output;
  const Outcome junk = Animat("analyze --knockouts --genome " +
                              testing::TestData("scenes/triangle.txtpb"));
  EXPECT_EQ(junk.exit_code, 1) << junk.output;
  const Outcome unwritable =
      Animat(source + " --knockouts -o " + Temp("missing/dir/knockouts.json"));
  EXPECT_EQ(unwritable.exit_code, 1) << unwritable.output;
}

TEST(AnalysisCliTest, FiguresOfAnAnimatHaveTheirFramesPanelsAndSeries) {
  const std::string source =
      "--genome " + Swimmer() + " --config " + ShortConfig();
  const Outcome strip = Animat("figure strip " + source + " --snapshots 5 -o " +
                               Temp("strip.svg"));
  ASSERT_EQ(strip.exit_code, 0) << strip.output;
  const testing::XmlElement s = ParseSvg(Temp("strip.svg"));
  const auto snapshots = s.FindAll("g", "snapshot");
  ASSERT_EQ(snapshots.size(), 5u);
  for (const testing::XmlElement* snapshot : snapshots) {
    EXPECT_EQ(snapshot->FindAll("circle", "cell").size(), 32u);
  }
  EXPECT_EQ(s.FindAll("g", "distance").size(), 1u);

  const Outcome activity =
      Animat("figure activity " + source + " -o " + Temp("activity.svg"));
  ASSERT_EQ(activity.exit_code, 0) << activity.output;
  const testing::XmlElement a = ParseSvg(Temp("activity.svg"));
  ASSERT_EQ(a.FindAll("g", "panel").size(), 2u);
  EXPECT_EQ(a.FindAll("polyline", "series").size(), 4u);

  const Outcome cells = Animat("figure cells " + source +
                               " --cells 0,5,31 -o " + Temp("cells.svg"));
  ASSERT_EQ(cells.exit_code, 0) << cells.output;
  const testing::XmlElement c = ParseSvg(Temp("cells.svg"));
  ASSERT_EQ(c.FindAll("g", "panel").size(), 3u);
  EXPECT_EQ(c.FindAll("polyline", "series").size(), 6u);

  const Outcome bad_cell =
      Animat("figure cells " + source + " --cells 32 -o " + Temp("cells.svg"));
  EXPECT_EQ(bad_cell.exit_code, 1);
  EXPECT_NE(bad_cell.output.find("cell 32"), std::string::npos);
}

// A store of two runs' worth of generations made by hand: real genomes (a
// swimmer, a failure) so the contact sheet has bodies to draw.
class StoreFiguresTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* suffix : {"", "-wal", "-shm", ".lock"}) {
      std::remove((Path() + suffix).c_str());
    }
    Result<std::unique_ptr<lineage::Store>> store =
        lineage::Store::Open(Path());
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    v1::RunConfig config;
    ASSERT_TRUE(
        ParseProto(kShortModel, ProtoFormat::kText, config.mutable_model())
            .ok());
    Result<int64_t> run = (*store)->CreateRun(42, config, "test");
    ASSERT_TRUE(run.ok());
    v1::Genome swimmer;
    v1::Genome failure;
    ASSERT_TRUE(ReadProtoFile(Swimmer(), &swimmer).ok());
    ASSERT_TRUE(
        ReadProtoFile(testing::TestData("genomes/seed-1-nonviable.json"),
                      &failure)
            .ok());
    // Generations 0..4 of two members each: id 2g a swimmer, 2g + 1 a
    // failure; generation 3 has no fitness at all.
    for (int g = 0; g < 5; ++g) {
      const uint64_t a = 2 * g;
      const uint64_t b = 2 * g + 1;
      std::vector<lineage::NewIndividual> made(2);
      made[0].id = a;
      made[0].generation = g;
      made[0].operators = {"random"};
      made[0].genome = g == 3 ? failure : swimmer;
      made[1].id = b;
      made[1].generation = g;
      made[1].operators = {"random"};
      made[1].genome = failure;
      ASSERT_TRUE((*store)->AddGeneration(*run, g, {a, b}, made).ok());
      std::vector<lineage::Evaluation> results(2);
      results[0].id = a;
      if (g == 3) {
        results[0].result.set_status(v1::EvaluationResult::NON_VIABLE);
      } else {
        results[0].result.set_status(v1::EvaluationResult::OK);
        results[0].result.set_fitness(0.1 * (g + 1));
      }
      results[1].id = b;
      results[1].result.set_status(v1::EvaluationResult::NON_VIABLE);
      ASSERT_TRUE((*store)->RecordEvaluations(*run, results).ok());
      lineage::GenerationStats stats;
      stats.evaluated = g == 3 ? 0 : 1;
      stats.failed = g == 3 ? 2 : 1;
      if (g != 3) {
        stats.best_id = a;
        stats.best = stats.mean = stats.median = 0.1 * (g + 1);
      }
      ASSERT_TRUE((*store)->CompleteGeneration(*run, g, {a, b}, stats).ok());
    }
  }
  void TearDown() override {
    for (const char* suffix : {"", "-wal", "-shm", ".lock"}) {
      std::remove((Path() + suffix).c_str());
    }
  }
  static std::string Path() { return Temp("store.db"); }
};

TEST_F(StoreFiguresTest, FitnessHasThreeSeriesPerStore) {
  const Outcome one =
      Animat("figure fitness --db " + Path() + " -o " + Temp("fitness.svg"));
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const testing::XmlElement f = ParseSvg(Temp("fitness.svg"));
  const auto series = f.FindAll("polyline", "series");
  ASSERT_EQ(series.size(), 3u);
  EXPECT_EQ(series[0]->Attribute("data-label"), "seed 42 best");
  // Generation 3 has no fitness: four points of five.
  const std::string points = series[0]->Attribute("points");
  EXPECT_EQ(std::count(points.begin(), points.end(), ','), 4);

  const Outcome two = Animat("figure fitness --db " + Path() + " --db " +
                             Path() + " -o " + Temp("fitness2.svg"));
  ASSERT_EQ(two.exit_code, 0) << two.output;
  EXPECT_EQ(ParseSvg(Temp("fitness2.svg")).FindAll("polyline", "series").size(),
            6u);
}

// A run record (scripts/run_record.py) of the fixture's run: seed 42, the
// short model, generations 0-4 at 0.1 (g + 1) except generation 3 (null).
// `statistics` replaces the generations when given.
std::string WriteRecord(const std::string& name,
                        const std::string& statistics = "") {
  std::string rows;
  for (int g = 0; g < 5; ++g) {
    const std::string x = g == 3 ? "null" : ShortestDouble(0.1 * (g + 1));
    rows += std::string(g ? ", " : "") +
            "{\"generation\": " + std::to_string(g) +
            ", \"best_fitness\": " + x + ", \"mean_fitness\": " + x +
            ", \"median_fitness\": " + x + ", \"best_id\": 7, \"size\": 2}";
  }
  const std::string dir = Temp(name);
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(WriteFile(dir + "/record.json",
                        "{\"run\": \"v3-test-seed42\", \"seed\": 42, "
                        "\"build_id\": \"test\", \"config_text\": \"model { " +
                            std::string("evaluation { motion_steps: 1200 } }") +
                            "\", \"statistics\": [" +
                            (statistics.empty() ? rows : statistics) + "]}\n")
                  .ok());
  return dir;
}

TEST_F(StoreFiguresTest, ARunRecordDrawsAsItsStoreDoes) {
  const Outcome store =
      Animat("figure fitness --db " + Path() + " -o " + Temp("store.svg"));
  ASSERT_EQ(store.exit_code, 0) << store.output;
  const std::string record = WriteRecord("record");
  const Outcome folder =
      Animat("figure fitness --record " + record + " -o " + Temp("rec.svg"));
  ASSERT_EQ(folder.exit_code, 0) << folder.output;
  EXPECT_EQ(*ReadFile(Temp("rec.svg")), *ReadFile(Temp("store.svg")));
  // The record.json itself, after a store: six series, the store's first.
  const Outcome both =
      Animat("figure fitness --record " + record + "/record.json --db " +
             Path() + " -o " + Temp("both.svg"));
  ASSERT_EQ(both.exit_code, 0) << both.output;
  const testing::XmlElement svg = ParseSvg(Temp("both.svg"));
  const auto series = svg.FindAll("polyline", "series");
  ASSERT_EQ(series.size(), 6u);
  EXPECT_EQ(series[3]->Attribute("data-label"), "seed 42 best");
  EXPECT_EQ(series[3]->Attribute("points"), series[0]->Attribute("points"));
}

TEST_F(StoreFiguresTest, AMalformedRunRecordIsRefusedNamingTheField) {
  const std::string row =
      "{\"generation\": 0, \"best_fitness\": 1, \"mean_fitness\": 1, "
      "\"median_fitness\": 1}";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"[]", "no completed generation"},
      {"{\"generation\": 0.5, \"best_fitness\": 1}", "generation"},
      {"{\"generation\": -1, \"best_fitness\": 1}", "generation"},
      {"{\"generation\": 0, \"mean_fitness\": 1, \"median_fitness\": 1}",
       "best_fitness: missing"},
      {"{\"generation\": 0, \"best_fitness\": \"1\", \"mean_fitness\": 1, "
       "\"median_fitness\": 1}",
       "best_fitness"},
      {row + ", " + row, "generations not increasing"},
      {"7", "statistics[0]: not an object"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const std::string statistics = cases[i].first == "[]" ? "" : cases[i].first;
    std::string dir = WriteRecord("bad" + std::to_string(i), statistics);
    if (cases[i].first == "[]") {
      ASSERT_TRUE(WriteFile(dir + "/record.json",
                            "{\"run\": \"r\", \"seed\": 1, \"config_text\": "
                            "\"\", \"statistics\": []}")
                      .ok());
    }
    const Outcome run =
        Animat("figure fitness --record " + dir + " -o " + Temp("bad.svg"));
    EXPECT_EQ(run.exit_code, 1) << cases[i].first;
    EXPECT_NE(run.output.find(cases[i].second), std::string::npos)
        << cases[i].first << ": " << run.output;
  }
  // Not JSON, no seed, a configuration that does not parse, no record.
  const std::string dir = Temp("broken");
  std::filesystem::create_directories(dir);
  for (const auto& [text, message] :
       std::vector<std::pair<std::string, std::string>>{
           {"{\"run\": ", "record.json"},
           {"{\"run\": \"r\", \"config_text\": \"\", \"statistics\": []}",
            "seed: missing"},
           {"{\"run\": \"r\", \"seed\": 1, \"config_text\": \"model {\", "
            "\"statistics\": []}",
            "config_text"}}) {
    ASSERT_TRUE(WriteFile(dir + "/record.json", text).ok());
    const Outcome run =
        Animat("figure fitness --record " + dir + " -o " + Temp("bad.svg"));
    EXPECT_EQ(run.exit_code, 1) << text;
    EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
  }
  const Outcome none = Animat("figure fitness --record " + Temp("none") +
                              " -o " + Temp("bad.svg"));
  EXPECT_EQ(none.exit_code, 1) << none.output;
  const Outcome neither = Animat("figure fitness -o " + Temp("bad.svg"));
  EXPECT_EQ(neither.exit_code, 1) << neither.output;
  EXPECT_NE(neither.output.find("--record"), std::string::npos);
}

TEST_F(StoreFiguresTest, TheContactSheetShowsTheBestEveryNGenerations) {
  const Outcome run = Animat("figure contact-sheet --db " + Path() +
                             " --every 3 -o " + Temp("sheet.svg"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const testing::XmlElement sheet = ParseSvg(Temp("sheet.svg"));
  // Generations 0 and 3, and the last (4).
  const auto pictures = sheet.FindAll("g", "individual");
  ASSERT_EQ(pictures.size(), 3u);
  EXPECT_EQ(pictures[0]->FindAll("circle", "cell").size(), 32u);
  EXPECT_EQ(pictures[0]->FindAll("polyline", "path").size(), 1u);
  EXPECT_TRUE(pictures[1]->FindAll("circle", "cell").empty());  // None.
  EXPECT_EQ(pictures[2]->FindAll("circle", "cell").size(), 32u);
  EXPECT_EQ(pictures[2]->FindAll("text")[0]->text, "generation 4");
}

TEST_F(StoreFiguresTest, KnockoutsOfAStoredIndividualUseItsRunsConfiguration) {
  const Outcome stored =
      Animat("analyze --db " + Path() + " --individual 4 --knockouts -o " +
             Temp("stored-knockouts.json"));
  ASSERT_EQ(stored.exit_code, 0) << stored.output;
  const Outcome direct =
      Animat("analyze --genome " + Swimmer() + " --config " + ShortConfig() +
             " --knockouts -o " + Temp("direct-knockouts.json"));
  ASSERT_EQ(direct.exit_code, 0) << direct.output;
  EXPECT_EQ(stored.output, direct.output);
  EXPECT_EQ(*ReadFile(Temp("stored-knockouts.json")),
            *ReadFile(Temp("direct-knockouts.json")));
}

TEST_F(StoreFiguresTest,
       ClusterTakesTheTopDistinctPhenotypesOfTheLastGeneration) {
  // Generation 4's members: the swimmer (8) and a failure (9).
  const Outcome run = Animat("cluster --db " + Path() + " --top 5 -o " +
                             Temp("store-clusters.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  v1::StrategyClustering c;
  ASSERT_TRUE(ReadProtoFile(Temp("store-clusters.json"), &c).ok());
  ASSERT_EQ(c.animat_size(), 1);
  const std::string stem =
      std::filesystem::path(Path()).stem().string() + " #8";
  EXPECT_EQ(c.animat(0).name(), stem);
  // Simulated under the run's model, as analyze does.
  const Outcome analyze = Animat("analyze --db " + Path() +
                                 " --individual 8 -o " + Temp("eight.json"));
  ASSERT_EQ(analyze.exit_code, 0) << analyze.output;
  const v1::Analysis a = ReadAnalysis(Temp("eight.json"));
  EXPECT_EQ(c.animat(0).fitness(), a.fitness());
  EXPECT_EQ(c.animat(0).label(), a.strategy().label());
}

TEST_F(StoreFiguresTest, AnalyzeOfAStoredIndividualUsesItsRunsConfiguration) {
  const Outcome stored = Animat("analyze --db " + Path() +
                                " --individual 4 -o " + Temp("stored.json"));
  ASSERT_EQ(stored.exit_code, 0) << stored.output;
  const Outcome direct = Animat("analyze --genome " + Swimmer() + " --config " +
                                ShortConfig() + " -o " + Temp("direct.json"));
  ASSERT_EQ(direct.exit_code, 0) << direct.output;
  EXPECT_EQ(*ReadFile(Temp("stored.json")), *ReadFile(Temp("direct.json")));
  const Outcome unknown = Animat("analyze --db " + Path() + " --individual 99");
  EXPECT_EQ(unknown.exit_code, 1);
}

// `animat signals` prints, as text and as JSON, the same measurement of
// the same animat, from a genome and from its trace; a failing animat
// exits 1 saying why.
TEST(AnalysisCliTest, SignalsAgreeAsTextAndJsonFromGenomeOrTrace) {
  const std::string config = ShortConfig();
  const Outcome text =
      Animat("signals --genome " + Swimmer() + " --config " + config);
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("motion_steps: 1200\n"), std::string::npos)
      << text.output;
  EXPECT_NE(text.output.find("crossing_steps: "), std::string::npos);
  EXPECT_NE(text.output.find("capped_share: "), std::string::npos);
  const Outcome json = Animat("signals --genome " + Swimmer() + " --config " +
                              config + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  EXPECT_EQ(json.output.rfind("{\n", 0), 0u) << json.output;
  EXPECT_NE(json.output.find("\"motion_steps\": 1200,"), std::string::npos);
  const Outcome simulate =
      Animat("simulate --genome " + Swimmer() + " --config " + config +
             " --trace " + Temp("signals-trace.binpb"));
  ASSERT_EQ(simulate.exit_code, 0) << simulate.output;
  const Outcome from_trace =
      Animat("signals --trace " + Temp("signals-trace.binpb") + " --json");
  ASSERT_EQ(from_trace.exit_code, 0) << from_trace.output;
  EXPECT_EQ(from_trace.output, json.output);

  const Outcome failing = Animat(
      "signals --genome " + testing::TestData("genomes/seed-1-nonviable.json"));
  EXPECT_EQ(failing.exit_code, 1) << failing.output;
  EXPECT_NE(failing.output.find("non_viable"), std::string::npos)
      << failing.output;
}

}  // namespace
}  // namespace animat
