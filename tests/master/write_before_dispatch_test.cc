// A genome leaves the master only once its individual is committed to the
// store: a worker played by the test (real protocol, real evaluations)
// looks each received individual up in the store, through a read-only
// connection of its own, before evaluating it.
#include <sqlite3.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>
#include <zmq.hpp>

#include "common/evaluation/model_config.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "tests/dispatch/dispatch_harness.h"
#include "tests/dispatch/fake_peers.h"
#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

// The committed genome of an individual, read as any reader of the store
// sees it (each lookup its own read transaction).
class CommittedGenomes {
 public:
  explicit CommittedGenomes(const std::string& path) {
    if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) !=
        SQLITE_OK) {
      ADD_FAILURE() << path << ": " << sqlite3_errmsg(db_);
      return;
    }
    sqlite3_busy_timeout(db_, 5000);
    if (sqlite3_prepare_v2(db_, "SELECT genome FROM individuals WHERE id = ?",
                           -1, &select_, nullptr) != SQLITE_OK) {
      ADD_FAILURE() << path << ": " << sqlite3_errmsg(db_);
    }
  }
  ~CommittedGenomes() {
    sqlite3_finalize(select_);
    sqlite3_close(db_);
  }

  // The stored serialised genome of `id`, or nothing if it is not there.
  std::optional<std::string> Find(uint64_t id) {
    if (select_ == nullptr) return std::nullopt;
    sqlite3_reset(select_);
    sqlite3_bind_int64(select_, 1, static_cast<sqlite3_int64>(id));
    const int rc = sqlite3_step(select_);
    if (rc != SQLITE_ROW) {
      if (rc != SQLITE_DONE) ADD_FAILURE() << sqlite3_errmsg(db_);
      return std::nullopt;
    }
    const auto* bytes =
        static_cast<const char*>(sqlite3_column_blob(select_, 0));
    std::string genome(bytes,
                       static_cast<size_t>(sqlite3_column_bytes(select_, 0)));
    sqlite3_reset(select_);
    return genome;
  }

 private:
  sqlite3* db_ = nullptr;
  sqlite3_stmt* select_ = nullptr;
};

TEST_F(MasterTest, EveryGenomeAWorkerReceivesIsAlreadyCommitted) {
  TestRun run;
  run.seed = 40;
  run.generations = 2;
  const std::string db = Path("run.db");
  std::unique_ptr<ChildProcess> master =
      StartRun(WriteConfig("run.txtpb", run), db);

  zmq::context_t context(1);
  FakeWorker worker(context, Endpoint());
  constexpr int kThreads = 2;
  worker.Hello(kThreads, 4242);
  const auto end = Clock::now() + kStepWait;
  while (!worker.welcomed() && Clock::now() < end && master->Running()) {
    worker.Pump();
    std::this_thread::sleep_for(milliseconds(5));
  }
  ASSERT_TRUE(worker.welcomed()) << master->Describe() << "\n"
                                 << master->output();
  ModelConfig config;
  for (const v1::Envelope& e : worker.received()) {
    if (e.has_welcome()) {
      ASSERT_TRUE(ConfigFromProto(e.welcome().config(), &config).ok());
    }
  }
  // The store exists: the master opens it before it serves.
  CommittedGenomes committed(db);
  worker.Credit(2 * kThreads);  // Work waits here as with a real worker.

  // Items are looked up as they arrive, then evaluated kThreads at a time
  // on other threads while this one keeps the session alive.
  struct InFlight {
    v1::WorkItem item;
    std::future<v1::EvaluationResult> result;
  };
  std::deque<InFlight> in_flight;
  size_t looked_up = 0;
  size_t next = 0;
  std::map<uint64_t, int> received;
  int missing = 0, different = 0;
  const auto run_end = Clock::now() + kRunWait;
  while (master->Running() && Clock::now() < run_end) {
    worker.Pump();
    const std::vector<v1::WorkItem>& items = worker.work_items();
    for (; looked_up < items.size(); ++looked_up) {
      const v1::WorkItem& item = items[looked_up];
      ++received[item.individual()];
      const std::optional<std::string> stored =
          committed.Find(item.individual());
      if (!stored) {
        if (++missing <= 5) {
          ADD_FAILURE() << "individual " << item.individual()
                        << " received before it was committed";
        }
      } else if (*stored != item.genome().SerializeAsString() ||
                 protocol::GenomeHash(item.genome()) != item.genome_hash()) {
        if (++different <= 5) {
          ADD_FAILURE() << "individual " << item.individual()
                        << " received with another genome than stored";
        }
      }
    }
    while (in_flight.size() < static_cast<size_t>(kThreads) &&
           next < items.size()) {
      const v1::WorkItem& item = items[next++];
      in_flight.push_back(
          {item,
           std::async(std::launch::async, [genome = item.genome(), &config] {
             return EvaluateDirectly(genome, config);
           })});
    }
    bool answered = false;
    while (!in_flight.empty() && in_flight.front().result.wait_for(milliseconds(
                                     0)) == std::future_status::ready) {
      v1::Envelope results;
      v1::WorkResult* r = results.mutable_results()->add_results();
      r->set_individual(in_flight.front().item.individual());
      r->set_genome_hash(in_flight.front().item.genome_hash());
      *r->mutable_result() = in_flight.front().result.get();
      worker.Send(results);
      worker.Credit(1);
      in_flight.pop_front();
      answered = true;
    }
    if (!answered) std::this_thread::sleep_for(milliseconds(1));
  }
  ASSERT_TRUE(AwaitExit(*master, milliseconds(0), "the run"));
  ASSERT_EQ(master->exit_code(), 0) << master->output();
  EXPECT_EQ(missing, 0);
  EXPECT_EQ(different, 0);

  // Every individual of the finished run came through this worker, but
  // the copies of a parent's genome, which took its evaluation.
  const Progress done = ReadProgress(db);
  EXPECT_TRUE(done.finished) << done.ToString();
  const int64_t reused = QueryInt(
      db, "SELECT COUNT(*) FROM evaluations WHERE reused_from IS NOT NULL");
  EXPECT_EQ(static_cast<int64_t>(received.size()), done.individuals - reused);
  for (const SqlRow& row :
       QueryRows(db,
                 "SELECT id FROM evaluations WHERE reused_from IS NOT"
                 " NULL")) {
    EXPECT_EQ(received.count(std::stoull(row.at(0))), 0u) << row.at(0);
  }
  EXPECT_EQ(done.complete_generations, run.generations);
}

}  // namespace
}  // namespace animat::testing
