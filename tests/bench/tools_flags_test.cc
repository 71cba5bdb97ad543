// Every flag of every developer tool (bench/: animat-accuracy, animat-floors,
// animat-dispatch-bench, animat-master-bench, animat-campaign-bench on CLI11;
// animat-bench,
// animat-eigen-bench, animat-lanes-bench on Google Benchmark), given a
// malformed value while the rest of the command line is valid: the tool exits 1
// or 2 with a message, never by a signal or an exception reaching terminate,
// and before it does any work. The flags are read from each tool's --help, so a
// flag added later is tried too; a flag whose value this test does not know
// fails it. Each base command line is cheap, in case a value were wrongly
// taken. (`animat` has the same test in tests/cli/flags_test.cc.)
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "common/base/status.h"
#include "common/io/proto_file.h"
#include "tests/cli/flag_cases.h"
#include "tests/cli/run_animat.h"

namespace animat::testing {
namespace {

class ToolsFlagsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "/animat-tools-flags-" +
           std::to_string(getpid());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(Path("a-directory"));
    std::filesystem::create_directories(Path("empty-directory"));
    std::filesystem::create_directories(Path("junk-set"));
    ASSERT_TRUE(WriteFile(Path("file.txt"), "text\n").ok());
    ASSERT_TRUE(WriteFile(Path("junk.json"), "{ not json").ok());
    ASSERT_TRUE(WriteFile(Path("junk-set/seed-1.json"), "{ not json").ok());
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Path(const std::string& name) const { return dir_ + "/" + name; }

  // The flags of `program`'s CLI11 --help.
  static std::vector<Flag> FlagsOf(const std::string& program) {
    const Outcome help = RunTool(program, "--help");
    EXPECT_EQ(help.exit_code, 0) << program << ": " << help.output;
    return FlagsInHelp(help.output);
  }

  // Tries every flag of CLI11 tool `program` on `base`: a flag without a
  // value with "=maybe", a flag named in `values` with those values, a
  // number with MalformedNumbers and those of `numbers` (out of range).
  void TryCli11Tool(
      const std::string& program, const std::vector<std::string>& base,
      const std::map<std::string, std::vector<std::string>>& values,
      const std::map<std::string, std::vector<std::string>>& numbers = {}) {
    TryEveryCase(program, "", base, FlagsOf(program), [&](const Flag& flag) {
      std::vector<std::vector<std::string>> cases;
      if (flag.type.empty()) {
        cases.push_back({flag.name + "=maybe"});
        return cases;
      }
      std::vector<std::string> malformed = MalformedNumbers(flag.type);
      if (const auto it = values.find(flag.name); it != values.end()) {
        malformed.insert(malformed.end(), it->second.begin(), it->second.end());
      }
      if (const auto it = numbers.find(flag.name); it != numbers.end()) {
        malformed.insert(malformed.end(), it->second.begin(), it->second.end());
      }
      for (const std::string& value : malformed) {
        cases.push_back({flag.name, value});
      }
      return cases;
    });
  }

  // What --worker and --worker-log must refuse.
  std::map<std::string, std::vector<std::string>> WorkerFlags() const {
    return {
        {"--worker",
         {"", Path("missing-worker"), Path("a-directory"), Path("file.txt")}},
        {"--worker-log",
         {"", Path("a-directory"), Path("missing/parent/workers.log")}},
    };
  }

  std::string dir_;
};

TEST_F(ToolsFlagsTest, Accuracy) {
  // --out is a directory, made if it does not exist: only what cannot be
  // one is malformed.
  TryCli11Tool("animat-accuracy",
               {"--quick", "--animats", "1", "--candidates", "R1f", "--repeats",
                "1", "--out", Path("report")},
               {
                   {"--out", {"", Path("file.txt"), Path("file.txt/report")}},
                   {"--data",
                    {"", Path("missing"), Path("file.txt"),
                     Path("empty-directory"), Path("junk-set")}},
                   {"--candidates", {"", "NOT-A-CANDIDATE"}},
               },
               {{"--repeats", {"0", "101"}}, {"--animats", {"-1"}}});
}

TEST_F(ToolsFlagsTest, Floors) {
  TryCli11Tool(
      "animat-floors", {},
      {{"--genome",
        {"", Path("missing.json"), Path("junk.json"), Path("a-directory")}}});
}

TEST_F(ToolsFlagsTest, DispatchBench) {
  std::map<std::string, std::vector<std::string>> values = WorkerFlags();
  values["--part"] = {"", "everything"};
  values["--genomes"] = {"", Path("missing.json"), Path("junk.json"),
                         Path("a-directory")};
  TryCli11Tool("animat-dispatch-bench",
               {"--part", "dispatch", "--individuals", "100", "--workers", "1",
                "--threads", "8"},
               values,
               {{"--individuals", {"0", "-1"}},
                {"--workers", {"0", "65"}},
                {"--threads", {"0", "4097"}},
                {"--evaluations", {"0"}}});
}

TEST_F(ToolsFlagsTest, MasterBench) {
  std::map<std::string, std::vector<std::string>> values = WorkerFlags();
  values["--db"] = {"", Path("a-directory"), Path("missing/parent/run.db")};
  values["--endpoint"] = {"", "abc", "127.0.0.1:5555", "tcp://127.0.0.1:abc",
                          "tcp://0.0.0.0:*"};
  TryCli11Tool("animat-master-bench",
               {"--population", "4", "--generations", "1", "--workers", "1",
                "--threads", "8"},
               values,
               {{"--population", {"3"}},
                {"--generations", {"0"}},
                {"--workers", {"0"}},
                {"--threads", {"0"}},
                {"--heartbeat-ms", {"9"}}});
  EXPECT_FALSE(std::filesystem::exists(Path("missing")));
}

TEST_F(ToolsFlagsTest, CampaignBench) {
  std::map<std::string, std::vector<std::string>> values = WorkerFlags();
  values["--arrangement"] = {"", "neither", "Campaign"};
  TryCli11Tool("animat-campaign-bench",
               {"--runs", "1", "--population", "4", "--generations", "1",
                "--slots", "1", "--delay-ms", "0", "--arrangement", "campaign"},
               values,
               {{"--runs", {"0", "65"}},
                {"--population", {"3"}},
                {"--generations", {"0"}},
                {"--slots", {"0", "65537"}},
                {"--delay-ms", {"-1", "60001"}},
                {"--delay-cv", {"-0.5", "11"}},
                {"--repeats", {"0", "101"}}});
  // Slots that do not split evenly over the runs.
  const Outcome uneven =
      RunTool("animat-campaign-bench", Join({"--runs", "3", "--slots", "10"}));
  EXPECT_EQ(uneven.exit_code, 2) << uneven.output;
  EXPECT_NE(uneven.output.find("--slots: 10 is not a multiple of --runs (3)"),
            std::string::npos)
      << uneven.output;
}

// Every flag of a Google Benchmark tool's usage ("[--benchmark_x=<...>]"),
// each with the malformed values of its kind of value.
void TryGoogleBenchmarkTool(const std::string& program,
                            const std::string& benchmark,
                            const std::string& dir) {
  const Outcome help = RunTool(program, "--help");
  ASSERT_EQ(help.exit_code, 0) << help.output;
  std::vector<Flag> flags;
  std::map<std::string, std::string> usage;  // Flag: what its value is.
  const std::regex line(R"(\[(--\w+)=([^\]]*)\])");
  for (std::sregex_iterator it(help.output.begin(), help.output.end(), line),
       end;
       it != end; ++it) {
    flags.push_back({(*it)[1], ""});
    usage[(*it)[1]] = (*it)[2];
  }
  EXPECT_GE(flags.size(), 16u) << help.output;
  const std::string huge(100000, '9');
  // By what the usage says a value is; std::nullopt: the flag alone.
  const std::map<std::string, std::vector<std::optional<std::string>>> kinds = {
      {"{true|false}", {"maybe", "", "2"}},
      {"{auto|true|false}", {"maybe", "", std::nullopt}},
      {"<regex>",
       {"(", "-[", "a{2,1}", std::string(100000, 'a'), "", std::nullopt}},
      {"<min_time>",
       {"abc", "0", "-1", "nan", "inf", "1e999", "0.5s", "", std::nullopt}},
      {"<min_warmup_time>", {"abc", "-1", "nan", "inf", "", std::nullopt}},
      {"<num_repetitions>", {"abc", "0", "-5", "1.5", huge, "", std::nullopt}},
      {"<verbosity>", {"abc", "-1", huge, "", std::nullopt}},
      {"<console|json|csv>", {"xml", "JSON", "", std::nullopt}},
      {"<json|console|csv>", {"xml", "JSON", "", std::nullopt}},
      {"<filename>",
       {dir + "/a-directory", dir + "/missing/parent/out.json", "",
        std::nullopt}},
      {"<key>=<value>,...", {"a", "=b", "a=b=c", "a=1,,b=2", "", std::nullopt}},
      {"{ns|us|ms|s}", {"yy", "sec", "", std::nullopt}},
  };
  // Lists one cheap benchmark; run for 10 ms if --benchmark_list_tests
  // were wrongly taken.
  const std::vector<std::string> base = {
      "--benchmark_list_tests=true", "--benchmark_filter=^" + benchmark + "$",
      "--benchmark_min_time=0.01"};
  TryEveryCase(program, "", base, flags, [&](const Flag& flag) {
    std::vector<std::vector<std::string>> cases;
    const auto kind = kinds.find(usage[flag.name]);
    if (kind == kinds.end()) return cases;  // A value not known here.
    for (const std::optional<std::string>& value : kind->second) {
      cases.push_back({value ? flag.name + "=" + *value : flag.name});
    }
    return cases;
  });
  // A flag the library does not have, and an argument that is no flag.
  for (const char* other : {"--benchmark_nonsense=1", "positional"}) {
    SCOPED_TRACE(other);
    ExpectRefused(RunTool(program, Join(base) + " " + other));
  }
}

TEST_F(ToolsFlagsTest, EvaluationBench) {
  TryGoogleBenchmarkTool("animat-bench", "BM_GrnStep<float>/isa:0", dir_);
}

TEST_F(ToolsFlagsTest, EigenBench) {
  TryGoogleBenchmarkTool("animat-eigen-bench", "BM_Accumulate<float>/0", dir_);
}

TEST_F(ToolsFlagsTest, LanesBench) {
  TryGoogleBenchmarkTool("animat-lanes-bench", "BM_SpringsScalar", dir_);
}

TEST_F(ToolsFlagsTest, UsageErrorsExit2AndHelpExits0) {
  for (const std::string program :
       {"animat-accuracy", "animat-floors", "animat-dispatch-bench",
        "animat-master-bench", "animat-campaign-bench", "animat-bench",
        "animat-eigen-bench", "animat-lanes-bench"}) {
    SCOPED_TRACE(program);
    EXPECT_EQ(RunTool(program, "--help").exit_code, 0);
  }
  for (const std::string program :
       {"animat-accuracy", "animat-floors", "animat-dispatch-bench",
        "animat-master-bench", "animat-campaign-bench"}) {
    SCOPED_TRACE(program);
    EXPECT_EQ(RunTool(program, "--no-such-flag").exit_code, 2);
  }
  for (const std::string program :
       {"animat-dispatch-bench", "animat-master-bench",
        "animat-campaign-bench"}) {
    const Outcome run = RunTool(program, Join({"--worker-log", ""}));
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_NE(run.output.find(program + ": --worker-log: an empty value"),
              std::string::npos)
        << run.output;
  }
  for (const std::string program :
       {"animat-bench", "animat-eigen-bench", "animat-lanes-bench"}) {
    const Outcome run = RunTool(program, "--benchmark_repetitions=-5");
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_EQ(run.output.rfind(program + ": --benchmark_repetitions: ", 0), 0u)
        << run.output;
  }
}

TEST_F(ToolsFlagsTest, FilesAreCheckedBeforeAnyWork) {
  // The output directory of the report, before the report is made.
  const Outcome accuracy =
      RunTool("animat-accuracy", Join({"--out", Path("file.txt")}));
  EXPECT_EQ(accuracy.exit_code, 1);
  EXPECT_EQ(accuracy.output,
            "animat-accuracy: --out " + Path("file.txt") + ": " +
                std::make_error_code(std::errc::not_a_directory).message() +
                "\n");
  // The workers' binary and log, before any part of the run.
  const Outcome dispatch =
      RunTool("animat-dispatch-bench", Join({"--worker", Path("a-directory")}));
  EXPECT_EQ(dispatch.exit_code, 1);
  EXPECT_EQ(dispatch.output, "animat-dispatch-bench: --worker " +
                                 Path("a-directory") +
                                 ": not a file (expected the animat-worker "
                                 "binary)\n");
  const Outcome master = RunTool(
      "animat-master-bench",
      Join({"--worker-log", Path("a-directory"), "--db", Path("run.db")}));
  EXPECT_EQ(master.exit_code, 1);
  EXPECT_EQ(
      master.output.rfind("animat-master-bench: --worker-log " +
                              Path("a-directory") + ": cannot append to it: ",
                          0),
      0u)
      << master.output;
  EXPECT_FALSE(std::filesystem::exists(Path("run.db")));
  // An endpoint beyond this machine, before the store is made.
  const Outcome beyond =
      RunTool("animat-master-bench",
              Join({"--endpoint", "tcp://0.0.0.0:*", "--db", Path("run.db")}));
  EXPECT_EQ(beyond.exit_code, 2);
  EXPECT_NE(beyond.output.find("reaches beyond this machine"),
            std::string::npos)
      << beyond.output;
  EXPECT_FALSE(std::filesystem::exists(Path("run.db")));
}

}  // namespace
}  // namespace animat::testing
