// Helpers shared by the lineage store tests: stores in memory or in
// temporary files, individuals and results made to order, and raw SQL
// reads for checking what the store wrote.
//
// Not thread-safe (like the Store they wrap).
#ifndef ANIMAT_TESTS_LINEAGE_LINEAGE_TEST_UTIL_H_
#define ANIMAT_TESTS_LINEAGE_LINEAGE_TEST_UTIL_H_

#include <unistd.h>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "animat/v1/evolution.pb.h"
#include "animat/v1/genome.pb.h"
#include "animat/v1/trace.pb.h"
#include "master/lineage/store.h"
#include "tests/lineage/store_test_peer.h"

namespace animat::testing {

// A temporary store file, unique to this process and `name`, removed
// (with its -wal, -shm and .lock companions) before use and on
// destruction.
class TempStorePath {
 public:
  explicit TempStorePath(const std::string& name)
      : path_(::testing::TempDir() + "/lineage-" + std::to_string(getpid()) +
              "-" + name + ".db") {
    Remove();
  }
  ~TempStorePath() { Remove(); }
  TempStorePath(const TempStorePath&) = delete;
  TempStorePath& operator=(const TempStorePath&) = delete;

  const std::string& path() const { return path_; }

 private:
  void Remove() const {
    for (const char* suffix : {"", "-wal", "-shm", ".lock"}) {
      std::remove((path_ + suffix).c_str());
    }
  }
  std::string path_;
};

// A private in-memory store; fails the test if it cannot be made.
inline std::unique_ptr<lineage::Store> MemoryStore() {
  Result<std::unique_ptr<lineage::Store>> store = lineage::Store::Open("");
  EXPECT_TRUE(store.ok()) << store.status().ToString();
  return store.ok() ? std::move(store).value() : nullptr;
}

// A small run configuration whose fields differ with `seed`.
inline v1::RunConfig SmallRunConfig(uint64_t seed) {
  v1::RunConfig config;
  config.mutable_model()->mutable_evaluation()->set_motion_steps(300);
  config.mutable_evolution()->set_seed(seed);
  config.mutable_evolution()->set_population(12);
  config.mutable_evolution()->set_generations(5);
  config.mutable_evolution()->set_elite(1);
  return config;
}

// Creates a run; fails the test (returning -1) if it cannot.
inline int64_t MakeRun(lineage::Store& store, uint64_t seed = 7) {
  Result<int64_t> run = store.CreateRun(seed, SmallRunConfig(seed), "test");
  EXPECT_TRUE(run.ok()) << run.status().ToString();
  return run.ok() ? *run : -1;
}

// A genome of `n` elements whose coordinates depend on `tag` (so genomes
// with different tags differ), with values that need all 64 bits.
inline v1::Genome MakeGenome(int n, uint64_t tag) {
  v1::Genome genome;
  for (int i = 0; i < n; ++i) {
    v1::Element* e = genome.add_elements();
    e->set_type(i % 2 == 0 ? v1::Element::P : v1::Element::G_INTERNAL);
    e->set_sign(i % 3 == 0 ? -1 : 1);
    e->set_x(0.1 * static_cast<double>(tag) + 1.0 / 3.0);
    e->set_y(static_cast<double>(i) / 7.0);
  }
  return genome;
}

inline lineage::NewIndividual MakeIndividual(
    uint64_t id, int generation, std::vector<uint64_t> parents = {},
    std::vector<std::string> operators = {"random"}) {
  lineage::NewIndividual n;
  n.id = id;
  n.generation = generation;
  n.parents = std::move(parents);
  n.operators = std::move(operators);
  n.genome = MakeGenome(3, id);
  return n;
}

// An evaluation with status OK and `fitness`.
inline lineage::Evaluation OkEvaluation(uint64_t id, double fitness) {
  lineage::Evaluation e;
  e.id = id;
  e.result.set_status(v1::EvaluationResult::OK);
  e.result.set_fitness(fitness);
  e.result.set_cells(32);
  e.result.set_steps(1000 + static_cast<int64_t>(id));
  e.result.set_state_hash(0x0123456789abcdefULL ^ id);
  e.wall_seconds = 0.25;
  e.worker = "host:42";
  return e;
}

// A body summary that differs with `chambers`, with spreads that need all
// 64 bits.
inline v1::BodySummary MakeBody(int chambers) {
  v1::BodySummary body;
  body.set_cells(32);
  body.set_springs(60 + chambers);
  body.set_chambers(chambers);
  body.set_skin_edges(20 - chambers);
  body.set_spread_major(2.0 + 1.0 / 3.0);
  body.set_spread_minor(0.1 * chambers);
  return body;
}

// A failed evaluation (no fitness).
inline lineage::Evaluation FailedEvaluation(
    uint64_t id,
    v1::EvaluationResult::Status status = v1::EvaluationResult::NON_VIABLE) {
  lineage::Evaluation e;
  e.id = id;
  e.result.set_status(status);
  e.result.set_reason("no path from input to output");
  e.result.set_cells(1);
  e.result.set_steps(0);
  e.wall_seconds = 0.001;
  e.worker = "host:43";
  return e;
}

// Every row of `query`, each column as text, "NULL" for NULL. Fails the
// test on an SQL error.
inline std::vector<std::vector<std::string>> Rows(lineage::Store& store,
                                                  const std::string& query) {
  std::vector<std::vector<std::string>> rows;
  const auto collect = [](void* out, int columns, char** values,
                          char**) -> int {
    std::vector<std::string> row;
    for (int c = 0; c < columns; ++c) {
      row.push_back(values[c] != nullptr ? values[c] : "NULL");
    }
    static_cast<std::vector<std::vector<std::string>>*>(out)->push_back(
        std::move(row));
    return 0;
  };
  char* error = nullptr;
  if (sqlite3_exec(lineage::StoreTestPeer::Database(store).handle(),
                   query.c_str(), collect, &rows, &error) != SQLITE_OK) {
    ADD_FAILURE() << query << ": " << (error != nullptr ? error : "error");
    sqlite3_free(error);
  }
  return rows;
}

// The single value of a one-row, one-column query ("NULL" for NULL).
inline std::string Value(lineage::Store& store, const std::string& query) {
  const std::vector<std::vector<std::string>> rows = Rows(store, query);
  EXPECT_EQ(rows.size(), 1u) << query;
  if (rows.size() != 1 || rows[0].empty()) return "";
  return rows[0][0];
}

inline bool IsHex16(const std::string& text) {
  static const std::regex kHex("^[0-9a-f]{16}$");
  return std::regex_match(text, kHex);
}

// "2026-11-21T14:03:07.123Z".
inline bool IsUtcStamp(const std::string& text) {
  static const std::regex kStamp(
      "^[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}\\.[0-9]{3}Z$");
  return std::regex_match(text, kStamp);
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_LINEAGE_LINEAGE_TEST_UTIL_H_
