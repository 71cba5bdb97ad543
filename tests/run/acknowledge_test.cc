// The run acknowledges a result to its worker only once it is committed:
// a worker told it may forget a result finds it in the store (read through
// a connection of its own, as another process would), so a master killed
// at any moment leaves every unrecorded result with a worker that will send
// it again (docs/lineage.md, "Durability").
//
// The run serves on a thread of its own, on simulated time (a ManualClock
// that the test thread advances as it plays the worker, over inproc://), so
// no heartbeat or liveness depends on how fast either thread runs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>
#include <zmq.hpp>

#include "common/base/clock.h"
#include "common/protocol/protocol.h"
#include "master/dispatch/dispatcher.h"
#include "master/lineage/sqlite.h"
#include "master/lineage/store.h"
#include "master/run/evolution_run.h"
#include "tests/dispatch/fake_peers.h"

namespace animat {
namespace {

using testing::FakeWorker;

// Reads the store at `path` through a read-only connection of its own, as
// another process would; each question sees the latest commit.
class StoreReader {
 public:
  explicit StoreReader(const std::string& path) {
    Result<std::unique_ptr<sql::Database>> db =
        sql::Database::Open(path, /*read_only=*/true);
    if (db.ok()) db_ = std::move(db).value();
  }
  // Whether the store holds an evaluation of `id`.
  bool Recorded(uint64_t id) {
    if (db_ == nullptr) return false;
    Result<sql::Statement> select =
        db_->Cached("SELECT COUNT(*) FROM evaluations WHERE id = ?");
    if (!select.ok()) return false;
    select->Bind(1, static_cast<int64_t>(id));
    Result<bool> row = select->Step();
    return row.ok() && *row && select->Int(0) == 1;
  }

 private:
  std::unique_ptr<sql::Database> db_;
};

TEST(AcknowledgeTest, AResultIsAcknowledgedOnlyOnceTheStoreHoldsIt) {
  const std::string path =
      std::string(std::getenv("TMPDIR") != nullptr ? std::getenv("TMPDIR")
                                                   : "/tmp") +
      "/animat-acknowledge-" + std::to_string(getpid()) + ".db";
  std::vector<std::string> files = {path, path + "-wal", path + "-shm",
                                    path + ".lock"};
  for (const std::string& f : files) std::remove(f.c_str());
  {
    Result<std::unique_ptr<lineage::Store>> store = lineage::Store::Open(path);
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    RunSettings settings;
    settings.evolution.seed = 5;
    settings.evolution.population = 4;
    settings.evolution.generations = 2;
    settings.evolution.elite = 1;
    Result<std::unique_ptr<EvolutionRun>> run =
        EvolutionRun::Start(store->get(), settings, [](std::string_view) {});
    ASSERT_TRUE(run.ok()) << run.status().ToString();
    ManualClock clock;
    zmq::context_t context(1);
    DispatcherOptions options;
    options.endpoint = "inproc://run-acknowledge-test";
    options.heartbeat_ms = 100;
    options.acknowledge_on_receipt = false;  // As animat-master.
    options.log = [](std::string_view) {};
    options.clock = &clock;
    Result<std::unique_ptr<Dispatcher>> dispatcher = Dispatcher::Create(
        &context, options, ConfigToProto((*run)->model_config()));
    ASSERT_TRUE(dispatcher.ok()) << dispatcher.status().ToString();

    std::atomic<bool> stop{false};
    std::atomic<bool> done{false};
    Status status;
    std::thread master([&] {
      status = (*run)->Run(dispatcher->get(), stop);
      done.store(true);
    });

    // A worker played by the test: every item gets a result at once (OK,
    // fitness 1 + its id / 10^6) and its credit back.
    FakeWorker fake(context, (*dispatcher)->endpoint(), clock);
    fake.Hello(1, 6161, 99);
    fake.Credit(64);
    StoreReader reader(path);
    std::set<uint64_t> answered;
    std::set<uint64_t> acknowledged;
    std::vector<uint64_t> early;  // Acknowledged before they were recorded.
    size_t items_seen = 0;
    size_t envelopes_seen = 0;
    const auto deadline =
        std::chrono::steady_clock::now() +
        std::chrono::seconds(600);  // Slow sanitizer builds included.
    const auto settle = [&] {
      fake.Pump();
      const std::vector<v1::WorkItem>& items = fake.work_items();
      if (items.size() > items_seen) {
        v1::Envelope results;
        for (; items_seen < items.size(); ++items_seen) {
          const v1::WorkItem& item = items[items_seen];
          v1::WorkResult* r = results.mutable_results()->add_results();
          r->set_individual(item.individual());
          r->set_genome_hash(item.genome_hash());
          r->mutable_result()->set_status(v1::EvaluationResult::OK);
          r->mutable_result()->set_fitness(
              1.0 + static_cast<double>(item.individual()) * 1e-6);
          r->set_wall_seconds(0.001);
          answered.insert(item.individual());
        }
        fake.Send(results);
        fake.Credit(static_cast<uint32_t>(results.results().results_size()));
      }
      const std::vector<v1::Envelope>& received = fake.received();
      for (; envelopes_seen < received.size(); ++envelopes_seen) {
        const v1::Envelope& e = received[envelopes_seen];
        if (!e.has_acknowledge()) continue;
        for (uint64_t id : e.acknowledge().individuals()) {
          if (!reader.Recorded(id)) early.push_back(id);
          acknowledged.insert(id);
        }
      }
    };
    while (!done.load() && std::chrono::steady_clock::now() < deadline) {
      settle();
      clock.Advance(std::chrono::milliseconds(1));
      fake.PumpWhenReady(std::chrono::milliseconds(1));
    }
    stop.store(true);
    master.join();
    ASSERT_TRUE(status.ok()) << status.ToString();
    EXPECT_TRUE((*run)->finished());
    // The last acknowledgements, sent as the run ended: over inproc://
    // whatever the master sent is there to read at once.
    settle();
    EXPECT_TRUE(early.empty()) << early.size()
                               << " results acknowledged before they were "
                                  "recorded, the first "
                               << (early.empty() ? 0 : early.front());
    // Every result the run recorded was acknowledged; one it never needed
    // (a candidate answered after the population was chosen is recorded
    // too, or dropped with the run's end) may not be.
    ASSERT_FALSE(answered.empty());
    size_t recorded = 0;
    for (uint64_t id : answered) {
      if (!reader.Recorded(id)) continue;
      ++recorded;
      EXPECT_EQ(acknowledged.count(id), 1u) << "individual " << id;
    }
    EXPECT_GT(recorded, 4u);
  }
  for (const std::string& f : files) std::remove(f.c_str());
}

}  // namespace
}  // namespace animat
