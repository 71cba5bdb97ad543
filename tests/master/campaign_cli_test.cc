// `animat campaign` end to end: several runs served at once by one master
// and one pool of local workers give, each, the store of the same run made
// alone, even when the campaign is killed with SIGKILL and started again;
// a finished campaign changes nothing, runs added to its file run alone,
// and `animat campaign status` says where each run stands.
#include <csignal>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

class CampaignCliTest : public MasterTest {
 protected:
  // animat campaign on the test's campaign file and folder.
  std::unique_ptr<ChildProcess> StartCampaign() {
    return StartAnimat({"campaign", "--campaign", Path("campaign.txtpb"),
                        "--dir", Path("runs"), "--workers", "2"});
  }
  // Runs the campaign command to its end; its output.
  std::string CampaignToEnd() {
    std::unique_ptr<ChildProcess> campaign = StartCampaign();
    if (!AwaitExit(*campaign, kRunWait, "the campaign")) return "";
    EXPECT_EQ(campaign->exit_code(), 0) << campaign->output();
    return campaign->output();
  }
  // The store of `run` made alone by animat-master with one worker.
  StoreContents Alone(const std::string& name, const TestRun& run) {
    const std::string db = Path("alone-" + name + ".db");
    RunToEnd(WriteConfig("alone-" + name + ".txtpb", run), db, 1);
    return ReadStoreContents(db);
  }
  std::string Store(const std::string& name) const {
    return Path("runs/" + name + ".db");
  }
};

TEST_F(CampaignCliTest, KilledAndStartedAgainEachRunIsTheRunMadeAlone) {
  TestRun base;
  base.generations = 6;
  base.motion_steps = kMotionStepsForSlowGenerations;
  WriteConfig("base.txtpb", base);
  ASSERT_TRUE(WriteFile(Path("campaign.txtpb"),
                        "runs { name: \"t\" config: \"base.txtpb\" "
                        "seeds: [3, 10] }\n"
                        "runs { name: \"small\" config: \"base.txtpb\" "
                        "set: \"evolution { population: 16 }\" }\n")
                  .ok());
  std::map<std::string, TestRun> runs;
  runs["t-seed3"] = base;
  runs["t-seed10"] = base;
  runs["t-seed10"].seed = 10;
  runs["small"] = base;
  runs["small"].population = 16;

  std::unique_ptr<ChildProcess> campaign = StartCampaign();
  ASSERT_TRUE(AwaitStore(
      Store("t-seed3"),
      [](const Progress& p) { return p.complete_generations >= 2; }, *campaign))
      << campaign->output();
  ASSERT_TRUE(campaign->Signal(SIGKILL));
  ASSERT_TRUE(AwaitExit(*campaign, kStepWait, "SIGKILL"));
  EXPECT_FALSE(ReadProgress(Store("t-seed3")).finished);

  const std::string resumed = CampaignToEnd();
  EXPECT_NE(resumed.find("finished: 3 runs in"), std::string::npos) << resumed;
  for (const auto& [name, run] : runs) {
    SCOPED_TRACE(name);
    ExpectSameContents(Alone(name, run), ReadStoreContents(Store(name)));
  }

  // Finished: said, and nothing changes.
  const StoreContents before = ReadStoreContents(Store("t-seed3"));
  const std::string again = CampaignToEnd();
  EXPECT_NE(again.find("the campaign is finished: its 3 runs"),
            std::string::npos)
      << again;
  ExpectSameContents(before, ReadStoreContents(Store("t-seed3")));

  // A run added to the file runs alone.
  ASSERT_TRUE(WriteFile(Path("campaign.txtpb"),
                        "runs { name: \"t\" config: \"base.txtpb\" "
                        "seeds: [3, 10, 4] }\n"
                        "runs { name: \"small\" config: \"base.txtpb\" "
                        "set: \"evolution { population: 16 }\" }\n")
                  .ok());
  const std::string added = CampaignToEnd();
  EXPECT_NE(added.find("1 of 4 runs to serve (3 finished)"), std::string::npos)
      << added;
  EXPECT_TRUE(ReadProgress(Store("t-seed4")).finished);
  ExpectSameContents(before, ReadStoreContents(Store("t-seed3")));

  std::unique_ptr<ChildProcess> status =
      StartAnimat({"campaign", "status", "--dir", Path("runs"), "--campaign",
                   Path("campaign.txtpb")});
  ASSERT_TRUE(AwaitExit(*status, kStepWait, "campaign status"));
  EXPECT_EQ(status->exit_code(), 0) << status->output();
  for (const char* name : {"t-seed3", "t-seed10", "t-seed4", "small"}) {
    EXPECT_NE(status->output().find(name), std::string::npos)
        << status->output();
  }
  EXPECT_NE(status->output().find("6/6"), std::string::npos)
      << status->output();
  EXPECT_NE(status->output().find("4 of 4 runs finished"), std::string::npos)
      << status->output();
}

// A campaign file can say that runs still improving go on
// (evolution.extend_to): each run makes as many generations as its own
// statistics decide, and `animat campaign status` counts to that.
TEST_F(CampaignCliTest, RunsStillImprovingGoOnAndStatusCountsToTheirEnd) {
  TestRun base;
  base.generations = 4;
  WriteConfig("base.txtpb", base);
  ASSERT_TRUE(WriteFile(Path("campaign.txtpb"),
                        "runs { name: \"x\" config: \"base.txtpb\" set: "
                        "\"evolution { extend_to: 7 extend_window: 1 }\" "
                        "seeds: [3, 10] }\n")
                  .ok());
  CampaignToEnd();
  std::unique_ptr<ChildProcess> status =
      StartAnimat({"campaign", "status", "--dir", Path("runs")});
  ASSERT_TRUE(AwaitExit(*status, kStepWait, "campaign status"));
  EXPECT_EQ(status->exit_code(), 0) << status->output();
  for (const char* name : {"x-seed3", "x-seed10"}) {
    SCOPED_TRACE(name);
    const std::string db = Store(name);
    const std::vector<SqlRow> best = QueryRows(
        db,
        "SELECT COALESCE((SELECT best_fitness FROM generation_statistics"
        " WHERE generation = 3), -1e300) > COALESCE((SELECT best_fitness"
        " FROM generation_statistics WHERE generation = 2), -1e300)");
    const int length = best.at(0).at(0) == "1" ? 7 : 4;
    const Progress done = ReadProgress(db);
    EXPECT_TRUE(done.finished) << done.ToString();
    EXPECT_EQ(done.complete_generations, length) << done.ToString();
    // The run's line: its name, then generations done / of the run.
    const std::string& out = status->output();
    const size_t at = out.find(std::string(name) + " ");
    ASSERT_NE(at, std::string::npos) << out;
    const std::string line = out.substr(at, out.find('\n', at) - at);
    std::string counted = std::to_string(length);
    counted += "/";
    counted += std::to_string(length);
    EXPECT_NE(line.find(counted), std::string::npos) << line;
  }
}

// A run that goes on while improving, killed past its `generations`,
// resumes to the run made alone, and once finished it is left alone: the
// campaign file's `generations` is not its length.
TEST_F(CampaignCliTest, AnExtensionKilledOnTheWayResumesAndThenStaysFinished) {
  TestRun base;
  base.generations = 4;
  base.motion_steps = kMotionStepsForSlowGenerations;
  WriteConfig("base.txtpb", base);
  ASSERT_TRUE(WriteFile(Path("campaign.txtpb"),
                        "runs { name: \"x\" config: \"base.txtpb\" set: "
                        "\"evolution { extend_to: 7 extend_window: 1 }\" "
                        "seeds: [10] }\n")
                  .ok());
  std::unique_ptr<ChildProcess> campaign = StartCampaign();
  // Seed 10 is still improving at generation 3, so it goes on to 7.
  ASSERT_TRUE(AwaitStore(
      Store("x-seed10"),
      [](const Progress& p) { return p.complete_generations >= 5; }, *campaign))
      << campaign->output();
  ASSERT_TRUE(campaign->Signal(SIGKILL));
  ASSERT_TRUE(AwaitExit(*campaign, kStepWait, "SIGKILL"));
  ASSERT_FALSE(ReadProgress(Store("x-seed10")).finished)
      << "the run ended before it was killed: the test needs a slower run";

  CampaignToEnd();
  TestRun alone = base;
  alone.seed = 10;
  alone.evolution_extra = "extend_to: 7 extend_window: 1";
  const StoreContents made = ReadStoreContents(Store("x-seed10"));
  ExpectSameContents(Alone("x-seed10", alone), made);
  EXPECT_EQ(ReadProgress(Store("x-seed10")).complete_generations, 7);

  const std::string again = CampaignToEnd();
  EXPECT_NE(again.find("the campaign is finished: its 1 runs"),
            std::string::npos)
      << again;
  ExpectSameContents(made, ReadStoreContents(Store("x-seed10")));
}

// animat-master --campaign serves workers started elsewhere (here, on the
// test's endpoint) as it serves one run's.
TEST_F(CampaignCliTest, AnimatMasterServesACampaignToWorkersItDidNotStart) {
  TestRun base;
  WriteConfig("base.txtpb", base);
  ASSERT_TRUE(WriteFile(Path("campaign.txtpb"),
                        "runs { name: \"m\" config: \"base.txtpb\" "
                        "seeds: [3, 10] }\n")
                  .ok());
  std::unique_ptr<ChildProcess> master = StartMaster(
      {"--campaign", Path("campaign.txtpb"), "--dir", Path("runs")});
  const auto workers = StartWorkers(2);
  ASSERT_TRUE(AwaitExit(*master, kRunWait, "the campaign's master"));
  EXPECT_EQ(master->exit_code(), 0) << master->output();
  EXPECT_NE(master->output().find("finished: 2 runs in"), std::string::npos)
      << master->output();
  TestRun seed10 = base;
  seed10.seed = 10;
  ExpectSameContents(Alone("m-seed10", seed10),
                     ReadStoreContents(Store("m-seed10")));

  // --campaign goes with --dir, and not with one run's options.
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{
           {"--campaign", Path("campaign.txtpb")},
           {"--campaign", Path("campaign.txtpb"), "--dir", Path("runs"), "--db",
            Path("x.db")},
           {"--bind", Endpoint()}}) {
    std::unique_ptr<ChildProcess> wrong = StartMaster(args);
    ASSERT_TRUE(AwaitExit(*wrong, kStepWait, "a usage error"));
    EXPECT_EQ(wrong->exit_code(), 2) << wrong->output();
  }
}

// Runs that differ in their model (here the drag) share the workers: each
// is sent every configuration with its first work of it, and each store is
// the run made alone.
TEST_F(CampaignCliTest, RunsOfDifferentModelsShareTheWorkersEachAsAlone) {
  TestRun base;
  base.generations = 4;
  WriteConfig("base.txtpb", base);
  ASSERT_TRUE(WriteFile(Path("campaign.txtpb"),
                        "runs { config: \"base.txtpb\" axes { "
                        "values { label: \"dn1\" } "
                        "values { label: \"dn10\" set: \"model { physics { "
                        "drag_normal: 10 } }\" } } seeds: [3] }\n")
                  .ok());
  const std::string output = CampaignToEnd();
  EXPECT_NE(output.find("finished: 2 runs in"), std::string::npos) << output;
  ExpectSameContents(Alone("dn1", base), ReadStoreContents(Store("dn1-seed3")));
  std::string dn10 = base.Text();
  dn10.insert(dn10.find("model {\n") + 8, "  physics { drag_normal: 10 }\n");
  ASSERT_TRUE(WriteFile(Path("alone-dn10.txtpb"), dn10).ok());
  RunToEnd(Path("alone-dn10.txtpb"), Path("alone-dn10.db"), 1);
  ExpectSameContents(ReadStoreContents(Path("alone-dn10.db")),
                     ReadStoreContents(Store("dn10-seed3")));
  // The two models' runs differ, so each ran under its own.
  EXPECT_NE(ReadStoreContents(Store("dn1-seed3")).individuals,
            ReadStoreContents(Store("dn10-seed3")).individuals);
}

}  // namespace
}  // namespace animat::testing
