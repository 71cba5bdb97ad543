// End-to-end tests of what the tools make of bad input (ids, empty and
// junk files, the wrong kind of configuration) and of what they print
// about themselves (--version, config defaults, numbers in messages).
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "animat/v1/evolution.pb.h"
#include "common/evaluation/model_config.h"
#include "common/io/proto_file.h"
#include "common/kernels/isa.h"
#include "common/protocol/protocol.h"
#include "master/evolution/evolution_params.h"
#include "tests/cli/run_animat.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using ::animat::testing::Animat;
using ::animat::testing::Outcome;

std::string Temp(const std::string& name) {
  return ::testing::TempDir() + "/animat-input-" + name;
}

// No byte outside printable ASCII but the line ends.
bool Printable(const std::string& text) {
  for (char c : text) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (u != '\n' && (u < 0x20 || u >= 0x7f)) return false;
  }
  return true;
}

TEST(CliInputTest, IdsAreWholeNumbers) {
  // Refused while the command line is read: the store need not exist.
  const std::string db = "--db " + Temp("none.db");
  const std::vector<std::string> commands = {
      "lineage genome ID " + db + " -o -",
      "lineage ancestors ID " + db,
      "lineage best " + db + " --run ID",
      "lineage genome 1 " + db + " --run ID -o -",
      "lineage ancestors 1 " + db + " --run ID",
      "lineage export " + db + " --run ID",
      "analyze " + db + " --individual ID",
      "analyze " + db + " --individual 1 --run ID",
      "figure strip " + db + " --individual ID -o x.svg",
      "figure strip " + db + " --individual 1 --run ID -o x.svg",
      "figure fitness " + db + " --run ID -o x.svg",
      "figure contact-sheet " + db + " --run ID -o x.svg",
      "render " + db + " --individual ID -o x.html",
      "render " + db + " --individual 1 --run ID -o x.html",
      "random-genome --seed 1 --individual ID -o x.json",
  };
  for (const std::string& command : commands) {
    for (const std::string id :
         {"-3", "abc", "1.5", "''", "+1", "0x10", "99999999999999999999999"}) {
      std::string line = command;
      line.replace(line.find("ID"), 2, id);
      SCOPED_TRACE("animat " + line);
      const Outcome run = Animat(line);
      EXPECT_EQ(run.exit_code, 2) << run.output;
      EXPECT_NE(run.output.find("expected an id"), std::string::npos)
          << run.output;
      EXPECT_EQ(run.output.find("18446744073709551613"), std::string::npos)
          << run.output;
    }
  }
  const Outcome run = Animat("random-genome --seed -1 -o " + Temp("r.json"));
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("--seed: expected a seed"), std::string::npos)
      << run.output;
}

TEST(CliInputTest, AGenomeFileWithoutElementsIsRefused) {
  const std::vector<std::pair<std::string, std::string>> files = {
      {"empty.txtpb", ""},   {"empty.binpb", ""},
      {"braces.json", "{}"}, {"none.json", "{\"elements\": []}"},
      {"empty.json", ""},
  };
  for (const auto& [name, contents] : files) {
    SCOPED_TRACE(name);
    const std::string path = Temp(name);
    ASSERT_TRUE(WriteFile(path, contents).ok());
    for (const std::string& command :
         {"simulate --genome " + path,
          "grn --steps 1 --inputs 0,0,0,1 --genome " + path,
          "render -o " + Temp("x.html") + " --genome " + path}) {
      const Outcome run = Animat(command);
      EXPECT_EQ(run.exit_code, 1) << command << "\n" << run.output;
      EXPECT_EQ(run.output.rfind("animat: " + path + ":", 0), 0u) << run.output;
    }
  }
}

TEST(CliInputTest, AJunkFileIsQuotedShortAndEscaped) {
  // 4 MB of junk: any bytes, and one printable line (not as binary:
  // "xxx..." is a valid message of unknown fields).
  std::string bytes(4 << 20, '\0');
  uint32_t state = 1;
  for (char& c : bytes) {
    state = state * 1664525u + 1013904223u;
    c = static_cast<char>(state >> 24);
  }
  const std::string line(4 << 20, 'x');
  const std::string genome = testing::TestData("genomes/example.json");
  int case_number = 0;
  for (const std::string& junk : {bytes, line}) {
    for (const std::string extension : {".json", ".txtpb", ".binpb"}) {
      if (junk == line && extension == ".binpb") continue;
      const std::string path =
          Temp("junk" + std::to_string(case_number++) + extension);
      ASSERT_TRUE(WriteFile(path, junk).ok());
      for (const std::string& command : {
               "simulate --genome " + path,
               "simulate --genome " + genome + " --config " + path,
               "evolve --db " + Temp("junk.db") + " --config " + path,
               "analyze --trace " + path,
               "render -o " + Temp("x.html") + " --trace " + path,
           }) {
        SCOPED_TRACE("animat " + command);
        const Outcome run = Animat(command);
        EXPECT_EQ(run.exit_code, 1) << run.output.substr(0, 1000);
        EXPECT_EQ(run.output.rfind("animat: " + path, 0), 0u)
            << run.output.substr(0, 1000);
        EXPECT_LT(run.output.size(), path.size() + 400)
            << run.output.substr(0, 1000);
        EXPECT_TRUE(Printable(run.output)) << run.output.substr(0, 1000);
      }
    }
  }
}

TEST(CliInputTest, NumbersInMessagesAreShortest) {
  const std::string config = Temp("dt.txtpb");
  ASSERT_TRUE(WriteFile(config, "physics { dt: -0.7 }\n").ok());
  const Outcome run =
      Animat("simulate --genome " + testing::TestData("genomes/example.json") +
             " --config " + config);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("physics.dt: must be finite and > 0, got -0.7\n"),
            std::string::npos)
      << run.output;
}

TEST(CliInputTest, AnIsaPathIsChosenByTheEnvironmentOrRefused) {
  const std::string simulate =
      "simulate --genome " + testing::TestData("genomes/seed-1198.json");
  const Outcome widest = Animat(simulate);
  ASSERT_EQ(widest.exit_code, 0) << widest.output;
  setenv("ANIMAT_ISA", "baseline", 1);
  const Outcome baseline = Animat(simulate);
  setenv("ANIMAT_ISA", "sse9", 1);
  const Outcome bad = Animat(simulate);
  unsetenv("ANIMAT_ISA");
  // The same bits on every path: the same output, state hash included.
  EXPECT_EQ(baseline.exit_code, 0);
  EXPECT_EQ(baseline.output, widest.output);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("ANIMAT_ISA: \"sse9\" is not an instruction-set "
                            "path (expected baseline, avx2 or avx512)"),
            std::string::npos)
      << bad.output;
}

TEST(CliInputTest, EveryToolTellsItsVersion) {
  const std::string expected =
      "build: " + protocol::BuildId() +
      "\nprotocol: " + std::to_string(protocol::kVersion) +
      "\nmodel: " + std::to_string(protocol::kModelVersion) +
      "\nkernels: " + IsaReport() + "\n";
  EXPECT_EQ(Animat("--version").output, expected);
  EXPECT_EQ(Animat("--version").exit_code, 0);
  for (const std::string tool : {"animat-master", "animat-worker"}) {
    SCOPED_TRACE(tool);
    // --version needs none of the required options.
    FILE* pipe = popen(
        (std::string(ANIMAT_BIN_DIR) + "/" + tool + " --version 2>&1").c_str(),
        "r");
    ASSERT_NE(pipe, nullptr);
    std::string output;
    char buffer[4096];
    size_t n;
    while ((n = fread(buffer, 1, sizeof(buffer), pipe)) > 0) {
      output.append(buffer, n);
    }
    const int status = pclose(pipe);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << output;
    EXPECT_EQ(output, expected);
  }
}

TEST(CliInputTest, ConfigDefaultsReadBack) {
  const std::string model = Temp("defaults.txtpb");
  Outcome run = Animat("config defaults > " + model);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  Result<ModelConfig> config = ReadConfigFile(model);
  ASSERT_TRUE(config.ok()) << config.status().ToString();
  EXPECT_EQ(ConfigToProto(*config).SerializeAsString(),
            ConfigToProto(ModelConfig{}).SerializeAsString());
  // Given as --config, the same as none.
  const std::string genome = testing::TestData("genomes/seed-1198.json");
  const Outcome with =
      Animat("simulate --genome " + genome + " --config " + model);
  const Outcome without = Animat("simulate --genome " + genome);
  EXPECT_EQ(with.exit_code, 0) << with.output;
  EXPECT_EQ(with.output, without.output);

  const std::string run_config = Temp("run-defaults.txtpb");
  run = Animat("config defaults --run > " + run_config);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  Result<RunSettings> settings = ReadRunConfigFile(run_config);
  ASSERT_TRUE(settings.ok()) << settings.status().ToString();
  EXPECT_EQ(RunSettingsToProto(*settings).SerializeAsString(),
            RunSettingsToProto(RunSettings{}).SerializeAsString());
}

TEST(CliInputTest, AConfigOfTheOtherKindIsNamed) {
  const std::string model = Temp("model.txtpb");
  ASSERT_TRUE(WriteFile(model, "physics { dt: 0.01 }\n").ok());
  const std::string run_config = Temp("run.json");
  ASSERT_TRUE(WriteFile(run_config, R"({"model": {"physics": {"dt": 0.01}},)"
                                    R"( "evolution": {"population": 10}})")
                  .ok());
  Outcome run =
      Animat("simulate --genome " + testing::TestData("genomes/example.json") +
             " --config " + run_config);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find(run_config +
                            ": a run configuration (animat.v1.RunConfig), "
                            "where a model configuration (animat.v1.Config) "
                            "is wanted: give what its model { } block holds "
                            "(animat config defaults prints one)"),
            std::string::npos)
      << run.output;

  const std::string db = Temp("kind.db");
  run = Animat("evolve --db " + db + " --config " + model);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(
      run.output.find(model + ": a model configuration (animat.v1.Config), "
                              "where a run configuration (animat.v1.RunConfig) "
                              "is wanted: put it in a model { } block beside "
                              "an evolution { } block (animat config defaults "
                              "--run prints one)"),
      std::string::npos)
      << run.output;
  EXPECT_FALSE(ReadFile(db).ok());
}

}  // namespace
}  // namespace animat
