// Every flag of every `animat` command, given a malformed value while the
// rest of the command line is valid: the command exits 1 or 2 with a
// message, never by a signal or an exception reaching terminate. The flags
// are read from each command's --help, so a flag added later is tried too;
// a flag whose value type this test does not know fails it. (animat-master
// and animat-worker have the same test in tests/master/startup_test.cc, the
// developer tools in tests/bench/tools_flags_test.cc.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "common/base/status.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "master/lineage/store.h"
#include "tests/cli/flag_cases.h"
#include "tests/cli/run_animat.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using ::animat::testing::Animat;
using ::animat::testing::Flag;
using ::animat::testing::FlagsInHelp;
using ::animat::testing::MalformedNumbers;
using ::animat::testing::Outcome;
using ::animat::testing::Quote;
using ::animat::testing::TryEveryCase;

std::vector<Flag> FlagsOf(const std::string& command) {
  const Outcome help = Animat(command + " --help");
  EXPECT_EQ(help.exit_code, 0) << command << ": " << help.output;
  return FlagsInHelp(help.output);
}

class FlagsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/animat-flags-" + std::to_string(getpid());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ + "/a-directory");
    genome_ = testing::TestData("genomes/seed-1198.json");
    config_ = Path("short.txtpb");
    ASSERT_TRUE(WriteFile(config_, "evaluation { motion_steps: 200 }\n").ok());
    run_config_ = Path("run.txtpb");
    ASSERT_TRUE(WriteFile(run_config_,
                          "model { evaluation { motion_steps: 50 } }\n"
                          "evolution { seed: 3 population: 4 generations: 1"
                          " elite: 1 tournament_size: 2 initial_units: 4 }\n")
                    .ok());
    junk_ = Path("junk.json");
    ASSERT_TRUE(WriteFile(junk_, "{ not json").ok());
    scene_ = testing::TestData("scenes/triangle.txtpb");
    trace_ = Path("trace.json");
    const Outcome traced =
        Animat("simulate --genome " + Quote(genome_) + " --config " +
               Quote(config_) + " --trace " + Quote(trace_) + " --every 20");
    ASSERT_EQ(traced.exit_code, 0) << traced.output;
    db_ = Path("store.db");
    MakeStore();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Path(const std::string& name) const { return dir_ + "/" + name; }

  // A store of one run with individual 0, evaluated.
  void MakeStore() {
    v1::Genome message;
    ASSERT_TRUE(ReadProtoFile(genome_, &message).ok());
    Result<Genome> genome = GenomeFromProto(message);
    ASSERT_TRUE(genome.ok());
    ModelConfig model;
    model.evaluation.motion_steps = 200;
    Result<std::unique_ptr<lineage::Store>> store = lineage::Store::Open(db_);
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    Result<int64_t> run = (*store)->CreateRun(1, v1::RunConfig(), "test");
    ASSERT_TRUE(run.ok());
    lineage::NewIndividual individual;
    individual.operators = {"random"};
    individual.genome = message;
    ASSERT_TRUE((*store)->AddIndividuals(*run, {individual}).ok());
    lineage::Evaluation evaluation;
    evaluation.result = EvaluationResultToProto(Evaluate(*genome, model));
    ASSERT_TRUE((*store)->RecordEvaluations(*run, {evaluation}).ok());
  }

  // The values that no flag of `type` may accept. An output file may be
  // any new path, so it is given only paths that cannot be written.
  std::vector<std::string> Malformed(const Flag& flag, bool output) const {
    if (flag.type == "TEXT" && output) {
      return {"", Path("a-directory"), Path("missing/parent/file.json")};
    }
    if (flag.type == "TEXT") {
      return {"", Path("missing.json"), junk_, Path("a-directory")};
    }
    return MalformedNumbers(flag.type);
  }

  // Runs `base` with each flag of `command` (but those in `skip`) given
  // each malformed value in turn; `outputs` names the flags that write.
  void TryEveryFlag(const std::string& command,
                    const std::vector<std::string>& base,
                    const std::vector<std::string>& outputs,
                    const std::vector<std::string>& skip = {}) {
    std::vector<Flag> flags;
    for (const Flag& flag : FlagsOf(command)) {
      if (std::find(skip.begin(), skip.end(), flag.name) == skip.end()) {
        flags.push_back(flag);
      }
    }
    TryEveryCase("animat", command, base, flags, [&](const Flag& flag) {
      std::vector<std::vector<std::string>> cases;
      if (flag.type.empty()) {
        cases.push_back({flag.name + "=maybe"});
        return cases;
      }
      const bool output =
          std::find(outputs.begin(), outputs.end(), flag.name) != outputs.end();
      for (const std::string& value : Malformed(flag, output)) {
        cases.push_back({flag.name, value});
      }
      return cases;
    });
  }

  std::string dir_, genome_, config_, run_config_, junk_, scene_, trace_, db_;
};

TEST_F(FlagsTest, ModelCommands) {
  TryEveryFlag("random-genome", {"--seed", "1", "-o", Path("g.json")},
               {"--output"});
  TryEveryFlag("grn",
               {"--genome", genome_, "--inputs", "0.1", "0.2", "0.3", "1",
                "--steps", "5"},
               {}, {"--inputs"});
  TryEveryFlag("simulate", {"--genome", genome_, "--config", config_},
               {"--trace"});
  TryEveryFlag("scene", {"--scene", scene_, "--steps", "5"}, {"--trace"});
  TryEveryFlag("config defaults", {}, {});
}

TEST_F(FlagsTest, AnInputOfGrnThatIsNotANumber) {
  for (const char* value : {"abc", "nan", "inf", ""}) {
    const Outcome run =
        Animat("grn --genome " + Quote(genome_) +
               " --steps 5 --inputs 0.1 0.2 " + Quote(value) + " 1");
    EXPECT_TRUE(run.exit_code == 1 || run.exit_code == 2)
        << value << ": exit " << run.exit_code << ": " << run.output;
  }
}

TEST_F(FlagsTest, AnalysisCommands) {
  const std::vector<std::string> base = {"--genome", genome_, "--config",
                                         config_};
  TryEveryFlag("analyze", base, {"--output"});
  std::vector<std::string> knockouts = base;
  knockouts.push_back("--knockouts");
  TryEveryFlag("analyze", knockouts, {"--output"});
  TryEveryFlag("cluster", base, {"--output", "--svg"}, {"--title"});
  TryEveryFlag("signals", base, {});
  TryEveryFlag(
      "render",
      {"--genome", genome_, "--config", config_, "-o", Path("page.html")},
      {"--output"});
  std::vector<std::string> figure = base;
  figure.insert(figure.end(), {"-o", Path("figure.svg")});
  for (const char* kind : {"strip", "activity", "cells"}) {
    TryEveryFlag(std::string("figure ") + kind, figure, {"--output"});
  }
  const std::string guidance = Path("guidance.txtpb");
  ASSERT_TRUE(WriteFile(guidance,
                        "guidance { enabled: true trials: 2 }\n"
                        "evaluation { motion_steps: 100 }\n")
                  .ok());
  TryEveryFlag(
      "figure guidance",
      {"--genome", genome_, "--config", guidance, "-o", Path("guidance.svg")},
      {"--output"});
  TryEveryFlag("figure fitness", {"--db", db_, "-o", Path("fitness.svg")},
               {"--output"});
  TryEveryFlag("figure contact-sheet", {"--db", db_, "-o", Path("sheet.svg")},
               {"--output"});
}

TEST_F(FlagsTest, LineageCommands) {
  TryEveryFlag("lineage best", {"--db", db_}, {});
  TryEveryFlag("lineage ancestors 0", {"--db", db_}, {"--output"});
  TryEveryFlag("lineage genome 0", {"--db", db_, "-o", Path("g.json")},
               {"--output"});
  TryEveryFlag("lineage export", {"--db", db_}, {"--output"});
  TryEveryFlag("lineage configs", {"--db", db_}, {"--output"});
  TryEveryFlag("lineage upgrade", {"--db", db_}, {});
}

TEST_F(FlagsTest, EvolveAndKeygen) {
  TryEveryFlag(
      "evolve",
      {"--config", run_config_, "--db", Path("evolve.db"), "--workers", "1"},
      {"--db"});
  TryEveryFlag("keygen", {"-o", Path("key")}, {"--output", "--cluster"});
}

}  // namespace
}  // namespace animat
