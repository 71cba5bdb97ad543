// The campaign file expanded into runs (master/campaign/campaign_file.h):
// names, merge order, grids, seeds, and errors that name the entry.
#include "master/campaign/campaign_file.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "common/io/proto_file.h"

namespace animat {
namespace {

v1::Campaign Parse(const std::string& text) {
  v1::Campaign campaign;
  const Status status = ParseProto(text, ProtoFormat::kText, &campaign);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return campaign;
}

std::vector<std::string> Names(const std::vector<CampaignRun>& runs) {
  std::vector<std::string> names;
  for (const CampaignRun& run : runs) names.push_back(run.name);
  return names;
}

// The error of expanding `text`, or "" when it expands.
std::string ErrorOf(const std::string& text) {
  Result<std::vector<CampaignRun>> runs = ExpandCampaign(Parse(text), "");
  return runs.ok() ? "" : runs.status().message();
}

TEST(CampaignFileTest, AGridTimesSeedsGivesEveryCombinationInOrder) {
  Result<std::vector<CampaignRun>> runs = ExpandCampaign(Parse(R"(
    runs {
      name: "paper"
      set: "evolution { population: 30 generations: 5 }"
      axes { values { label: "dn0.1" set: "model { physics { drag_normal: 0.1 } }" }
             values { label: "dn1" set: "model { physics { drag_normal: 1 } }" } }
      axes { values { label: "all" set: "model { physics { contact_rule: ALL } }" }
             values { label: "" } }
      seeds: [1, 2]
    })"),
                                                         "");
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  EXPECT_EQ(Names(*runs),
            (std::vector<std::string>{
                "paper-dn0.1-all-seed1", "paper-dn0.1-all-seed2",
                "paper-dn0.1-seed1", "paper-dn0.1-seed2", "paper-dn1-all-seed1",
                "paper-dn1-all-seed2", "paper-dn1-seed1", "paper-dn1-seed2"}));
  const CampaignRun& run = (*runs)[5];  // paper-dn1-all-seed2
  EXPECT_EQ(run.settings.evolution.seed, 2u);
  EXPECT_EQ(run.settings.evolution.population, 30);
  EXPECT_EQ(run.settings.evolution.generations, 5);
  EXPECT_EQ(run.config.model().physics().drag_normal(), 1.0);
  EXPECT_EQ(run.config.model().physics().contact_rule(),
            v1::PhysicsConfig::ALL);
  EXPECT_FALSE((*runs)[6].config.model().physics().has_contact_rule());
}

TEST(CampaignFileTest, LaterFieldsOverrideEarlierOnesAndTheFileComesFirst) {
  const std::string dir =
      ::testing::TempDir() + "/campaign-file-" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  ASSERT_TRUE(WriteFile(dir + "/base.txtpb",
                        "evolution { seed: 7 population: 40 elite: 3 }\n")
                  .ok());
  ASSERT_TRUE(WriteFile(dir + "/c.txtpb", R"(
    runs { name: "a" config: "base.txtpb" set: "evolution { population: 50 }"
           axes { values { label: "x" set: "evolution { population: 60 }" } } }
    runs { name: "b" config: "base.txtpb" })")
                  .ok());
  Result<std::vector<CampaignRun>> runs = ReadCampaignFile(dir + "/c.txtpb");
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  ASSERT_EQ(Names(*runs), (std::vector<std::string>{"a-x", "b"}));
  EXPECT_EQ((*runs)[0].settings.evolution.population, 60);
  EXPECT_EQ((*runs)[0].settings.evolution.elite, 3);
  EXPECT_EQ((*runs)[0].settings.evolution.seed, 7u);  // No seeds: the file's.
  EXPECT_EQ((*runs)[1].settings.evolution.population, 40);
}

TEST(CampaignFileTest, TheExampleCampaignExpandsAsDocumented) {
  Result<std::vector<CampaignRun>> runs = ReadCampaignFile(
      std::string(ANIMAT_SOURCE_DIR) + "/configs/campaigns/tournament.txtpb");
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  ASSERT_EQ(runs->size(), 12u);
  EXPECT_EQ(runs->front().name, "paper-t3-seed1");
  EXPECT_EQ(runs->back().name, "paper-t5-seed6");
  EXPECT_EQ(runs->back().settings.evolution.tournament_size, 5);
  EXPECT_EQ(runs->back().settings.evolution.population, 300);  // The paper's.
  EXPECT_EQ(runs->back().config.model().physics().drag_normal(), 0.1);
}

// The energy and guidance campaign names its runs as scripts/seeded_runs.sh
// did, each with its configuration file's fields.
TEST(CampaignFileTest, TheEnergyAndGuidanceCampaignHasTheirRuns) {
  Result<std::vector<CampaignRun>> runs =
      ReadCampaignFile(std::string(ANIMAT_SOURCE_DIR) +
                       "/configs/campaigns/energy-guidance.txtpb");
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  std::vector<std::string> names;
  for (const CampaignRun& run : *runs) names.push_back(run.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{
                "energy-dn1-seed1", "energy-dn1-seed2", "energy-dn1-seed3",
                "guidance-seed1", "guidance-seed2", "guidance-seed3",
                "energy-holding-dn1-seed1", "energy-holding-dn1-seed2",
                "energy-holding-dn1-seed3", "guidance-lead-seed1",
                "guidance-lead-seed2", "guidance-lead-seed3"}));
  const v1::RunConfig& energy = runs->at(1).config;
  EXPECT_EQ(energy.model().evaluation().fitness(),
            v1::EvaluationConfig::DISTANCE_WITHIN_ENERGY_BUDGET);
  EXPECT_EQ(energy.model().physics().drag_normal(), 1.0);
  EXPECT_EQ(energy.evolution().seed(), 2u);
  EXPECT_EQ(energy.evolution().generations(), 150);
  const v1::RunConfig& guidance = runs->at(5).config;
  EXPECT_TRUE(guidance.model().guidance().enabled());
  EXPECT_EQ(guidance.evolution().seed(), 3u);
  EXPECT_EQ(guidance.evolution().generations(), 100);
  EXPECT_EQ(guidance.model().guidance().lead_steps(), 0);
  // The third edition's arms: holding charged, the chemical on early.
  const v1::RunConfig& holding = runs->at(7).config;
  EXPECT_EQ(holding.model().evaluation().holding_cost(), 0.05);
  EXPECT_EQ(holding.model().physics().contact_rule(), v1::PhysicsConfig::NONE);
  EXPECT_EQ(holding.evolution().seed(), 2u);
  const v1::RunConfig& lead = runs->at(11).config;
  EXPECT_EQ(lead.model().guidance().lead_steps(), 200);
  EXPECT_EQ(lead.evolution().seed(), 3u);
  EXPECT_EQ(lead.evolution().generations(), 100);
}

// The replication's campaign names its runs as scripts/replicate.sh did,
// with the same fields.
TEST(CampaignFileTest, TheReplicationCampaignHasTheReplicationsRuns) {
  Result<std::vector<CampaignRun>> runs =
      ReadCampaignFile(std::string(ANIMAT_SOURCE_DIR) +
                       "/configs/campaigns/replication-v3.txtpb");
  ASSERT_TRUE(runs.ok()) << runs.status().ToString();
  ASSERT_EQ(runs->size(), 30u);
  std::map<std::string, const CampaignRun*> by_name;
  for (const CampaignRun& run : *runs) by_name[run.name] = &run;
  for (const char* name :
       {"dn0.1-seed1", "dn1-seed6", "dn10-seed3", "all-dn0.1-seed4",
        "kl1-dn0.1-seed1", "dn0.01-seed4"}) {
    EXPECT_EQ(by_name.count(name), 1u) << name;
  }
  const v1::RunConfig& dn10 = by_name.at("dn10-seed3")->config;
  EXPECT_EQ(dn10.model().physics().drag_normal(), 10.0);
  EXPECT_EQ(dn10.model().physics().drag_tangential(), 0.05);
  EXPECT_EQ(dn10.evolution().seed(), 3u);
  EXPECT_EQ(dn10.evolution().generations(), 150);
  const v1::RunConfig& all = by_name.at("all-dn0.1-seed2")->config;
  EXPECT_EQ(all.model().physics().contact_rule(), v1::PhysicsConfig::ALL);
  EXPECT_EQ(all.model().physics().drag_normal(), 0.1);
  EXPECT_EQ(
      by_name.at("kl1-dn0.1-seed1")->config.model().signals().kernel_length(),
      1.0);
  EXPECT_EQ(by_name.at("dn0.01-seed1")->config.model().physics().drag_normal(),
            0.01);
  // The main runs were extended by raising their generations; the arms
  // say it in the file.
  EXPECT_EQ(dn10.evolution().extend_to(), 0);
  for (const char* arm :
       {"all-dn0.1-seed1", "kl1-dn0.1-seed4", "dn0.01-seed2"}) {
    EXPECT_EQ(by_name.at(arm)->config.evolution().generations(), 150) << arm;
    EXPECT_EQ(by_name.at(arm)->config.evolution().extend_to(), 250) << arm;
  }
}

TEST(CampaignFileTest, MistakesAreRefusedNamingTheEntry) {
  EXPECT_EQ(ErrorOf(""), "the campaign has no runs (runs { ... })");
  EXPECT_EQ(ErrorOf(R"(runs { name: "a" seeds: [1, 1] })"),
            "two runs are named a-seed1; each run needs its own name (store)");
  EXPECT_NE(ErrorOf(R"(runs { name: "../up" })").find("runs[0].name: "),
            std::string::npos);
  EXPECT_NE(
      ErrorOf(
          R"(runs { name: "a" } runs { name: "b" set: "evolution { populaton: 3 }" })")
          .find("runs[1].set: "),
      std::string::npos);
  EXPECT_NE(ErrorOf(R"(runs { name: "a" axes { } })")
                .find("runs[0].axes[0]: an axis needs values"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"(runs { name: "a" axes { values { label: "a b" } } })")
                .find("runs[0].axes[0].values[0].label: "),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"(runs { name: "a" set: "evolution { population: -5 }" })")
                .find("runs[0] (run a): "),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"(runs { config: "no-such-file.txtpb" name: "a" })")
                .find("runs[0].config: "),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"(runs { })").find("runs[0]: its runs have no name"),
            std::string::npos);
  EXPECT_NE(ErrorOf(R"(runs { name: "big" seeds: [)" +
                    [] {
                      std::string seeds;
                      for (int s = 1; s <= 1001; ++s) {
                        if (s > 1) seeds += ',';
                        seeds += std::to_string(s);
                      }
                      return seeds;
                    }() +
                    "] }")
                .find("more than 1000 runs"),
            std::string::npos);
}

}  // namespace
}  // namespace animat
