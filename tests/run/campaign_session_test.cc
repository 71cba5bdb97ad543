// A campaign's session in this process (master/campaign/campaign_session.h):
// its runs' threads and the thread that pumps their shared dispatcher,
// served by real animat-worker processes; run under ThreadSanitizer in CI.
#include "master/campaign/campaign_session.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "common/io/proto_file.h"
#include "master/lineage/store.h"
#include "tests/dispatch/worker_process.h"

namespace animat {
namespace {

using testing::WorkerArgs;
using testing::WorkerProcess;

// Small bodies, short evaluations, a small population: seconds a run.
constexpr char kRunConfig[] =
    "model {\n"
    "  development { max_cells: 8 }\n"
    "  evaluation { equilibration_steps: 50 motion_steps: 200 }\n"
    "}\n"
    "evolution { population: 12 generations: 3 elite: 2 "
    "initial_min_fitness: 0 }\n";

TEST(CampaignSessionTest, EveryRunIsServedToItsEndThroughOneDispatcher) {
  const std::string dir =
      ::testing::TempDir() + "/campaign-session-" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(WriteFile(dir + "/run.txtpb", kRunConfig).ok());
  ASSERT_TRUE(WriteFile(dir + "/campaign.txtpb",
                        "runs { name: \"r\" config: \"run.txtpb\" "
                        "seeds: [3, 10] }\n")
                  .ok());

  std::mutex mutex;  // The sinks are called from the runs' threads.
  std::vector<std::string> lines;
  std::map<std::string, int> generations;
  CampaignOptions o;
  o.campaign_path = dir + "/campaign.txtpb";
  o.dir = dir + "/runs";
  o.session.bind = "ipc://" + dir + "/master.ipc";
  o.session.heartbeat_ms = 500;
  o.session.log = [&](std::string_view line) {
    std::lock_guard<std::mutex> lock(mutex);
    lines.emplace_back(line);
  };
  o.session.outcome = o.session.log;
  o.session.dispatcher_log = [](std::string_view) {};
  o.progress = [&](const std::string& run, const GenerationReport&) {
    std::lock_guard<std::mutex> lock(mutex);
    ++generations[run];
  };
  std::vector<std::unique_ptr<WorkerProcess>> workers;
  for (int i = 0; i < 2; ++i) {
    WorkerArgs args;
    args.endpoint = o.session.bind;
    args.heartbeat_ms = 500;
    workers.push_back(std::make_unique<WorkerProcess>(args));
  }

  const Status status = RunCampaign(o);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(generations,
            (std::map<std::string, int>{{"r-seed10", 3}, {"r-seed3", 3}}));
  EXPECT_NE(lines.back().find("finished: 2 runs in"), std::string::npos)
      << lines.back();
  for (const char* name : {"r-seed3", "r-seed10"}) {
    Result<std::unique_ptr<lineage::Store>> store =
        lineage::Store::OpenForQueries(o.dir + "/" + name + ".db");
    ASSERT_TRUE(store.ok()) << store.status().ToString();
    Result<std::vector<lineage::RunRow>> runs = (*store)->Runs();
    ASSERT_TRUE(runs.ok() && runs->size() == 1u) << name;
    EXPECT_EQ((*runs)[0].state, "finished") << name;
  }
  workers.clear();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace animat
