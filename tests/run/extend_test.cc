// A run still improving at `generations` goes on to `extend_to`
// (evolution.extend_to, extend_window): the decision is read from the
// store's statistics, so a run stopped and resumed during its extension
// makes the same lineage as one never stopped; and a run not improving
// ends at `generations`. Served by genome_scoring.h's stand-in workers.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "master/evolution/evolution_params.h"
#include "master/lineage/queries.h"
#include "master/lineage/store.h"
#include "master/run/evolution_run.h"
#include "tests/lineage/lineage_test_util.h"
#include "tests/run/genome_scoring.h"

namespace animat {
namespace {

using ::animat::testing::GenomeScoring;
using ::animat::testing::MemoryStore;
using ::animat::testing::Rows;
using Table = std::vector<std::vector<std::string>>;

RunSettings Extending(uint64_t seed, int window) {
  RunSettings settings;
  settings.evolution.seed = seed;
  settings.evolution.population = 12;
  settings.evolution.generations = 6;
  settings.evolution.elite = 1;
  settings.evolution.extend_to = 9;
  settings.evolution.extend_window = window;
  return settings;
}

// Runs `settings` in `store` to its end, or until `stop_after` generations
// are complete (resuming the run already in the store when `resume`).
// Returns the generations the run has completed.
int RunIn(lineage::Store* store, const RunSettings& settings, bool resume,
          std::optional<int> stop_after = std::nullopt) {
  Result<std::unique_ptr<EvolutionRun>> run =
      resume ? EvolutionRun::Resume(store, settings, /*force=*/false,
                                    std::nullopt, [](std::string_view) {})
             : EvolutionRun::Start(store, settings, [](std::string_view) {});
  EXPECT_TRUE(run.ok()) << run.status().ToString();
  if (!run.ok()) return -1;
  GenomeScoring scoring(/*follow_genome=*/true);
  std::atomic<bool> stop{false};
  const Status status =
      (*run)->Run(&scoring, stop, [&](const GenerationReport& report) {
        if (stop_after && report.generation + 1 >= *stop_after) stop = true;
      });
  EXPECT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ((*run)->finished(), !stop_after.has_value());
  Result<std::vector<lineage::CompletedGeneration>> done =
      lineage::CompletedGenerations(*store, (*run)->run_id());
  EXPECT_TRUE(done.ok()) << done.status().ToString();
  return done.ok() ? static_cast<int>(done->size()) : -1;
}

// What the store's statistics say the run should make.
int ExpectedLength(lineage::Store& store, const RunSettings& settings) {
  const EvolutionParams& p = settings.evolution;
  const auto best = [&store](int generation) -> std::optional<double> {
    const Table row =
        Rows(store,
             "SELECT best_fitness FROM generation_statistics WHERE"
             " generation = " +
                 std::to_string(generation));
    if (row.size() != 1 || row[0][0] == "NULL") return std::nullopt;
    return std::stod(row[0][0]);
  };
  return EvolutionLength(p, best(p.generations - 1),
                         best(p.generations - 1 - p.extend_window));
}

TEST(ExtendTest, ARunGoesOnOnlyWhileImprovingAndResumesTheSame) {
  // Seeds and windows under which the stand-in runs do and do not improve
  // in their last generations; both must occur for the test to say much.
  int extended = 0, ended = 0;
  for (uint64_t seed : {1, 2, 3, 4}) {
    for (int window : {1, 3}) {
      const RunSettings settings = Extending(seed, window);
      std::unique_ptr<lineage::Store> whole = MemoryStore();
      const int made = RunIn(whole.get(), settings, /*resume=*/false);
      const int expected = ExpectedLength(*whole, settings);
      EXPECT_EQ(made, expected) << "seed " << seed << ", window " << window;
      (expected == 9 ? extended : ended) += 1;
      if (expected != 9) continue;

      // Stopped within the extension, then resumed: the same lineage.
      std::unique_ptr<lineage::Store> parts = MemoryStore();
      EXPECT_EQ(RunIn(parts.get(), settings, false, /*stop_after=*/7), 7);
      EXPECT_EQ(RunIn(parts.get(), settings, /*resume=*/true), 9);
      for (const char* query :
           {"SELECT id, generation, operators, genome_hash, status, fitness,"
            " reused_from FROM individuals WHERE generation > 0 ORDER BY id",
            "SELECT generation, id, rank FROM members ORDER BY 1, 2",
            "SELECT generation, best_id, best_fitness, mean_fitness FROM"
            " generation_statistics ORDER BY generation"}) {
        EXPECT_EQ(Rows(*parts, query), Rows(*whole, query)) << query;
      }
    }
  }
  EXPECT_GT(extended, 0);
  EXPECT_GT(ended, 0);
}

// A finished run resumed with more generations than its extend_to runs to
// them, and its recorded configuration still reads back.
TEST(ExtendTest, ResumedWithMoreGenerationsTheRunGoesOnToThem) {
  const RunSettings settings = Extending(1, 1);
  std::unique_ptr<lineage::Store> store = MemoryStore();
  RunIn(store.get(), settings, /*resume=*/false);
  for (int round = 0; round < 2; ++round) {
    Result<std::unique_ptr<EvolutionRun>> run =
        EvolutionRun::Resume(store.get(), std::nullopt, /*force=*/false,
                             11 + round, [](std::string_view) {});
    ASSERT_TRUE(run.ok()) << run.status().ToString();
    GenomeScoring scoring(/*follow_genome=*/true);
    std::atomic<bool> stop{false};
    ASSERT_TRUE((*run)->Run(&scoring, stop).ok());
    EXPECT_TRUE((*run)->finished());
    Result<std::vector<lineage::CompletedGeneration>> done =
        lineage::CompletedGenerations(*store, (*run)->run_id());
    ASSERT_TRUE(done.ok()) << done.status().ToString();
    EXPECT_EQ(done->size(), 11u + round);
  }
}

TEST(ExtendTest, LengthIsGenerationsUnlessStillImproving) {
  EvolutionParams p;
  p.generations = 150;
  EXPECT_FALSE(EvolutionExtends(p));
  EXPECT_EQ(EvolutionLength(p, 2.0, 1.0), 150);  // extend_to 0: never.
  EXPECT_EQ(EvolutionMaxLength(p), 150);
  p.extend_to = 100;  // Not beyond: extends nothing.
  EXPECT_EQ(EvolutionMaxLength(p), 150);
  p.extend_to = 250;
  EXPECT_TRUE(EvolutionExtends(p));
  EXPECT_EQ(EvolutionMaxLength(p), 250);
  EXPECT_EQ(EvolutionLength(p, 2.0, 1.0), 250);
  EXPECT_EQ(EvolutionLength(p, 1.0, 1.0), 150);           // The same best: not.
  EXPECT_EQ(EvolutionLength(p, 1.0, std::nullopt), 250);  // None before.
  EXPECT_EQ(EvolutionLength(p, std::nullopt, std::nullopt), 150);
  EXPECT_EQ(EvolutionLength(p, -1.0, -2.0), 250);  // Guidance scores.
}

TEST(ExtendTest, AnExtensionLooksBackWithinTheRunsGenerations) {
  v1::EvolutionConfig message;
  message.set_generations(150);
  message.set_extend_to(250);
  message.set_extend_window(150);
  EvolutionParams p;
  const Status status = EvolutionParamsFromProto(message, &p);
  EXPECT_FALSE(status.ok());
  EXPECT_NE(status.message().find("evolution.extend_window"), std::string::npos)
      << status.message();
  // Up to `generations`, extend_to extends nothing, and is kept (a run
  // resumed with more generations than its extend_to reads back).
  message.set_extend_to(150);
  ASSERT_TRUE(EvolutionParamsFromProto(message, &p).ok());
  EXPECT_FALSE(EvolutionExtends(p));
  EXPECT_EQ(EvolutionLength(p, 2.0, 1.0), 150);
  message.set_extend_to(250);
  message.set_extend_window(20);
  ASSERT_TRUE(EvolutionParamsFromProto(message, &p).ok());
  EXPECT_EQ(p.extend_to, 250);
  EXPECT_EQ(p.extend_window, 20);
  // Round trip.
  EvolutionParams back;
  ASSERT_TRUE(EvolutionParamsFromProto(EvolutionParamsToProto(p), &back).ok());
  EXPECT_EQ(back.extend_to, 250);
  EXPECT_EQ(back.extend_window, 20);
}

}  // namespace
}  // namespace animat
