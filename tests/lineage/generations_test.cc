// Generations in the lineage store: AddGeneration, the same in parts
// (BeginGeneration, with evaluations reused for copies),
// CompleteGeneration, Generation, LatestGeneration.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "master/lineage/sqlite.h"
#include "master/lineage/store.h"
#include "tests/lineage/lineage_test_util.h"

namespace animat::lineage {
namespace {

using ::animat::testing::IsUtcStamp;
using ::animat::testing::MakeIndividual;
using ::animat::testing::MakeRun;
using ::animat::testing::MemoryStore;
using ::animat::testing::Rows;
using ::animat::testing::TempStorePath;
using ::animat::testing::Value;

using Table = std::vector<std::vector<std::string>>;

class GenerationsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = MemoryStore();
    ASSERT_NE(store_, nullptr);
    run_ = MakeRun(*store_);
    ASSERT_TRUE(
        store_
            ->AddIndividuals(run_, {MakeIndividual(0, 0), MakeIndividual(1, 0),
                                    MakeIndividual(2, 0), MakeIndividual(3, 0)})
            .ok());
  }

  std::unique_ptr<Store> store_;
  int64_t run_ = 0;
};

TEST_F(GenerationsTest, AddGenerationOfExistingIndividuals) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {3, 0, 2}).ok());
  Result<GenerationRow> g = store_->Generation(run_, 0);
  ASSERT_TRUE(g.ok()) << g.status().ToString();
  EXPECT_EQ(g->generation, 0);
  EXPECT_EQ(g->size, 3);
  EXPECT_FALSE(g->complete);
  EXPECT_EQ(g->members, (std::vector<uint64_t>{0, 2, 3}));  // By id.
  const Table row = Rows(*store_,
                         "SELECT size, created_at, completed_at, evaluated,"
                         " failed, best_id, best_fitness, mean_fitness,"
                         " median_fitness FROM generations");
  ASSERT_EQ(row.size(), 1u);
  EXPECT_EQ(row[0][0], "3");
  EXPECT_TRUE(IsUtcStamp(row[0][1])) << row[0][1];
  for (size_t c = 2; c < row[0].size(); ++c) {
    EXPECT_EQ(row[0][c], "NULL") << "column " << c;
  }
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM members WHERE rank IS NULL"),
            "3");
}

TEST_F(GenerationsTest, AddGenerationWithItsIndividuals) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
  ASSERT_TRUE(store_
                  ->AddGeneration(run_, 1, {0, 4, 5},
                                  {MakeIndividual(4, 1, {0, 1}, {"crossover"}),
                                   MakeIndividual(5, 1, {1}, {"sign"})})
                  .ok());
  Result<GenerationRow> g = store_->Generation(run_, 1);
  ASSERT_TRUE(g.ok());
  EXPECT_EQ(g->size, 3);
  EXPECT_EQ(g->members, (std::vector<uint64_t>{0, 4, 5}));
  Result<IndividualRow> child = store_->Individual(run_, 4);
  ASSERT_TRUE(child.ok()) << child.status().ToString();
  EXPECT_EQ(child->parents, (std::vector<uint64_t>{0, 1}));
  EXPECT_EQ(child->operators, "crossover");
  Result<std::vector<uint64_t>> pending = store_->Unevaluated(run_);
  ASSERT_TRUE(pending.ok());
  EXPECT_EQ(*pending, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5}));
}

TEST_F(GenerationsTest, AddGenerationIsAtomicWhenAnIndividualFails) {
  // Individual 2 exists already: the insert fails, and neither the
  // generation nor its members nor the other new individual appear.
  const Status status = store_->AddGeneration(
      run_, 0, {0, 6, 2},
      {MakeIndividual(6, 0, {0}), MakeIndividual(2, 0, {1})});
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM generations"), "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM members"), "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM individuals WHERE id = 6"),
            "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM parents"), "0");
  Result<std::optional<GenerationRow>> latest = store_->LatestGeneration(run_);
  ASSERT_TRUE(latest.ok());
  EXPECT_FALSE(latest->has_value());
}

TEST_F(GenerationsTest, AddGenerationIsAtomicWhenTheGenerationExists) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
  EXPECT_FALSE(
      store_->AddGeneration(run_, 0, {7}, {MakeIndividual(7, 0)}).ok());
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM individuals WHERE id = 7"),
            "0");
  Result<GenerationRow> g = store_->Generation(run_, 0);
  ASSERT_TRUE(g.ok());
  EXPECT_EQ(g->members, (std::vector<uint64_t>{0, 1}));
}

TEST_F(GenerationsTest, AGenerationWrittenInPartsIsTheGenerationAtOnce) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
  Result<std::unique_ptr<GenerationWrite>> write =
      store_->BeginGeneration(run_, 1, {0, 4, 5});
  ASSERT_TRUE(write.ok()) << write.status().ToString();
  ASSERT_TRUE(
      (*write)->Add({MakeIndividual(4, 1, {0, 1}, {"crossover"})}).ok());
  ASSERT_TRUE((*write)->Add({}).ok());
  ASSERT_TRUE((*write)->Add({MakeIndividual(5, 1, {1}, {"sign"})}).ok());
  ASSERT_TRUE((*write)->Commit().ok());
  EXPECT_FALSE((*write)->Commit().ok()) << "committed once only";
  write->reset();

  Result<GenerationRow> g = store_->Generation(run_, 1);
  ASSERT_TRUE(g.ok()) << g.status().ToString();
  EXPECT_EQ(g->members, (std::vector<uint64_t>{0, 4, 5}));
  Result<IndividualRow> child = store_->Individual(run_, 4);
  ASSERT_TRUE(child.ok()) << child.status().ToString();
  EXPECT_EQ(child->parents, (std::vector<uint64_t>{0, 1}));
  // One time stamp for the generation and its offspring.
  EXPECT_EQ(Value(*store_,
                  "SELECT COUNT(DISTINCT created_at) FROM (SELECT created_at"
                  " FROM births WHERE generation = 1 UNION ALL SELECT"
                  " created_at FROM generations WHERE generation = 1)"),
            "1");
}

TEST_F(GenerationsTest, AGenerationWriteNotCommittedLeavesNothing) {
  {
    Result<std::unique_ptr<GenerationWrite>> write =
        store_->BeginGeneration(run_, 0, {0, 6});
    ASSERT_TRUE(write.ok()) << write.status().ToString();
    ASSERT_TRUE((*write)->Add({MakeIndividual(6, 0, {0})}).ok());
  }
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM generations"), "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM individuals WHERE id = 6"),
            "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM parents"), "0");
  // The store goes on as before.
  EXPECT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
}

TEST_F(GenerationsTest, AFailedPartUndoesTheWholeGenerationWrite) {
  Result<std::unique_ptr<GenerationWrite>> write =
      store_->BeginGeneration(run_, 0, {0, 6, 2});
  ASSERT_TRUE(write.ok()) << write.status().ToString();
  ASSERT_TRUE((*write)->Add({MakeIndividual(6, 0, {0})}).ok());
  // Individual 2 exists already.
  const Status failed = (*write)->Add({MakeIndividual(2, 0, {1})});
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ((*write)->Add({MakeIndividual(7, 0)}).ToString(),
            failed.ToString());
  EXPECT_EQ((*write)->Commit().ToString(), failed.ToString());
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM generations"), "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM individuals WHERE id >= 6"),
            "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM parents"), "0");
}

// Reuse copies a member's evaluation to an offspring of the same genome:
// every column but those that say where and how long it ran, the trials,
// and the individual whose simulation it is, through a chain of copies.
TEST_F(GenerationsTest, ReuseCopiesAMembersEvaluationWithItsTrials) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1, 2, 3}).ok());
  Evaluation guided = ::animat::testing::OkEvaluation(0, -0.75);
  guided.result.set_max_overlap(0.0625);
  guided.result.set_distance(3.5);
  guided.result.set_energy(12.25);
  guided.result.add_source_distances(29.0);
  guided.result.add_source_distances(31.5);
  *guided.result.mutable_body() = ::animat::testing::MakeBody(4);
  guided.isa = "avx512";
  Evaluation crashed =
      ::animat::testing::FailedEvaluation(1, v1::EvaluationResult::CRASHED);
  ASSERT_TRUE(
      store_
          ->RecordEvaluations(
              run_, {guided, crashed, ::animat::testing::FailedEvaluation(2)})
          .ok());
  Result<std::unique_ptr<GenerationWrite>> write =
      store_->BeginGeneration(run_, 1, {0, 4, 5, 6, 7});
  ASSERT_TRUE(write.ok()) << write.status().ToString();
  ASSERT_TRUE((*write)
                  ->Add({MakeIndividual(4, 1, {0}, {"copy"}),
                         MakeIndividual(5, 1, {1}, {"copy"}),
                         MakeIndividual(6, 1, {2}, {"copy"}),
                         MakeIndividual(7, 1, {3}, {"copy"})})
                  .ok());
  EXPECT_TRUE(*(*write)->Reuse(4, 0));
  EXPECT_FALSE(*(*write)->Reuse(5, 1)) << "a crash says nothing of a genome";
  EXPECT_TRUE(*(*write)->Reuse(6, 2));
  EXPECT_FALSE(*(*write)->Reuse(7, 3)) << "3 is not evaluated";
  EXPECT_FALSE(*(*write)->Reuse(4, 2)) << "4 keeps its first evaluation";
  EXPECT_FALSE(*(*write)->Reuse(99, 0)) << "99 was never made";
  ASSERT_TRUE((*write)->Commit().ok());
  write->reset();

  // What the evaluation says of the genome.
  const auto result_of = [this](int id) {
    return Rows(*store_,
                "SELECT status, reason, fitness, cells, steps, state_hash,"
                " springs, chambers, skin_edges, spread_major, spread_minor,"
                " distance, energy, max_overlap FROM evaluations WHERE id = " +
                    std::to_string(id));
  };
  EXPECT_EQ(result_of(4), result_of(0));
  EXPECT_EQ(result_of(6), result_of(2));
  EXPECT_EQ(Rows(*store_,
                 "SELECT id, reused_from, wall_seconds, worker, isa FROM"
                 " evaluations ORDER BY id"),
            (Table{{"0", "NULL", "0.25", "host:42", "avx512"},
                   {"1", "NULL", "0.001", "host:43", "NULL"},
                   {"2", "NULL", "0.001", "host:43", "NULL"},
                   {"4", "0", "NULL", "NULL", "NULL"},
                   {"6", "2", "NULL", "NULL", "NULL"}}));
  EXPECT_EQ(Rows(*store_,
                 "SELECT id, trial, source_distance FROM trials"
                 " ORDER BY id, trial"),
            (Table{{"0", "0", "29.0"},
                   {"0", "1", "31.5"},
                   {"4", "0", "29.0"},
                   {"4", "1", "31.5"}}));
  EXPECT_TRUE(IsUtcStamp(
      Value(*store_, "SELECT evaluated_at FROM evaluations WHERE id = 4")));
  Result<std::vector<uint64_t>> pending = store_->Unevaluated(run_);
  ASSERT_TRUE(pending.ok());
  EXPECT_EQ(*pending, (std::vector<uint64_t>{3, 5, 7}));

  // A copy of the copy names the individual that was simulated.
  ASSERT_TRUE(store_->CompleteGeneration(run_, 0, {0, 1, 2, 3}, {}).ok());
  write = store_->BeginGeneration(run_, 2, {4, 8});
  ASSERT_TRUE(write.ok()) << write.status().ToString();
  ASSERT_TRUE((*write)->Add({MakeIndividual(8, 2, {4}, {"copy"})}).ok());
  EXPECT_TRUE(*(*write)->Reuse(8, 4));
  ASSERT_TRUE((*write)->Commit().ok());
  EXPECT_EQ(Value(*store_, "SELECT reused_from FROM individuals WHERE id = 8"),
            "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM trials WHERE id = 8"), "2");
}

// Reuse is part of the generation's transaction: not committed, nothing.
TEST_F(GenerationsTest, AReuseNotCommittedLeavesNothing) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
  ASSERT_TRUE(
      store_->RecordEvaluations(run_, {::animat::testing::OkEvaluation(0, 1.5)})
          .ok());
  {
    Result<std::unique_ptr<GenerationWrite>> write =
        store_->BeginGeneration(run_, 1, {0, 4});
    ASSERT_TRUE(write.ok()) << write.status().ToString();
    ASSERT_TRUE((*write)->Add({MakeIndividual(4, 1, {0}, {"copy"})}).ok());
    EXPECT_TRUE(*(*write)->Reuse(4, 0));
  }
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM evaluations"), "1");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM births WHERE id = 4"), "0");
}

TEST(GenerationWriteTest, OtherConnectionsSeeTheGenerationOnlyOnceCommitted) {
  const TempStorePath path("generation-write");
  Result<std::unique_ptr<Store>> store = Store::Open(path.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  const int64_t run = MakeRun(**store);
  ASSERT_TRUE((*store)->AddIndividuals(run, {MakeIndividual(0, 0)}).ok());
  Result<std::unique_ptr<Store>> reader = Store::OpenForQueries(path.path());
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  const auto generations = [&] {
    return Value(**reader, "SELECT COUNT(*) FROM generations") + " " +
           Value(**reader, "SELECT COUNT(*) FROM births");
  };

  Result<std::unique_ptr<GenerationWrite>> write =
      (*store)->BeginGeneration(run, 0, {0, 1, 2});
  ASSERT_TRUE(write.ok()) << write.status().ToString();
  ASSERT_TRUE((*write)->Add({MakeIndividual(1, 0)}).ok());
  EXPECT_EQ(generations(), "0 1");
  ASSERT_TRUE((*write)->Add({MakeIndividual(2, 0)}).ok());
  EXPECT_EQ(generations(), "0 1");
  ASSERT_TRUE((*write)->Commit().ok());
  EXPECT_EQ(generations(), "1 3");
}

// The transaction a generation's write holds between its chunks harms no
// reader (WAL): a reader's own transaction, begun before the write and
// kept open across its chunks and its commit, neither blocks the commit
// nor sees half a generation; its next transaction sees all of it. A
// reader that begins mid-write is not blocked either.
TEST(GenerationWriteTest, AReaderAcrossTheWriteNeitherBlocksNorSeesHalf) {
  const TempStorePath path("generation-reader");
  Result<std::unique_ptr<Store>> store = Store::Open(path.path());
  ASSERT_TRUE(store.ok()) << store.status().ToString();
  const int64_t run = MakeRun(**store);
  ASSERT_TRUE((*store)->AddIndividuals(run, {MakeIndividual(0, 0)}).ok());
  Result<std::unique_ptr<sql::Database>> reader =
      sql::Database::Open(path.path(), /*read_only=*/true);
  ASSERT_TRUE(reader.ok()) << reader.status().ToString();
  const auto count = [&](sql::Database& db) {
    Result<sql::Statement> s = db.Prepare(
        "SELECT (SELECT COUNT(*) FROM generations) || ' ' ||"
        " (SELECT COUNT(*) FROM births)");
    EXPECT_TRUE(s.ok()) << s.status().ToString();
    if (!s.ok()) return std::string("error");
    Result<bool> row = s->Step();
    EXPECT_TRUE(row.ok() && *row);
    return row.ok() && *row ? s->Text(0) : std::string("error");
  };
  ASSERT_TRUE((*reader)->Execute("BEGIN").ok());
  EXPECT_EQ(count(**reader), "0 1");  // The reader's snapshot starts here.

  Result<std::unique_ptr<GenerationWrite>> write =
      (*store)->BeginGeneration(run, 0, {0, 1, 2});
  ASSERT_TRUE(write.ok()) << write.status().ToString();
  ASSERT_TRUE((*write)->Add({MakeIndividual(1, 0)}).ok());
  Result<std::unique_ptr<sql::Database>> late =
      sql::Database::Open(path.path(), /*read_only=*/true);
  ASSERT_TRUE(late.ok()) << late.status().ToString();
  EXPECT_EQ(count(**late), "0 1");  // Begun mid-write: not blocked.
  ASSERT_TRUE((*write)->Add({MakeIndividual(2, 0)}).ok());
  const Status committed = (*write)->Commit();
  EXPECT_TRUE(committed.ok()) << committed.ToString();
  EXPECT_EQ(count(**reader), "0 1");  // Still its snapshot: no half.
  ASSERT_TRUE((*reader)->Execute("COMMIT").ok());
  EXPECT_EQ(count(**reader), "1 3");
  EXPECT_EQ(count(**late), "1 3");
}

TEST_F(GenerationsTest, CompleteGenerationSetsRanksAndStatistics) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1, 2, 3}).ok());
  GenerationStats stats;
  stats.evaluated = 3;
  stats.failed = 1;
  stats.best_id = 2;
  stats.best = 0.75;
  stats.mean = 0.5;
  stats.median = 0.4;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 0, {2, 0, 3, 1}, stats).ok());

  EXPECT_EQ(Rows(*store_, "SELECT id, rank FROM members ORDER BY id"),
            (Table{{"0", "1"}, {"1", "3"}, {"2", "0"}, {"3", "2"}}));
  const Table row =
      Rows(*store_,
           "SELECT run_id, generation, size, evaluated, failed, best_id,"
           " best_fitness, mean_fitness, median_fitness, completed_at >= "
           "created_at FROM generation_statistics");
  EXPECT_EQ(row, (Table{{std::to_string(run_), "0", "4", "3", "1", "2", "0.75",
                         "0.5", "0.4", "1"}}));
  EXPECT_TRUE(
      IsUtcStamp(Value(*store_, "SELECT completed_at FROM generations")));

  Result<GenerationRow> g = store_->Generation(run_, 0);
  ASSERT_TRUE(g.ok());
  EXPECT_TRUE(g->complete);
  EXPECT_EQ(g->members, (std::vector<uint64_t>{2, 0, 3, 1}));  // Rank order.
}

TEST_F(GenerationsTest, CompleteGenerationWithoutAnyFitness) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {1, 0}).ok());
  GenerationStats stats;
  stats.failed = 2;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 0, {1, 0}, stats).ok());
  EXPECT_EQ(Rows(*store_,
                 "SELECT evaluated, failed, best_id, best_fitness,"
                 " mean_fitness, median_fitness, completed_at IS NOT NULL"
                 " FROM generations"),
            (Table{{"0", "2", "NULL", "NULL", "NULL", "NULL", "1"}}));
  Result<GenerationRow> g = store_->Generation(run_, 0);
  ASSERT_TRUE(g.ok());
  EXPECT_TRUE(g->complete);
  EXPECT_EQ(g->members, (std::vector<uint64_t>{1, 0}));
}

TEST_F(GenerationsTest, CompletingOneGenerationLeavesOthersAlone) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 1, {1, 0}).ok());
  GenerationStats stats;
  stats.evaluated = 2;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 1, {1, 0}, stats).ok());
  Result<GenerationRow> g0 = store_->Generation(run_, 0);
  ASSERT_TRUE(g0.ok());
  EXPECT_FALSE(g0->complete);
  EXPECT_EQ(Value(*store_,
                  "SELECT COUNT(*) FROM members WHERE generation = 0 AND "
                  "rank IS NOT NULL"),
            "0");
}

TEST_F(GenerationsTest, LatestGenerationIsTheHighestOfTheRun) {
  Result<std::optional<GenerationRow>> latest = store_->LatestGeneration(run_);
  ASSERT_TRUE(latest.ok());
  EXPECT_FALSE(latest->has_value());
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 2, {3}).ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 1, {2}).ok());
  latest = store_->LatestGeneration(run_);
  ASSERT_TRUE(latest.ok());
  ASSERT_TRUE(latest->has_value());
  EXPECT_EQ((*latest)->generation, 2);
  EXPECT_EQ((*latest)->members, (std::vector<uint64_t>{3}));
  EXPECT_FALSE((*latest)->complete);

  // Another run's generations do not count.
  const int64_t other = MakeRun(*store_, 8);
  latest = store_->LatestGeneration(other);
  ASSERT_TRUE(latest.ok());
  EXPECT_FALSE(latest->has_value());
}

TEST_F(GenerationsTest, UnknownGenerationIsNotFound) {
  Result<GenerationRow> g = store_->Generation(run_, 3);
  ASSERT_FALSE(g.ok());
  EXPECT_EQ(g.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(g.status().message(),
            "no generation 3 in run " + std::to_string(run_));
}

}  // namespace
}  // namespace animat::lineage
