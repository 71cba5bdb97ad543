// Runs in the lineage store: CreateRun, Runs, FinishRun, UpdateRunConfig
// and the configuration history it keeps (ConfigHistory).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include <google/protobuf/text_format.h>
#include <google/protobuf/util/message_differencer.h>

#include "common/base/clock.h"
#include "common/protocol/genome_wire.h"
#include "master/lineage/store.h"
#include "tests/lineage/lineage_test_util.h"
#include "tests/lineage/store_test_peer.h"

namespace animat::lineage {
namespace {

using ::animat::testing::IsHex16;
using ::animat::testing::IsUtcStamp;
using ::animat::testing::MemoryStore;
using ::animat::testing::SmallRunConfig;
using ::animat::testing::Value;
using ::google::protobuf::util::MessageDifferencer;

TEST(RunsTest, CreateRunRoundTrips) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  const v1::RunConfig config = SmallRunConfig(3);
  Result<int64_t> run = store->CreateRun(3, config, "animat 0.1 abc gcc x86");
  ASSERT_TRUE(run.ok()) << run.status().ToString();

  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  ASSERT_EQ(runs->size(), 1u);
  const RunRow& row = (*runs)[0];
  EXPECT_EQ(row.run_id, *run);
  EXPECT_EQ(row.seed, 3u);
  EXPECT_TRUE(MessageDifferencer::Equals(row.config, config))
      << row.config.DebugString();
  EXPECT_TRUE(IsHex16(row.config_hash)) << row.config_hash;
  EXPECT_EQ(row.config_hash, Hex64(protocol::MessageHash(config)));
  EXPECT_EQ(row.build_id, "animat 0.1 abc gcc x86");
  EXPECT_TRUE(IsUtcStamp(row.started_at)) << row.started_at;
  EXPECT_EQ(row.ended_at, "");
  EXPECT_EQ(row.state, "running");

  // config_text is the same configuration in text format.
  v1::RunConfig from_text;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(
      Value(*store, "SELECT config_text FROM runs"), &from_text));
  EXPECT_TRUE(MessageDifferencer::Equals(from_text, config));
  EXPECT_EQ(Value(*store, "SELECT ended_at FROM runs"), "NULL");
}

TEST(RunsTest, SeedsAboveTwoToThe63RoundTrip) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  const uint64_t seed = 0xfedcba9876543210ULL;
  ASSERT_TRUE(store->CreateRun(seed, SmallRunConfig(seed), "b").ok());
  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_TRUE(runs.ok());
  ASSERT_EQ(runs->size(), 1u);
  EXPECT_EQ((*runs)[0].seed, seed);
}

TEST(RunsTest, RunsAreListedOldestFirst) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  Result<int64_t> first = store->CreateRun(1, SmallRunConfig(1), "b");
  Result<int64_t> second = store->CreateRun(2, SmallRunConfig(2), "b");
  ASSERT_TRUE(first.ok() && second.ok());
  EXPECT_NE(*first, *second);
  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_TRUE(runs.ok());
  ASSERT_EQ(runs->size(), 2u);
  EXPECT_EQ((*runs)[0].run_id, *first);
  EXPECT_EQ((*runs)[0].seed, 1u);
  EXPECT_EQ((*runs)[1].run_id, *second);
  EXPECT_EQ((*runs)[1].seed, 2u);
  EXPECT_NE((*runs)[0].config_hash, (*runs)[1].config_hash);
}

TEST(RunsTest, FinishRunSetsEndedAtAndState) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  Result<int64_t> run = store->CreateRun(1, SmallRunConfig(1), "b");
  Result<int64_t> other = store->CreateRun(2, SmallRunConfig(2), "b");
  ASSERT_TRUE(run.ok() && other.ok());
  ASSERT_TRUE(store->FinishRun(*run).ok());
  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_TRUE(runs.ok());
  ASSERT_EQ(runs->size(), 2u);
  EXPECT_EQ((*runs)[0].state, "finished");
  EXPECT_TRUE(IsUtcStamp((*runs)[0].ended_at)) << (*runs)[0].ended_at;
  EXPECT_GE((*runs)[0].ended_at, (*runs)[0].started_at);
  // Only that run.
  EXPECT_EQ((*runs)[1].state, "running");
  EXPECT_EQ((*runs)[1].ended_at, "");
}

TEST(RunsTest, UpdateRunConfigReplacesConfigAndMarksRunning) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  Result<int64_t> run = store->CreateRun(1, SmallRunConfig(1), "b");
  ASSERT_TRUE(run.ok());
  ASSERT_TRUE(store->FinishRun(*run).ok());
  v1::RunConfig longer = SmallRunConfig(1);
  longer.mutable_evolution()->set_generations(40);
  ASSERT_TRUE(
      store->UpdateRunConfig(*run, 20, longer, "b", "generations set to 40")
          .ok());

  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_TRUE(runs.ok());
  ASSERT_EQ(runs->size(), 1u);
  const RunRow& row = (*runs)[0];
  EXPECT_TRUE(MessageDifferencer::Equals(row.config, longer));
  EXPECT_EQ(row.config_hash, Hex64(protocol::MessageHash(longer)));
  EXPECT_NE(row.config_hash, Hex64(protocol::MessageHash(SmallRunConfig(1))));
  EXPECT_EQ(row.state, "running");
  EXPECT_EQ(row.ended_at, "");
  EXPECT_EQ(row.build_id, "b");
  v1::RunConfig from_text;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(
      Value(*store, "SELECT config_text FROM runs"), &from_text));
  EXPECT_TRUE(MessageDifferencer::Equals(from_text, longer));
}

// After a forced resume with a configuration of another seed, the row's
// seed column agrees with its configuration.
TEST(RunsTest, UpdateRunConfigKeepsSeedColumnInStepWithConfig) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  Result<int64_t> run = store->CreateRun(1, SmallRunConfig(1), "b");
  ASSERT_TRUE(run.ok());
  ASSERT_TRUE(
      store->UpdateRunConfig(*run, 3, SmallRunConfig(9), "b", "--force").ok());
  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_TRUE(runs.ok());
  ASSERT_EQ(runs->size(), 1u);
  EXPECT_EQ((*runs)[0].seed, (*runs)[0].config.evolution().seed());
}

// Issue 14: a forced resume replaced the run's configuration and nothing
// recorded that earlier generations ran with the old one. The history
// keeps every configuration, from which generation, by which build, why.
TEST(RunsTest, ConfigHistoryKeepsEveryConfigurationFromItsGeneration) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  Result<int64_t> run = store->CreateRun(1, SmallRunConfig(1), "build-a");
  Result<int64_t> other = store->CreateRun(2, SmallRunConfig(2), "build-a");
  ASSERT_TRUE(run.ok() && other.ok());
  v1::RunConfig longer = SmallRunConfig(1);
  longer.mutable_evolution()->set_generations(40);
  ASSERT_TRUE(store
                  ->UpdateRunConfig(*run, 12, longer, "build-a",
                                    "generations set to 40")
                  .ok());
  ASSERT_TRUE(store
                  ->UpdateRunConfig(*run, 25, SmallRunConfig(9), "build-b",
                                    "--force: the configuration given differs")
                  .ok());

  Result<std::vector<RunConfigRow>> history = store->ConfigHistory(*run);
  ASSERT_TRUE(history.ok()) << history.status().ToString();
  ASSERT_EQ(history->size(), 3u);
  const std::vector<
      std::tuple<int, int, v1::RunConfig, std::string, std::string>>
      expected = {{0, 0, SmallRunConfig(1), "build-a", "started"},
                  {1, 12, longer, "build-a", "generations set to 40"},
                  {2, 25, SmallRunConfig(9), "build-b",
                   "--force: the configuration given differs"}};
  for (size_t i = 0; i < expected.size(); ++i) {
    SCOPED_TRACE("change " + std::to_string(i));
    const RunConfigRow& row = (*history)[i];
    const auto& [change, from, config, build, reason] = expected[i];
    EXPECT_EQ(row.change, change);
    EXPECT_EQ(row.from_generation, from);
    EXPECT_TRUE(MessageDifferencer::Equals(row.config, config));
    EXPECT_EQ(row.config_hash, Hex64(protocol::MessageHash(config)));
    EXPECT_EQ(row.build_id, build);
    EXPECT_EQ(row.reason, reason);
    EXPECT_TRUE(IsUtcStamp(row.recorded_at)) << row.recorded_at;
  }
  // The run's row shows the last; the other run's history is its own.
  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_TRUE(runs.ok());
  EXPECT_EQ((*runs)[0].config_hash, (*history)[2].config_hash);
  EXPECT_EQ((*runs)[0].build_id, "build-b");
  Result<std::vector<RunConfigRow>> others = store->ConfigHistory(*other);
  ASSERT_TRUE(others.ok());
  ASSERT_EQ(others->size(), 1u);
  EXPECT_TRUE(
      MessageDifferencer::Equals((*others)[0].config, SmallRunConfig(2)));
  Result<std::vector<RunConfigRow>> none = store->ConfigHistory(99);
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
  // config_text is each configuration in text format.
  v1::RunConfig from_text;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(
      Value(*store, "SELECT config_text FROM run_configs WHERE run_id = " +
                        std::to_string(*run) + " AND change = 1"),
      &from_text));
  EXPECT_TRUE(MessageDifferencer::Equals(from_text, longer));
}

// A change is all or nothing: the run's row and its history agree.
TEST(RunsTest, ConfigChangeOfAnUnknownRunLeavesNoHistory) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  Result<int64_t> run = store->CreateRun(1, SmallRunConfig(1), "b");
  ASSERT_TRUE(run.ok());
  // run_configs refers to runs: the insert fails, and the update with it.
  EXPECT_FALSE(
      store->UpdateRunConfig(*run + 1, 2, SmallRunConfig(3), "b", "x").ok());
  EXPECT_EQ(Value(*store, "SELECT COUNT(*) FROM run_configs"), "1");
}

TEST(RunsTest, UnreadableConfigurationIsReportedNotIgnored) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->CreateRun(1, SmallRunConfig(1), "b").ok());
  ASSERT_TRUE(StoreTestPeer::Database(*store)
                  .Execute("UPDATE runs SET config = X'ffffffff'")
                  .ok());
  Result<std::vector<RunRow>> runs = store->Runs();
  ASSERT_FALSE(runs.ok());
  EXPECT_NE(runs.status().message().find("unreadable configuration"),
            std::string::npos)
      << runs.status().message();
}

TEST(RunsTest, StateIsCheckedBySchema) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  ASSERT_TRUE(store->CreateRun(1, SmallRunConfig(1), "b").ok());
  EXPECT_FALSE(StoreTestPeer::Database(*store)
                   .Execute("UPDATE runs SET state = 'paused'")
                   .ok());
  EXPECT_EQ(Value(*store, "SELECT state FROM runs"), "running");
}

// Every time the store records is its clock's: on a manual clock, exactly
// the times the test set.
TEST(RunsTest, EveryTimeRecordedIsTheStoresClocks) {
  ManualClock clock;
  clock.Advance(std::chrono::hours(24 * 365));  // 1971-01-01.
  Result<std::unique_ptr<Store>> opened = Store::Open("", clock);
  ASSERT_TRUE(opened.ok()) << opened.status().ToString();
  Store& store = **opened;
  const int64_t run = ::animat::testing::MakeRun(store);
  clock.Advance(std::chrono::milliseconds(1500));
  ASSERT_TRUE(
      store
          .AddGeneration(run, 0, {0}, {::animat::testing::MakeIndividual(0, 0)})
          .ok());
  clock.Advance(std::chrono::minutes(2));
  ASSERT_TRUE(
      store.RecordEvaluations(run, {::animat::testing::OkEvaluation(0, 2.0)})
          .ok());
  clock.Advance(std::chrono::hours(3));
  GenerationStats stats;
  stats.evaluated = 1;
  stats.best_id = 0;
  stats.best = stats.mean = stats.median = 2.0;
  ASSERT_TRUE(store.CompleteGeneration(run, 0, {0}, stats).ok());
  clock.Advance(std::chrono::milliseconds(1));
  ASSERT_TRUE(store.FinishRun(run).ok());

  EXPECT_EQ(Value(store, "SELECT started_at FROM runs"),
            "1971-01-01T00:00:00.000Z");
  EXPECT_EQ(Value(store, "SELECT recorded_at FROM run_configs"),
            "1971-01-01T00:00:00.000Z");
  EXPECT_EQ(Value(store, "SELECT created_at FROM births"),
            "1971-01-01T00:00:01.500Z");
  EXPECT_EQ(Value(store, "SELECT created_at FROM generations"),
            "1971-01-01T00:00:01.500Z");
  EXPECT_EQ(Value(store, "SELECT evaluated_at FROM evaluations"),
            "1971-01-01T00:02:01.500Z");
  EXPECT_EQ(Value(store, "SELECT completed_at FROM generations"),
            "1971-01-01T03:02:01.500Z");
  EXPECT_EQ(Value(store, "SELECT ended_at FROM runs"),
            "1971-01-01T03:02:01.501Z");
}

}  // namespace
}  // namespace animat::lineage
