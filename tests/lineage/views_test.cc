// The lineage store's SQL views (best, ancestry, line_of_descent,
// generation_statistics) and queries (master/lineage/queries.h), on small
// pedigrees made by hand.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "master/lineage/queries.h"
#include "master/lineage/store.h"
#include "tests/lineage/lineage_test_util.h"

namespace animat::lineage {
namespace {

using ::animat::testing::FailedEvaluation;
using ::animat::testing::MakeIndividual;
using ::animat::testing::MakeRun;
using ::animat::testing::MemoryStore;
using ::animat::testing::OkEvaluation;
using ::animat::testing::Rows;

using Table = std::vector<std::vector<std::string>>;

// The diamond A, B -> C; A -> D; C, D -> E, and F made from E and A (so A
// is F's parent and also its great-grandparent): ids A=1 ... F=6.
constexpr uint64_t kA = 1, kB = 2, kC = 3, kD = 4, kE = 5, kF = 6;

class ViewsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = MemoryStore();
    ASSERT_NE(store_, nullptr);
    run_ = MakeRun(*store_);
    ASSERT_TRUE(store_
                    ->AddIndividuals(
                        run_, {MakeIndividual(kA, 0), MakeIndividual(kB, 0),
                               MakeIndividual(kC, 1, {kA, kB}, {"crossover"}),
                               MakeIndividual(kD, 1, {kA}, {"sign"}),
                               MakeIndividual(kE, 2, {kC, kD},
                                              {"crossover", "coordinate"}),
                               MakeIndividual(kF, 3, {kE, kA}, {"crossover"})})
                    .ok());
    ASSERT_TRUE(store_
                    ->RecordEvaluations(
                        run_, {OkEvaluation(kA, 1.0), OkEvaluation(kB, 2.0),
                               OkEvaluation(kC, 3.0), OkEvaluation(kD, 2.5),
                               OkEvaluation(kE, 5.0), FailedEvaluation(kF)})
                    .ok());
  }

  std::string Run() const { return std::to_string(run_); }

  std::unique_ptr<Store> store_;
  int64_t run_ = 0;
};

TEST_F(ViewsTest, AncestryGivesEachAncestorOnceAtItsShortestDistance) {
  const Table rows = Rows(*store_,
                          "SELECT descendant, ancestor, distance FROM ancestry"
                          " WHERE run_id = " +
                              Run() + " ORDER BY descendant, ancestor");
  EXPECT_EQ(rows, (Table{{"3", "1", "1"},
                         {"3", "2", "1"},
                         {"4", "1", "1"},
                         {"5", "1", "2"},
                         {"5", "2", "2"},
                         {"5", "3", "1"},
                         {"5", "4", "1"},
                         {"6", "1", "1"},
                         {"6", "2", "3"},
                         {"6", "3", "2"},
                         {"6", "4", "2"},
                         {"6", "5", "1"}}));
}

TEST_F(ViewsTest, BestIsTheHighestFitness) {
  EXPECT_EQ(Rows(*store_, "SELECT run_id, id, generation, fitness FROM best"),
            (Table{{Run(), "5", "2", "5.0"}}));
}

TEST_F(ViewsTest, BestBreaksTiesByLowestIdAndIsPerRun) {
  // Another run where 8 and 7 tie (8 is written and evaluated first).
  const int64_t other = MakeRun(*store_, 8);
  ASSERT_TRUE(
      store_
          ->AddIndividuals(other, {MakeIndividual(8, 0), MakeIndividual(7, 0),
                                   MakeIndividual(9, 0)})
          .ok());
  ASSERT_TRUE(store_
                  ->RecordEvaluations(
                      other, {OkEvaluation(8, 0.5), OkEvaluation(7, 0.5),
                              OkEvaluation(9, 0.25)})
                  .ok());
  EXPECT_EQ(Rows(*store_, "SELECT run_id, id FROM best ORDER BY run_id"),
            (Table{{Run(), "5"}, {std::to_string(other), "7"}}));
  Result<Summary> best = Best(*store_, other);
  ASSERT_TRUE(best.ok()) << best.status().ToString();
  EXPECT_EQ(best->id, 7u);
}

TEST_F(ViewsTest, BestIgnoresFailedAndPendingIndividuals) {
  // A new individual, not yet evaluated, and one that failed.
  ASSERT_TRUE(store_
                  ->AddIndividuals(run_, {MakeIndividual(20, 4, {kE}),
                                          MakeIndividual(21, 4, {kE})})
                  .ok());
  ASSERT_TRUE(store_
                  ->RecordEvaluations(
                      run_, {FailedEvaluation(
                                21, v1::EvaluationResult::NUMERICAL_FAILURE)})
                  .ok());
  EXPECT_EQ(Rows(*store_, "SELECT id FROM best"), (Table{{"5"}}));
}

TEST_F(ViewsTest, LineOfDescentFollowsFirstParentsFromTheBest) {
  EXPECT_EQ(Rows(*store_,
                 "SELECT run_id, step, id, generation, operators, fitness"
                 " FROM line_of_descent ORDER BY run_id, step"),
            (Table{{Run(), "0", "5", "2", "crossover,coordinate", "5.0"},
                   {Run(), "1", "3", "1", "crossover", "3.0"},
                   {Run(), "2", "1", "0", "random", "1.0"}}));
}

TEST_F(ViewsTest, GenerationStatisticsShowsEachGeneration) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {kA, kB}).ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 1, {kB, kC, kD}).ok());
  GenerationStats stats;
  stats.evaluated = 2;
  stats.best_id = kB;
  stats.best = 2.0;
  stats.mean = 1.5;
  stats.median = 1.5;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 0, {kB, kA}, stats).ok());
  EXPECT_EQ(
      Rows(*store_,
           "SELECT generation, size, evaluated, failed, best_id,"
           " best_fitness, mean_fitness, median_fitness,"
           " completed_at IS NOT NULL FROM generation_statistics"
           " ORDER BY generation"),
      (Table{{"0", "2", "2", "0", "2", "2.0", "1.5", "1.5", "1"},
             {"1", "3", "NULL", "NULL", "NULL", "NULL", "NULL", "NULL", "0"}}));
}

TEST_F(ViewsTest, CompletedGenerationsGivesTheRecordedStatisticsInOrder) {
  Result<std::vector<CompletedGeneration>> none =
      CompletedGenerations(*store_, run_);
  ASSERT_TRUE(none.ok()) << none.status().ToString();
  EXPECT_TRUE(none->empty());
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {kA, kB}).ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 1, {kB, kC, kD}).ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 2, {kC, kE, kF}).ok());
  GenerationStats first;
  first.evaluated = 2;
  first.best_id = kB;
  first.best = 2.0;
  first.mean = 1.5;
  first.median = 1.5;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 0, {kB, kA}, first).ok());
  GenerationStats third;  // No fitness at all: the optionals stay empty.
  third.failed = 3;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 2, {kC, kE, kF}, third).ok());
  // Generation 1 is not complete and is left out.
  Result<std::vector<CompletedGeneration>> done =
      CompletedGenerations(*store_, run_);
  ASSERT_TRUE(done.ok()) << done.status().ToString();
  ASSERT_EQ(done->size(), 2u);
  EXPECT_EQ((*done)[0].generation, 0);
  EXPECT_EQ((*done)[0].stats.evaluated, 2);
  EXPECT_EQ((*done)[0].stats.failed, 0);
  EXPECT_EQ((*done)[0].stats.best_id, std::optional<uint64_t>(kB));
  EXPECT_EQ((*done)[0].stats.best, std::optional<double>(2.0));
  EXPECT_EQ((*done)[0].stats.mean, std::optional<double>(1.5));
  EXPECT_EQ((*done)[0].stats.median, std::optional<double>(1.5));
  EXPECT_EQ((*done)[1].generation, 2);
  EXPECT_EQ((*done)[1].stats.evaluated, 0);
  EXPECT_EQ((*done)[1].stats.failed, 3);
  EXPECT_FALSE((*done)[1].stats.best_id);
  EXPECT_FALSE((*done)[1].stats.best);
  EXPECT_FALSE((*done)[1].stats.mean);
  EXPECT_FALSE((*done)[1].stats.median);
}

TEST_F(ViewsTest, ScoresGivesEveryIndividualInIdOrder) {
  ASSERT_TRUE(store_->AddIndividuals(run_, {MakeIndividual(7, 3)}).ok());
  Result<std::vector<Score>> scores = Scores(*store_, run_);
  ASSERT_TRUE(scores.ok()) << scores.status().ToString();
  ASSERT_EQ(scores->size(), 7u);
  const std::vector<std::optional<double>> fitness = {
      1.0, 2.0, 3.0, 2.5, 5.0, std::nullopt, std::nullopt};
  for (size_t i = 0; i < scores->size(); ++i) {
    EXPECT_EQ((*scores)[i].id, i + 1);
    EXPECT_EQ((*scores)[i].evaluated, i + 1 != 7) << "id " << i + 1;
    EXPECT_EQ((*scores)[i].fitness, fitness[i]) << "id " << i + 1;
  }
  const int64_t other = MakeRun(*store_);
  Result<std::vector<Score>> empty = Scores(*store_, other);
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty->empty());
}

TEST_F(ViewsTest, CountRunCountsWhatTheRunHolds) {
  // Generation 0 of A and B, complete; generation 1 of B, C and a new,
  // unevaluated individual G without parents.
  constexpr uint64_t kG = 7;
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {kA, kB}).ok());
  GenerationStats stats;
  stats.evaluated = 2;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 0, {kB, kA}, stats).ok());
  ASSERT_TRUE(
      store_->AddGeneration(run_, 1, {kB, kC, kG}, {MakeIndividual(kG, 1)})
          .ok());
  Result<RunCounts> n = CountRun(*store_, run_);
  ASSERT_TRUE(n.ok()) << n.status().ToString();
  EXPECT_FALSE(n->finished);
  EXPECT_EQ(n->individuals, 7);
  EXPECT_EQ(n->evaluated, 6);
  EXPECT_EQ(n->ok, 5);  // F failed.
  EXPECT_EQ(n->with_fitness, 5);
  EXPECT_EQ(n->with_worker, 6);
  EXPECT_EQ(n->with_evaluation_time, 6);
  EXPECT_EQ(n->with_genome, 7);
  EXPECT_EQ(n->offspring, 5);                  // C, D, E, F and G.
  EXPECT_EQ(n->offspring_without_parents, 1);  // G.
  EXPECT_EQ(n->needed_unevaluated, 1);         // G.
  EXPECT_EQ(n->generations, 2);
  EXPECT_EQ(n->complete_generations, 1);
  EXPECT_EQ(n->generations_evaluated, 2);
  EXPECT_EQ(n->members, 5);
  EXPECT_EQ(n->ranked_members, 2);

  ASSERT_TRUE(store_->FinishRun(run_).ok());
  n = CountRun(*store_, run_);
  ASSERT_TRUE(n.ok());
  EXPECT_TRUE(n->finished);

  // Another run's rows are not counted.
  const int64_t other = MakeRun(*store_);
  Result<RunCounts> none = CountRun(*store_, other);
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->finished);
  EXPECT_EQ(none->individuals, 0);
  EXPECT_EQ(none->generations, 0);
  EXPECT_EQ(none->members, 0);
}

TEST_F(ViewsTest, BestQuery) {
  Result<Summary> best = Best(*store_, run_);
  ASSERT_TRUE(best.ok()) << best.status().ToString();
  EXPECT_EQ(best->id, kE);
  EXPECT_EQ(best->generation, 2);
  EXPECT_EQ(best->operators, "crossover,coordinate");
  EXPECT_EQ(best->status, "ok");
  EXPECT_EQ(best->fitness, 5.0);
  EXPECT_FALSE(best->body.has_value());  // Its result had none.
}

TEST_F(ViewsTest, BestQueryGivesTheBodyRecorded) {
  const int64_t other = MakeRun(*store_, 8);
  ASSERT_TRUE(
      store_
          ->AddIndividuals(other, {MakeIndividual(0, 0), MakeIndividual(1, 0)})
          .ok());
  Evaluation best_one = OkEvaluation(1, 4.0);
  *best_one.result.mutable_body() = ::animat::testing::MakeBody(9);
  ASSERT_TRUE(
      store_->RecordEvaluations(other, {OkEvaluation(0, 1.0), best_one}).ok());
  Result<Summary> best = Best(*store_, other);
  ASSERT_TRUE(best.ok()) << best.status().ToString();
  EXPECT_EQ(best->id, 1u);
  ASSERT_TRUE(best->body.has_value());
  EXPECT_EQ(best->body->cells(), 32);  // The evaluation's cells.
  EXPECT_EQ(best->body->springs(), 69);
  EXPECT_EQ(best->body->chambers(), 9);
  EXPECT_EQ(best->body->skin_edges(), 11);
  EXPECT_EQ(best->body->spread_major(), 2.0 + 1.0 / 3.0);
  EXPECT_EQ(best->body->spread_minor(), 0.1 * 9);
}

TEST_F(ViewsTest, BestQueryWithoutAnyFitnessIsNotFound) {
  const int64_t other = MakeRun(*store_, 8);
  ASSERT_TRUE(
      store_
          ->AddIndividuals(other, {MakeIndividual(0, 0), MakeIndividual(1, 0)})
          .ok());
  ASSERT_TRUE(store_->RecordEvaluations(other, {FailedEvaluation(0)}).ok());
  Result<Summary> best = Best(*store_, other);
  ASSERT_FALSE(best.ok());
  EXPECT_EQ(best.status().code(), StatusCode::kNotFound);
}

TEST_F(ViewsTest, AncestorsNearestFirstThenById) {
  Result<std::vector<Summary>> ancestors = Ancestors(*store_, run_, kF);
  ASSERT_TRUE(ancestors.ok()) << ancestors.status().ToString();
  std::vector<std::pair<int, uint64_t>> got;
  for (const Summary& s : *ancestors) got.push_back({s.distance, s.id});
  EXPECT_EQ(got, (std::vector<std::pair<int, uint64_t>>{
                     {1, kA}, {1, kE}, {2, kC}, {2, kD}, {3, kB}}));
  const Summary& c = (*ancestors)[2];
  EXPECT_EQ(c.generation, 1);
  EXPECT_EQ(c.operators, "crossover");
  EXPECT_EQ(c.status, "ok");
  EXPECT_EQ(c.fitness, 3.0);
}

TEST_F(ViewsTest, AncestorsOfTheDiamondsTip) {
  Result<std::vector<Summary>> ancestors = Ancestors(*store_, run_, kE);
  ASSERT_TRUE(ancestors.ok());
  std::vector<std::pair<int, uint64_t>> got;
  for (const Summary& s : *ancestors) got.push_back({s.distance, s.id});
  EXPECT_EQ(got, (std::vector<std::pair<int, uint64_t>>{
                     {1, kC}, {1, kD}, {2, kA}, {2, kB}}));
}

TEST_F(ViewsTest, AncestorsOfARootAreNone) {
  Result<std::vector<Summary>> ancestors = Ancestors(*store_, run_, kA);
  ASSERT_TRUE(ancestors.ok());
  EXPECT_TRUE(ancestors->empty());
}

TEST_F(ViewsTest, AncestorsOfAnUnknownIdIsNotFound) {
  Result<std::vector<Summary>> ancestors = Ancestors(*store_, run_, 99);
  ASSERT_FALSE(ancestors.ok());
  EXPECT_EQ(ancestors.status().code(), StatusCode::kNotFound);
  // And in another run, even with the same ids.
  const int64_t other = MakeRun(*store_, 8);
  ancestors = Ancestors(*store_, other, kF);
  ASSERT_FALSE(ancestors.ok());
  EXPECT_EQ(ancestors.status().code(), StatusCode::kNotFound);
}

TEST_F(ViewsTest, AncestorsOfAPendingIndividual) {
  ASSERT_TRUE(store_->AddIndividuals(run_, {MakeIndividual(30, 4, {kD})}).ok());
  Result<std::vector<Summary>> ancestors = Ancestors(*store_, run_, 30);
  ASSERT_TRUE(ancestors.ok());
  ASSERT_EQ(ancestors->size(), 2u);
  EXPECT_EQ((*ancestors)[0].id, kD);
  EXPECT_EQ((*ancestors)[1].id, kA);
  EXPECT_EQ((*ancestors)[1].distance, 2);
}

TEST_F(ViewsTest, ChooseRunDefaultsToTheLatest) {
  Result<int64_t> chosen = ChooseRun(*store_, std::nullopt);
  ASSERT_TRUE(chosen.ok());
  EXPECT_EQ(*chosen, run_);
  const int64_t other = MakeRun(*store_, 8);
  chosen = ChooseRun(*store_, std::nullopt);
  ASSERT_TRUE(chosen.ok());
  EXPECT_EQ(*chosen, other);
  chosen = ChooseRun(*store_, run_);
  ASSERT_TRUE(chosen.ok());
  EXPECT_EQ(*chosen, run_);
  chosen = ChooseRun(*store_, other + 5);
  ASSERT_FALSE(chosen.ok());
  EXPECT_EQ(chosen.status().code(), StatusCode::kNotFound);

  std::unique_ptr<Store> empty = MemoryStore();
  ASSERT_NE(empty, nullptr);
  chosen = ChooseRun(*empty, std::nullopt);
  ASSERT_FALSE(chosen.ok());
  EXPECT_EQ(chosen.status().code(), StatusCode::kNotFound);
}

// Splits RFC 4180 CSV (quoted fields may hold commas and doubled quotes)
// into rows of fields; fails the test on malformed input.
Table ParseCsv(const std::string& text) {
  Table rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false;
  bool field_started = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      EXPECT_TRUE(field.empty()) << "quote inside a field at " << i;
      quoted = true;
      field_started = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
      field_started = false;
    } else if (c == '\n') {
      row.push_back(field);
      rows.push_back(row);
      row.clear();
      field.clear();
      field_started = false;
    } else {
      field += c;
      field_started = true;
    }
  }
  EXPECT_FALSE(quoted) << "unterminated quote";
  EXPECT_TRUE(field.empty() && !field_started && row.empty())
      << "the last line has no newline";
  return rows;
}

TEST(ExportAlifeTest, WritesTheStandardPhylogenyCsv) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  const int64_t run = MakeRun(*store);
  ASSERT_TRUE(store
                  ->AddIndividuals(
                      run, {MakeIndividual(5, 0), MakeIndividual(0, 0),
                            MakeIndividual(3, 0), MakeIndividual(1, 0),
                            MakeIndividual(7, 1, {3, 5}, {"crossover", "sign"}),
                            MakeIndividual(8, 1, {5, 3}, {"crossover"}),
                            MakeIndividual(9, 2, {7}, {"coordinate"})})
                  .ok());
  ASSERT_TRUE(
      store
          ->RecordEvaluations(run, {OkEvaluation(0, 0.1), FailedEvaluation(1),
                                    OkEvaluation(3, 2.0), OkEvaluation(5, 1.25),
                                    OkEvaluation(7, 4.5), OkEvaluation(8, 0.0)})
          .ok());
  // Another run's individuals stay out.
  const int64_t other = MakeRun(*store, 8);
  ASSERT_TRUE(store->AddIndividuals(other, {MakeIndividual(4, 0)}).ok());

  std::ostringstream out;
  const Status status = ExportAlife(*store, run, out);
  ASSERT_TRUE(status.ok()) << status.ToString();
  EXPECT_EQ(out.str(),
            "id,ancestor_list,origin_time,fitness,status,operators\n"
            "0,\"[NONE]\",0,0.1,ok,\"random\"\n"
            "1,\"[NONE]\",0,,non_viable,\"random\"\n"
            "3,\"[NONE]\",0,2,ok,\"random\"\n"
            "5,\"[NONE]\",0,1.25,ok,\"random\"\n"
            "7,\"[3,5]\",1,4.5,ok,\"crossover,sign\"\n"
            "8,\"[5,3]\",1,0,ok,\"crossover\"\n"
            "9,\"[7]\",2,,,\"coordinate\"\n");

  const Table rows = ParseCsv(out.str());
  ASSERT_EQ(rows.size(), 8u);
  EXPECT_EQ(rows[0],
            (std::vector<std::string>{"id", "ancestor_list", "origin_time",
                                      "fitness", "status", "operators"}));
  for (const std::vector<std::string>& row : rows) EXPECT_EQ(row.size(), 6u);
  EXPECT_EQ(rows[5][1], "[3,5]");
  EXPECT_EQ(rows[5][5], "crossover,sign");
  EXPECT_EQ(rows[6][1], "[5,3]");
  EXPECT_EQ(std::strtod(rows[1][3].c_str(), nullptr), 0.1);  // Exact.
  uint64_t previous = 0;
  for (size_t r = 2; r < rows.size(); ++r) {
    const uint64_t id = std::strtoull(rows[r][0].c_str(), nullptr, 10);
    EXPECT_GT(id, previous);
    previous = id;
  }
}

TEST(ExportAlifeTest, EmptyRunGivesTheHeaderOnly) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  const int64_t run = MakeRun(*store);
  std::ostringstream out;
  ASSERT_TRUE(ExportAlife(*store, run, out).ok());
  EXPECT_EQ(out.str(),
            "id,ancestor_list,origin_time,fitness,status,operators\n");
}

TEST(TopDistinctPhenotypesTest,
     TheFittestOfEachStateHashInTheLastCompletedGeneration) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  const int64_t run = MakeRun(*store);
  EXPECT_EQ(TopDistinctPhenotypes(*store, run, 5).status().code(),
            StatusCode::kNotFound);
  std::vector<NewIndividual> made;
  for (uint64_t id = 1; id <= 9; ++id) {
    made.push_back(MakeIndividual(id, id <= 3 ? 0 : 1));
  }
  ASSERT_TRUE(store->AddIndividuals(run, made).ok());
  // Fitness 10 − id, except that 6 ties 5; hashes: 4, 5 and 7 alike; 8
  // failed.
  std::vector<Evaluation> results;
  for (uint64_t id = 1; id <= 9; ++id) {
    if (id == 8) {
      results.push_back(FailedEvaluation(id));
      continue;
    }
    Evaluation e = OkEvaluation(id, id == 6 ? 5.0 : 10.0 - id);
    if (id == 5 || id == 7)
      e.result.set_state_hash(OkEvaluation(4, 0).result.state_hash());
    results.push_back(e);
  }
  ASSERT_TRUE(store->RecordEvaluations(run, results).ok());
  ASSERT_TRUE(store->AddGeneration(run, 0, {1, 2, 3}).ok());
  ASSERT_TRUE(store->CompleteGeneration(run, 0, {1, 2, 3}, {}).ok());
  ASSERT_TRUE(store->AddGeneration(run, 1, {1, 4, 5, 6, 7, 8, 9}).ok());
  ASSERT_TRUE(
      store->CompleteGeneration(run, 1, {1, 4, 5, 6, 7, 9, 8}, {}).ok());
  // Generation 2 is begun, not completed: generation 1 is the last.
  ASSERT_TRUE(store->AddGeneration(run, 2, {1, 2}).ok());
  Result<std::vector<Phenotype>> top = TopDistinctPhenotypes(*store, run, 3);
  ASSERT_TRUE(top.ok()) << top.status().ToString();
  // By fitness: 1 (9), 4 (6), 5 (5, 4's hash), 6 (5), 7 (3, 4's hash), 9.
  ASSERT_EQ(top->size(), 3u);
  EXPECT_EQ((*top)[0].id, 1u);
  EXPECT_EQ((*top)[0].members, 1);
  EXPECT_EQ((*top)[0].generation, 1);
  EXPECT_EQ((*top)[1].id, 4u);
  EXPECT_EQ((*top)[1].members, 3);
  EXPECT_EQ((*top)[1].fitness, 6);
  EXPECT_EQ((*top)[2].id, 6u);
  EXPECT_EQ(
      (*top)[2].state_hash,
      Rows(*store, "SELECT state_hash FROM evaluations WHERE id = 6")[0][0]);
  Result<std::vector<Phenotype>> all = TopDistinctPhenotypes(*store, run, 100);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 4u);  // 1, 4, 6, 9.
  EXPECT_EQ(all->back().id, 9u);
}

}  // namespace
}  // namespace animat::lineage
