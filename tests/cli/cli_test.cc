// End-to-end tests of build/bin/animat: the real binary, real files.
#include <sys/wait.h>
#include <unistd.h>

#include <google/protobuf/struct.pb.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdio>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "animat/v1/trace.pb.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "master/lineage/store.h"
#include "tests/cli/run_animat.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using ::animat::testing::Animat;
using ::animat::testing::Outcome;
using google::protobuf::Struct;

// A file name of this test's own: ctest runs the tests of this file in
// parallel processes (and other checkouts may run them at the same time), so
// the name carries the test's name and the process id.
std::string Temp(const std::string& name) {
  const ::testing::TestInfo* test =
      ::testing::UnitTest::GetInstance()->current_test_info();
  return ::testing::TempDir() + "/animat-cli-" +
         (test != nullptr ? std::string(test->name()) + "-" : std::string()) +
         std::to_string(::getpid()) + "-" + name;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A configuration with a short motion phase, to keep the tests fast.
std::string ShortConfig() {
  const std::string path = Temp("short.txtpb");
  EXPECT_TRUE(WriteFile(path, "evaluation { motion_steps: 200 }\n").ok());
  return path;
}

TEST(CliTest, RandomGenomeIsAPureFunctionOfTheSeed) {
  ASSERT_EQ(Animat("random-genome --seed 7 -o " + Temp("a.json")).exit_code, 0);
  ASSERT_EQ(Animat("random-genome --seed 7 -o " + Temp("b.json")).exit_code, 0);
  ASSERT_EQ(Animat("random-genome --seed 8 -o " + Temp("c.json")).exit_code, 0);
  EXPECT_EQ(*ReadFile(Temp("a.json")), *ReadFile(Temp("b.json")));
  EXPECT_NE(*ReadFile(Temp("a.json")), *ReadFile(Temp("c.json")));
  v1::Genome message;
  ASSERT_TRUE(ReadProtoFile(Temp("a.json"), &message).ok());
  Result<Genome> genome = GenomeFromProto(message);
  ASSERT_TRUE(genome.ok());
  EXPECT_EQ(genome->elements.size(), 30u);  // 10 units of 2, 10 S.
}

TEST(CliTest, RandomGenomeTakesUnitsAndTextFormat) {
  ASSERT_EQ(Animat("random-genome --seed 3 --units 4 -o " + Temp("g.txtpb"))
                .exit_code,
            0);
  v1::Genome message;
  ASSERT_TRUE(ReadProtoFile(Temp("g.txtpb"), &message).ok());
  EXPECT_EQ(message.elements_size(), 18);
}

TEST(CliTest, GrnPrintsOneRowPerStepInNodeOrder) {
  const Outcome run =
      Animat("grn --genome " + testing::TestData("genomes/example.json") +
             " --inputs 0,0,0,1 --steps 3");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> lines = Lines(run.output);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "step,in_0_UNIFORM,unit_1,out_3_DIVIDE");
  // Step 1 by hand: A = 10 exp(-0.5) * 1; L = 0.05 tanh(A / 2); the output
  // node still reads L = 0 of the unit, so it stays at 0.
  EXPECT_EQ(lines[1], "1,1,0.04976833334335129,0");
  EXPECT_EQ(lines[3].substr(0, 2), "3,");
}

TEST(CliTest, GrnRejectsAWrongNumberOfInputs) {
  const Outcome run =
      Animat("grn --genome " + testing::TestData("genomes/example.json") +
             " --inputs 0,0,1 --steps 3");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("--inputs"), std::string::npos) << run.output;
}

TEST(CliTest, SimulatePrintsStatusAndFitness) {
  const Outcome run = Animat("simulate --genome " +
                             testing::TestData("genomes/seed-1198.json") +
                             " --config " + ShortConfig());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::vector<std::string> lines = Lines(run.output);
  ASSERT_GE(lines.size(), 7u);
  EXPECT_EQ(lines[0], "status: ok");
  EXPECT_EQ(lines[1].rfind("fitness: ", 0), 0u);
  // Under the paper's fitness the distance is the fitness.
  EXPECT_EQ(lines[2], "distance: " + lines[1].substr(9));
  EXPECT_EQ(lines[3].rfind("energy: ", 0), 0u);
  EXPECT_EQ(lines[4].rfind("max_overlap: ", 0), 0u);
  EXPECT_EQ(lines[5], "cells: 32");
  EXPECT_EQ(lines[6], "steps: 800");
}

// "key: value" lines as a map, in order.
std::vector<std::pair<std::string, std::string>> KeyValues(
    const std::string& text) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const std::string& line : Lines(text)) {
    const size_t colon = line.find(": ");
    EXPECT_NE(colon, std::string::npos) << line;
    if (colon == std::string::npos) continue;
    pairs.emplace_back(line.substr(0, colon), line.substr(colon + 2));
  }
  return pairs;
}

// simulate --json: one object whose keys and values, in order, are the
// text output's lines; strings stay strings, numbers are numbers.
void ExpectJsonMatchesText(const std::string& json, const std::string& text) {
  Struct object;
  const auto parsed =
      google::protobuf::util::JsonStringToMessage(json, &object);
  ASSERT_TRUE(parsed.ok()) << parsed.ToString() << "\n" << json;
  const auto lines = KeyValues(text);
  EXPECT_EQ(static_cast<size_t>(object.fields_size()), lines.size()) << json;
  size_t position = 0;
  for (const auto& [key, value] : lines) {
    SCOPED_TRACE(key);
    // In the text's order.
    const size_t at = json.find("\"" + key + "\":");
    ASSERT_NE(at, std::string::npos) << json;
    EXPECT_GT(at, position);
    position = at;
    const auto field = object.fields().find(key);
    ASSERT_NE(field, object.fields().end());
    if (field->second.has_string_value()) {
      EXPECT_EQ(field->second.string_value(), value);
    } else {
      ASSERT_TRUE(field->second.has_number_value());
      EXPECT_EQ(field->second.number_value(), std::stod(value));
    }
  }
}

// The body's summary follows the other lines; a genome that builds no body
// prints none.
TEST(CliTest, SimulatePrintsTheBodyItBuilt) {
  const std::string genome = testing::TestData("genomes/seed-1198.json");
  const Outcome text =
      Animat("simulate --genome " + genome + " --config " + ShortConfig());
  ASSERT_EQ(text.exit_code, 0) << text.output;
  const auto lines = KeyValues(text.output);
  std::vector<std::string> keys;
  for (const auto& [key, value] : lines) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{
                      "status", "fitness", "distance", "energy", "max_overlap",
                      "cells", "steps", "state_hash", "springs", "chambers",
                      "skin_edges", "spread_major", "spread_minor"}));
  ASSERT_EQ(lines.size(), keys.size());
  EXPECT_GT(std::stoi(lines[8].second), 0);  // Chambers.

  const Outcome failed =
      Animat("simulate --genome " +
             testing::TestData("genomes/seed-2-too-few-cells.json"));
  ASSERT_EQ(failed.exit_code, 0) << failed.output;
  EXPECT_EQ(failed.output.find("chambers"), std::string::npos) << failed.output;
}

TEST(CliTest, SimulateOfAFailureHasAReasonAndNoFitness) {
  const Outcome run =
      Animat("simulate --genome " +
             testing::TestData("genomes/seed-1-nonviable.json"));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("status: non_viable"), std::string::npos);
  EXPECT_NE(run.output.find("reason: "), std::string::npos);
  EXPECT_EQ(run.output.find("fitness"), std::string::npos);
}

TEST(CliTest, SimulateJsonHasTheTextsKeysAndValues) {
  for (const std::string genome :
       {"genomes/seed-1198.json", "genomes/seed-2-too-few-cells.json",
        "genomes/seed-1-nonviable.json"}) {
    SCOPED_TRACE(genome);
    const std::string arguments = "simulate --genome " +
                                  testing::TestData(genome) + " --config " +
                                  ShortConfig();
    const Outcome text = Animat(arguments);
    const Outcome json = Animat(arguments + " --json");
    ASSERT_EQ(text.exit_code, 0) << text.output;
    ASSERT_EQ(json.exit_code, 0) << json.output;
    ExpectJsonMatchesText(json.output, text.output);
  }
  const Outcome ok = Animat("simulate --json --genome " +
                            testing::TestData("genomes/seed-1198.json") +
                            " --config " + ShortConfig());
  EXPECT_NE(ok.output.find("\"status\": \"ok\""), std::string::npos)
      << ok.output;
  EXPECT_NE(ok.output.find("\"steps\": 800,"), std::string::npos) << ok.output;
  EXPECT_TRUE(std::regex_search(
      ok.output, std::regex("\"state_hash\": \"[0-9a-f]{16}\",")))
      << ok.output;
}

// The text and JSON of `simulate` and the lineage store's row of the same
// evaluation (recorded as the master records a worker's result) hold the
// same values under the same names: status in lowercase, the state hash in
// 16 hex digits, integers as integers.
TEST(CliTest, SimulateAndTheLineageStoreAgree) {
  const std::string genome_path = testing::TestData("genomes/seed-1198.json");
  const std::string arguments =
      "simulate --genome " + genome_path + " --config " + ShortConfig();
  const Outcome text = Animat(arguments);
  const Outcome json = Animat(arguments + " --json");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  ASSERT_EQ(json.exit_code, 0) << json.output;
  ExpectJsonMatchesText(json.output, text.output);

  v1::Genome message;
  ASSERT_TRUE(ReadProtoFile(genome_path, &message).ok());
  Result<Genome> genome = GenomeFromProto(message);
  ASSERT_TRUE(genome.ok());
  v1::Config config_message;
  ASSERT_TRUE(ReadProtoFile(ShortConfig(), &config_message).ok());
  ModelConfig config;
  ASSERT_TRUE(ConfigFromProto(config_message, &config).ok());
  const std::string db = Temp("agree.db");
  for (const char* suffix : {"", "-wal", "-shm", ".lock"}) {
    std::remove((db + suffix).c_str());
  }
  {
    Result<std::unique_ptr<lineage::Store>> store = lineage::Store::Open(db);
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    Result<int64_t> run = (*store)->CreateRun(1, v1::RunConfig(), "test");
    ASSERT_TRUE(run.ok());
    lineage::NewIndividual individual;
    individual.operators = {"random"};
    individual.genome = message;
    ASSERT_TRUE((*store)->AddIndividuals(*run, {individual}).ok());
    lineage::Evaluation evaluation;
    evaluation.result = EvaluationResultToProto(Evaluate(*genome, config));
    ASSERT_TRUE((*store)->RecordEvaluations(*run, {evaluation}).ok());
  }
  sqlite3* handle = nullptr;
  ASSERT_EQ(sqlite3_open_v2(db.c_str(), &handle, SQLITE_OPEN_READONLY, nullptr),
            SQLITE_OK);
  sqlite3_stmt* row = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(handle, "SELECT * FROM evaluations", -1, &row,
                               nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(row), SQLITE_ROW);
  std::map<std::string, int> column;
  for (int c = 0; c < sqlite3_column_count(row); ++c) {
    column[sqlite3_column_name(row, c)] = c;
  }
  for (const auto& [key, value] : KeyValues(text.output)) {
    SCOPED_TRACE(key);
    ASSERT_TRUE(column.contains(key)) << "the store has no column " << key;
    const int c = column[key];
    switch (sqlite3_column_type(row, c)) {
      case SQLITE_TEXT:
        EXPECT_EQ(reinterpret_cast<const char*>(sqlite3_column_text(row, c)),
                  value);
        break;
      case SQLITE_INTEGER:
        EXPECT_EQ(sqlite3_column_int64(row, c), std::stoll(value));
        break;
      case SQLITE_FLOAT:
        EXPECT_EQ(sqlite3_column_double(row, c), std::stod(value));
        break;
      default:
        ADD_FAILURE() << "NULL or a blob in the store";
    }
  }
  sqlite3_finalize(row);
  sqlite3_close(handle);
  for (const char* suffix : {"", "-wal", "-shm", ".lock"}) {
    std::remove((db + suffix).c_str());
  }
}

TEST(CliTest, SimulateWritesACompleteTrace) {
  const std::string trace_path = Temp("trace.json");
  const Outcome run = Animat(
      "simulate --genome " + testing::TestData("genomes/seed-1198.json") +
      " --config " + ShortConfig() + " --trace " + trace_path + " --every 50");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  v1::Trace trace;
  ASSERT_TRUE(ReadProtoFile(trace_path, &trace).ok());
  EXPECT_EQ(trace.config().evaluation().motion_steps(), 200);
  EXPECT_EQ(trace.config().physics().stiffness(), 10.0);  // Defaults too.
  EXPECT_EQ(trace.genome().elements_size(), 30);
  // Development steps 0, 50, ..., 350 and the last, 399.
  ASSERT_EQ(trace.development_size(), 9);
  EXPECT_EQ(trace.development(8).step(), 399);
  EXPECT_EQ(trace.development(8).x_size(), 32);
  EXPECT_EQ(trace.development(0).radius(0), 1.0);
  EXPECT_EQ(trace.body().nodes_size(), 32);
  EXPECT_GT(trace.body().springs_size(), 31);
  EXPECT_GT(trace.body().chambers_size(), 0);
  EXPECT_GT(trace.body().skin_size(), 0);
  // Equilibration 0..200 by 50 (5 frames), motion 0..200 by 50 (5 frames).
  ASSERT_EQ(trace.frames_size(), 10);
  EXPECT_EQ(trace.frames(0).phase(), v1::MotionFrame::EQUILIBRATION);
  EXPECT_EQ(trace.frames(9).phase(), v1::MotionFrame::MOTION);
  EXPECT_EQ(trace.frames(9).step(), 200);
  EXPECT_EQ(trace.frames(9).vx_size(), 32);
  EXPECT_EQ(trace.frames(9).expand_size(), 32);
  EXPECT_EQ(trace.result().status(), v1::EvaluationResult::OK);
  EXPECT_TRUE(trace.result().has_fitness());
}

TEST(CliTest, BadGenomeNamesTheFileAndTheField) {
  const std::string path = Temp("bad.json");
  ASSERT_TRUE(WriteFile(path,
                        R"({"elements": [{"type": "P", "sign": 0, "x": 1,)"
                        R"( "y": 1}]})")
                  .ok());
  const Outcome run = Animat("simulate --genome " + path);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find(path), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("elements[0].sign"), std::string::npos)
      << run.output;
}

TEST(CliTest, MalformedFilesAndUnknownExtensionsAreErrors) {
  const std::string garbage = Temp("garbage.json");
  ASSERT_TRUE(WriteFile(garbage, "{\"elements\": [ {\"type\": \"Q\" ").ok());
  Outcome run = Animat("simulate --genome " + garbage);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find(garbage), std::string::npos) << run.output;

  const std::string unknown = Temp("genome.yaml");
  ASSERT_TRUE(WriteFile(unknown, "elements: []").ok());
  run = Animat("simulate --genome " + unknown);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find(".txtpb"), std::string::npos) << run.output;

  run = Animat("simulate --genome " + Temp("missing.json"));
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("no such file"), std::string::npos);
}

TEST(CliTest, BadConfigNamesTheField) {
  const std::string config = Temp("bad-config.txtpb");
  ASSERT_TRUE(WriteFile(config, "physics { actuation_max: 0.5 }\n").ok());
  const Outcome run = Animat("simulate --genome " +
                             testing::TestData("genomes/seed-1198.json") +
                             " --config " + config);
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("physics.actuation_max"), std::string::npos)
      << run.output;
}

TEST(CliTest, SceneRunsAHandMadeBody) {
  const std::string trace_path = Temp("scene-trace.json");
  const Outcome run =
      Animat("scene --scene " + testing::TestData("scenes/triangle.txtpb") +
             " --steps 100 --every 25 --trace " + trace_path);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("status: ok"), std::string::npos);
  EXPECT_NE(run.output.find("steps: 100"), std::string::npos);
  v1::Trace trace;
  ASSERT_TRUE(ReadProtoFile(trace_path, &trace).ok());
  ASSERT_EQ(trace.frames_size(), 5);  // Steps 0, 25, 50, 75, 100.
  EXPECT_EQ(trace.frames(0).x(1), 2.0);
  EXPECT_EQ(trace.body().chambers_size(), 1);
  EXPECT_EQ(trace.config().physics().mass(), 1.0);
}

TEST(CliTest, SceneWithABadIndexNamesTheField) {
  const std::string path = Temp("bad-scene.txtpb");
  ASSERT_TRUE(WriteFile(path,
                        "body { nodes { x: 0 } nodes { x: 1 } "
                        "springs { a: 0 b: 5 rest_length: 1 } }\n")
                  .ok());
  const Outcome run = Animat("scene --scene " + path + " --steps 10");
  EXPECT_EQ(run.exit_code, 1);
  EXPECT_NE(run.output.find("body.springs[0].b"), std::string::npos)
      << run.output;
}

}  // namespace
}  // namespace animat
