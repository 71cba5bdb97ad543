// Individuals and their evaluations in the lineage store: AddIndividuals,
// RecordEvaluations, Individual, IndividualsOf, ScoresOf, MemberScores,
// Unevaluated, NextId.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "common/protocol/genome_wire.h"
#include "master/lineage/store.h"
#include "tests/lineage/lineage_test_util.h"
#include "tests/lineage/store_test_peer.h"

namespace animat::lineage {
namespace {

using ::animat::testing::FailedEvaluation;
using ::animat::testing::IsHex16;
using ::animat::testing::IsUtcStamp;
using ::animat::testing::MakeBody;
using ::animat::testing::MakeGenome;
using ::animat::testing::MakeIndividual;
using ::animat::testing::MakeRun;
using ::animat::testing::MemoryStore;
using ::animat::testing::OkEvaluation;
using ::animat::testing::Rows;
using ::animat::testing::Value;

using Table = std::vector<std::vector<std::string>>;

std::vector<uint64_t> IdsOf(const std::vector<Score>& scores) {
  std::vector<uint64_t> ids;
  for (const Score& s : scores) ids.push_back(s.id);
  return ids;
}

class IndividualsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = MemoryStore();
    ASSERT_NE(store_, nullptr);
    run_ = MakeRun(*store_);
  }

  std::unique_ptr<Store> store_;
  int64_t run_ = 0;
};

TEST_F(IndividualsTest, AddedIndividualReadsBackWithParentsInOrder) {
  ASSERT_TRUE(
      store_
          ->AddIndividuals(run_, {MakeIndividual(3, 0), MakeIndividual(5, 0),
                                  MakeIndividual(9, 0)})
          .ok());
  NewIndividual child =
      MakeIndividual(10, 1, {9, 3, 5}, {"crossover", "sign", "coordinate"});
  ASSERT_TRUE(store_->AddIndividuals(run_, {child}).ok());

  Result<IndividualRow> row = store_->Individual(run_, 10);
  ASSERT_TRUE(row.ok()) << row.status().ToString();
  EXPECT_EQ(row->id, 10u);
  EXPECT_EQ(row->generation, 1);
  EXPECT_EQ(row->parents, (std::vector<uint64_t>{9, 3, 5}));
  EXPECT_EQ(row->operators, "crossover,sign,coordinate");
  EXPECT_EQ(row->genome.SerializeAsString(), child.genome.SerializeAsString());
  EXPECT_FALSE(row->evaluated);
  EXPECT_EQ(row->status, "");
  EXPECT_EQ(row->reason, "");
  EXPECT_FALSE(row->fitness.has_value());

  EXPECT_EQ(Rows(*store_,
                 "SELECT position, parent FROM parents WHERE child = 10 "
                 "ORDER BY position"),
            (Table{{"0", "9"}, {"1", "3"}, {"2", "5"}}));
  const Table columns = Rows(
      *store_,
      "SELECT generation, genome_hash, elements, created_at, status, reason,"
      " fitness, cells, steps, wall_seconds, worker, state_hash,"
      " evaluated_at FROM individuals WHERE id = 10");
  ASSERT_EQ(columns.size(), 1u);
  EXPECT_EQ(columns[0][0], "1");
  EXPECT_EQ(columns[0][1], Hex64(protocol::GenomeHash(child.genome)));
  EXPECT_TRUE(IsHex16(columns[0][1])) << columns[0][1];
  EXPECT_EQ(columns[0][2], "3");
  EXPECT_TRUE(IsUtcStamp(columns[0][3])) << columns[0][3];
  for (size_t c = 4; c < columns[0].size(); ++c) {
    EXPECT_EQ(columns[0][c], "NULL") << "column " << c;
  }
}

TEST_F(IndividualsTest, RandomIndividualHasNoParents) {
  ASSERT_TRUE(store_->AddIndividuals(run_, {MakeIndividual(0, 0)}).ok());
  Result<IndividualRow> row = store_->Individual(run_, 0);
  ASSERT_TRUE(row.ok());
  EXPECT_TRUE(row->parents.empty());
  EXPECT_EQ(row->operators, "random");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM parents"), "0");
}

TEST_F(IndividualsTest, OperatorsAreJoinedByCommas) {
  ASSERT_TRUE(store_
                  ->AddIndividuals(run_, {MakeIndividual(0, 0, {}, {}),
                                          MakeIndividual(1, 0, {}, {"random"}),
                                          MakeIndividual(2, 1, {0, 1},
                                                         {"crossover", "type",
                                                          "duplication"})})
                  .ok());
  EXPECT_EQ(
      Rows(*store_, "SELECT id, operators FROM individuals ORDER BY id"),
      (Table{{"0", ""}, {"1", "random"}, {"2", "crossover,type,duplication"}}));
}

TEST_F(IndividualsTest, GenomeBlobRoundTripsBitForBit) {
  NewIndividual n = MakeIndividual(0, 0);
  n.genome = MakeGenome(50, 12345);
  v1::Element* e = n.genome.add_elements();
  e->set_type(v1::Element::S_OUT);
  e->set_sign(-1);
  e->set_x(-0.0);
  e->set_y(std::numeric_limits<double>::denorm_min());
  e->set_channel(v1::Element::CONTRACT);
  ASSERT_TRUE(store_->AddIndividuals(run_, {n}).ok());
  Result<IndividualRow> row = store_->Individual(run_, 0);
  ASSERT_TRUE(row.ok());
  EXPECT_EQ(row->genome.SerializeAsString(), n.genome.SerializeAsString());
  ASSERT_EQ(row->genome.elements_size(), 51);
  EXPECT_TRUE(std::signbit(row->genome.elements(50).x()));
  EXPECT_EQ(row->genome.elements(50).y(),
            std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(row->genome.elements(50).channel(), v1::Element::CONTRACT);
  EXPECT_EQ(Value(*store_, "SELECT elements FROM individuals"), "51");
}

TEST_F(IndividualsTest, AddIndividualsIsOneTransaction) {
  // A batch whose last individual repeats its first: nothing of it stays,
  // not even the parents written before the failure.
  const Status status = store_->AddIndividuals(
      run_, {MakeIndividual(10, 1, {1, 2}), MakeIndividual(11, 1, {2}),
             MakeIndividual(10, 1, {3})});
  EXPECT_FALSE(status.ok());
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM individuals"), "0");
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM parents"), "0");
  Result<uint64_t> next = store_->NextId(run_);
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(*next, 0u);

  // A batch colliding with an earlier one leaves the earlier one as it was.
  NewIndividual first = MakeIndividual(20, 0);
  ASSERT_TRUE(store_->AddIndividuals(run_, {first}).ok());
  NewIndividual clash = MakeIndividual(20, 3, {7}, {"sign"});
  clash.genome = MakeGenome(8, 99);
  EXPECT_FALSE(
      store_->AddIndividuals(run_, {MakeIndividual(21, 0), clash}).ok());
  EXPECT_EQ(Rows(*store_, "SELECT id, generation, operators FROM individuals"),
            (Table{{"20", "0", "random"}}));
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM parents"), "0");
  Result<IndividualRow> row = store_->Individual(run_, 20);
  ASSERT_TRUE(row.ok());
  EXPECT_EQ(row->genome.SerializeAsString(), first.genome.SerializeAsString());

  // The store still takes writes after the rollback.
  EXPECT_TRUE(store_->AddIndividuals(run_, {MakeIndividual(21, 0)}).ok());
}

TEST_F(IndividualsTest, AddIndividualsToAnUnknownRunFails) {
  EXPECT_FALSE(store_->AddIndividuals(run_ + 100, {MakeIndividual(0, 0)}).ok());
  EXPECT_EQ(Value(*store_, "SELECT COUNT(*) FROM individuals"), "0");
}

TEST_F(IndividualsTest, RunsHaveTheirOwnIds) {
  const int64_t other = MakeRun(*store_, 8);
  NewIndividual mine = MakeIndividual(0, 0);
  NewIndividual theirs = MakeIndividual(0, 4, {}, {"sign"});
  theirs.genome = MakeGenome(6, 77);
  ASSERT_TRUE(store_->AddIndividuals(run_, {mine}).ok());
  ASSERT_TRUE(store_->AddIndividuals(other, {theirs}).ok());
  ASSERT_TRUE(store_->RecordEvaluations(other, {OkEvaluation(0, 2.0)}).ok());
  Result<IndividualRow> a = store_->Individual(run_, 0);
  Result<IndividualRow> b = store_->Individual(other, 0);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->generation, 0);
  EXPECT_FALSE(a->evaluated);
  EXPECT_EQ(b->generation, 4);
  EXPECT_EQ(b->fitness, 2.0);
  EXPECT_EQ(b->genome.SerializeAsString(), theirs.genome.SerializeAsString());
  Result<std::vector<uint64_t>> pending = store_->Unevaluated(run_);
  ASSERT_TRUE(pending.ok());
  EXPECT_EQ(*pending, (std::vector<uint64_t>{0}));
}

TEST_F(IndividualsTest, RecordEvaluationsSetsEveryColumn) {
  ASSERT_TRUE(
      store_
          ->AddIndividuals(run_, {MakeIndividual(0, 0), MakeIndividual(1, 0),
                                  MakeIndividual(2, 0), MakeIndividual(3, 0)})
          .ok());
  Evaluation ok = OkEvaluation(0, 0.1);  // Needs all 17 digits.
  ok.result.set_state_hash(0x00000000000000abULL);
  ok.wall_seconds = 1.5;
  ok.worker = "node7:1234";
  ASSERT_TRUE(
      store_
          ->RecordEvaluations(
              run_,
              {ok, FailedEvaluation(1),
               FailedEvaluation(2, v1::EvaluationResult::NUMERICAL_FAILURE),
               FailedEvaluation(3, v1::EvaluationResult::NOT_EVALUATED)})
          .ok());

  const Table rows = Rows(
      *store_,
      "SELECT id, status, reason, fitness = 0.1, cells, steps, wall_seconds,"
      " worker, state_hash, typeof(fitness) FROM individuals ORDER BY id");
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"0", "ok", "", "1", "32", "1000",
                                               "1.5", "node7:1234",
                                               "00000000000000ab", "real"}));
  EXPECT_EQ(rows[1],
            (std::vector<std::string>{
                "1", "non_viable", "no path from input to output", "NULL", "1",
                "0", "0.001", "host:43", "0000000000000000", "null"}));
  EXPECT_EQ(rows[2][1], "numerical_failure");
  EXPECT_EQ(rows[3][1], "not_evaluated");
  EXPECT_EQ(rows[3][9], "null");
  for (const std::string& stamp :
       {Value(*store_, "SELECT evaluated_at FROM individuals WHERE id = 0"),
        Value(*store_, "SELECT evaluated_at FROM individuals WHERE id = 3")}) {
    EXPECT_TRUE(IsUtcStamp(stamp)) << stamp;
  }

  Result<IndividualRow> row = store_->Individual(run_, 0);
  ASSERT_TRUE(row.ok());
  EXPECT_TRUE(row->evaluated);
  EXPECT_EQ(row->status, "ok");
  EXPECT_EQ(row->fitness, 0.1);  // The same bits.
  Result<IndividualRow> failed = store_->Individual(run_, 1);
  ASSERT_TRUE(failed.ok());
  EXPECT_TRUE(failed->evaluated);
  EXPECT_EQ(failed->status, "non_viable");
  EXPECT_EQ(failed->reason, "no path from input to output");
  EXPECT_FALSE(failed->fitness.has_value());
}

// The body summary of a result goes into the body columns, the spreads
// bit for bit; a result without one (no body was built) leaves them NULL.
TEST_F(IndividualsTest, RecordEvaluationsRecordsTheBodySummary) {
  ASSERT_TRUE(
      store_
          ->AddIndividuals(run_, {MakeIndividual(0, 0), MakeIndividual(1, 0),
                                  MakeIndividual(2, 0), MakeIndividual(3, 0)})
          .ok());
  Evaluation ok = OkEvaluation(0, 1.5);
  *ok.result.mutable_body() = MakeBody(7);
  // A chain: a body without a chamber, refused by min_chambers.
  Evaluation chain = FailedEvaluation(1, v1::EvaluationResult::DEGENERATE_BODY);
  chain.result.set_reason("no chamber: the body encloses no area");
  *chain.result.mutable_body() = MakeBody(0);
  chain.result.mutable_body()->set_spread_minor(0.0);
  ASSERT_TRUE(
      store_
          ->RecordEvaluations(
              run_, {ok, chain, FailedEvaluation(2),
                     FailedEvaluation(3, v1::EvaluationResult::TOO_FEW_CELLS)})
          .ok());

  EXPECT_EQ(
      Rows(*store_,
           "SELECT id, status, cells, springs, chambers, skin_edges,"
           " typeof(spread_major), typeof(spread_minor)"
           " FROM individuals ORDER BY id"),
      (Table{{"0", "ok", "32", "67", "7", "13", "real", "real"},
             {"1", "degenerate_body", "1", "60", "0", "20", "real", "real"},
             {"2", "non_viable", "1", "NULL", "NULL", "NULL", "null", "null"},
             {"3", "too_few_cells", "1", "NULL", "NULL", "NULL", "null",
              "null"}}));
  Result<sql::Statement> spreads = StoreTestPeer::Database(*store_).Prepare(
      "SELECT spread_major, spread_minor FROM individuals WHERE id = ?");
  ASSERT_TRUE(spreads.ok());
  for (const Evaluation* e : {&ok, &chain}) {
    spreads->Bind(1, static_cast<int64_t>(e->id));
    Result<bool> row = spreads->Step();
    ASSERT_TRUE(row.ok() && *row);
    EXPECT_EQ(std::bit_cast<uint64_t>(spreads->Double(0)),
              std::bit_cast<uint64_t>(e->result.body().spread_major()))
        << "individual " << e->id;
    EXPECT_EQ(std::bit_cast<uint64_t>(spreads->Double(1)),
              std::bit_cast<uint64_t>(e->result.body().spread_minor()))
        << "individual " << e->id;
    spreads->Reset();
  }
}

// What bodies evolved: the chambers of every evaluation, counted.
TEST_F(IndividualsTest, ChambersGroupByCountsTheBodiesOfEachKind) {
  std::vector<NewIndividual> made;
  std::vector<Evaluation> results;
  const int chambers[] = {3, 1, 3, 0, 5, 3, 1};
  for (uint64_t id = 0; id < 10; ++id) {
    made.push_back(MakeIndividual(id, 0));
    if (id < 7) {
      Evaluation e =
          chambers[id] == 0
              ? FailedEvaluation(id, v1::EvaluationResult::DEGENERATE_BODY)
              : OkEvaluation(id, 0.5 * static_cast<double>(id));
      *e.result.mutable_body() = MakeBody(chambers[id]);
      results.push_back(std::move(e));
    } else if (id < 9) {
      results.push_back(FailedEvaluation(id));  // No body.
    }                                           // 9 is pending.
  }
  ASSERT_TRUE(store_->AddIndividuals(run_, made).ok());
  ASSERT_TRUE(store_->RecordEvaluations(run_, results).ok());
  EXPECT_EQ(
      Rows(*store_,
           "SELECT chambers, COUNT(*) FROM individuals"
           " GROUP BY chambers ORDER BY chambers"),
      (Table{{"NULL", "3"}, {"0", "1"}, {"1", "2"}, {"3", "3"}, {"5", "1"}}));
  EXPECT_EQ(Rows(*store_,
                 "SELECT chambers, COUNT(*) FROM individuals"
                 " WHERE status = 'ok' GROUP BY chambers ORDER BY chambers"),
            (Table{{"1", "2"}, {"3", "3"}, {"5", "1"}}));
}

TEST_F(IndividualsTest, FirstEvaluationIsKept) {
  ASSERT_TRUE(
      store_->AddIndividuals(run_, {MakeIndividual(0, 0), MakeIndividual(1, 0)})
          .ok());
  ASSERT_TRUE(
      store_
          ->RecordEvaluations(run_, {OkEvaluation(0, 0.5), FailedEvaluation(1)})
          .ok());
  const Table before = Rows(*store_, "SELECT * FROM individuals ORDER BY id");

  Evaluation again = OkEvaluation(0, 0.9);
  again.worker = "other:1";
  again.result.set_state_hash(1);
  *again.result.mutable_body() = MakeBody(4);
  // A duplicate result (a lease that expired and came back twice) succeeds
  // and changes nothing, within one batch or in a later one.
  EXPECT_TRUE(store_->RecordEvaluations(run_, {again, again}).ok());
  EXPECT_TRUE(
      store_->RecordEvaluations(run_, {OkEvaluation(1, 3.0), again}).ok());
  EXPECT_EQ(Rows(*store_, "SELECT * FROM individuals ORDER BY id"), before);
  Result<IndividualRow> row = store_->Individual(run_, 0);
  ASSERT_TRUE(row.ok());
  EXPECT_EQ(row->fitness, 0.5);
}

// A guidance evaluation (docs/model.md §10.2) records each trial's final
// distance to its source; the first evaluation's trials are kept with it,
// and an evaluation without guidance, or not ok, has none.
TEST_F(IndividualsTest, GuidanceEvaluationsRecordTheirTrials) {
  ASSERT_TRUE(
      store_
          ->AddIndividuals(run_, {MakeIndividual(0, 0), MakeIndividual(1, 0),
                                  MakeIndividual(2, 0)})
          .ok());
  Evaluation guided = OkEvaluation(0, -1.25);
  for (double d : {29.5, 31.0, 30.25, 34.25}) {
    guided.result.add_source_distances(d);
  }
  Evaluation again = guided;
  again.result.set_source_distances(0, 1.0);
  ASSERT_TRUE(store_
                  ->RecordEvaluations(run_, {guided, OkEvaluation(1, 0.5),
                                             FailedEvaluation(2), again})
                  .ok());
  EXPECT_EQ(Rows(*store_,
                 "SELECT id, trial, source_distance FROM trials"
                 " ORDER BY id, trial"),
            (Table{{"0", "0", "29.5"},
                   {"0", "1", "31.0"},
                   {"0", "2", "30.25"},
                   {"0", "3", "34.25"}}));
  // A later duplicate changes nothing either.
  ASSERT_TRUE(store_->RecordEvaluations(run_, {again}).ok());
  EXPECT_EQ(Value(*store_, "SELECT SUM(source_distance) FROM trials"), "125.0");
  // The mean score is the fitness: D - mean d_k with D = 30.
  EXPECT_EQ(Value(*store_,
                  "SELECT 30 - AVG(t.source_distance) = i.fitness FROM trials t"
                  " JOIN individuals i ON i.run_id = t.run_id AND i.id = t.id"),
            "1");
}

TEST_F(IndividualsTest, FirstEvaluationInABatchIsKept) {
  ASSERT_TRUE(store_->AddIndividuals(run_, {MakeIndividual(0, 0)}).ok());
  ASSERT_TRUE(store_
                  ->RecordEvaluations(
                      run_, {OkEvaluation(0, 0.25), OkEvaluation(0, 0.75)})
                  .ok());
  EXPECT_EQ(Value(*store_, "SELECT fitness FROM individuals"), "0.25");
}

TEST_F(IndividualsTest, RecordEvaluationsIsOneTransaction) {
  ASSERT_TRUE(
      store_
          ->AddIndividuals(run_, {MakeIndividual(1, 0), MakeIndividual(2, 0),
                                  MakeIndividual(3, 0)})
          .ok());
  // Fault injection: recording individual 3's evaluation fails.
  ASSERT_TRUE(StoreTestPeer::Database(*store_)
                  .Execute("CREATE TEMP TRIGGER fail_three BEFORE INSERT ON "
                           "main.evaluations WHEN NEW.id = 3 BEGIN SELECT "
                           "RAISE(ABORT, 'injected failure'); END")
                  .ok());
  const Status status = store_->RecordEvaluations(
      run_, {OkEvaluation(1, 1.0), OkEvaluation(2, 2.0), OkEvaluation(3, 3.0)});
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("injected failure"), std::string::npos)
      << status.message();
  Result<std::vector<uint64_t>> pending = store_->Unevaluated(run_);
  ASSERT_TRUE(pending.ok());
  EXPECT_EQ(*pending, (std::vector<uint64_t>{1, 2, 3}));
  EXPECT_EQ(Value(*store_,
                  "SELECT COUNT(*) FROM individuals WHERE worker "
                  "IS NOT NULL OR fitness IS NOT NULL"),
            "0");

  // Once the fault is gone the same batch goes through.
  ASSERT_TRUE(
      StoreTestPeer::Database(*store_).Execute("DROP TRIGGER fail_three").ok());
  EXPECT_TRUE(
      store_
          ->RecordEvaluations(run_, {OkEvaluation(1, 1.0), OkEvaluation(2, 2.0),
                                     OkEvaluation(3, 3.0)})
          .ok());
  pending = store_->Unevaluated(run_);
  ASSERT_TRUE(pending.ok());
  EXPECT_TRUE(pending->empty());
}

TEST_F(IndividualsTest, UnevaluatedListsPendingIdsInIncreasingOrder) {
  ASSERT_TRUE(
      store_
          ->AddIndividuals(run_, {MakeIndividual(7, 1), MakeIndividual(2, 0),
                                  MakeIndividual(5, 0), MakeIndividual(11, 2)})
          .ok());
  Result<std::vector<uint64_t>> pending = store_->Unevaluated(run_);
  ASSERT_TRUE(pending.ok());
  EXPECT_EQ(*pending, (std::vector<uint64_t>{2, 5, 7, 11}));
  ASSERT_TRUE(store_
                  ->RecordEvaluations(
                      run_, {OkEvaluation(5, 1.0), FailedEvaluation(11)})
                  .ok());
  pending = store_->Unevaluated(run_);
  ASSERT_TRUE(pending.ok());
  EXPECT_EQ(*pending, (std::vector<uint64_t>{2, 7}));
}

TEST_F(IndividualsTest, NextIdIsOneMoreThanTheHighest) {
  Result<uint64_t> next = store_->NextId(run_);
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(*next, 0u);
  ASSERT_TRUE(
      store_
          ->AddIndividuals(run_, {MakeIndividual(0, 0), MakeIndividual(41, 0),
                                  MakeIndividual(7, 0)})
          .ok());
  next = store_->NextId(run_);
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(*next, 42u);
  // Per run.
  next = store_->NextId(MakeRun(*store_, 9));
  ASSERT_TRUE(next.ok());
  EXPECT_EQ(*next, 0u);
}

TEST_F(IndividualsTest, IndividualsOfGivesOneGenerationInIncreasingId) {
  ASSERT_TRUE(
      store_
          ->AddIndividuals(
              run_, {MakeIndividual(9, 1, {0}), MakeIndividual(0, 0),
                     MakeIndividual(4, 1, {0, 0}), MakeIndividual(6, 2, {4})})
          .ok());
  ASSERT_TRUE(store_->RecordEvaluations(run_, {OkEvaluation(9, 1.25)}).ok());
  Result<std::vector<IndividualRow>> rows = store_->IndividualsOf(run_, 1);
  ASSERT_TRUE(rows.ok()) << rows.status().ToString();
  ASSERT_EQ(rows->size(), 2u);
  EXPECT_EQ((*rows)[0].id, 4u);
  EXPECT_EQ((*rows)[0].parents, (std::vector<uint64_t>{0, 0}));
  EXPECT_FALSE((*rows)[0].evaluated);
  EXPECT_EQ((*rows)[1].id, 9u);
  EXPECT_EQ((*rows)[1].parents, (std::vector<uint64_t>{0}));
  EXPECT_EQ((*rows)[1].fitness, 1.25);
  EXPECT_EQ((*rows)[1].genome.SerializeAsString(),
            MakeIndividual(9, 1).genome.SerializeAsString());
  rows = store_->IndividualsOf(run_, 5);
  ASSERT_TRUE(rows.ok());
  EXPECT_TRUE(rows->empty());
}

TEST_F(IndividualsTest, ScoresOfGivesOneGenerationsScores) {
  ASSERT_TRUE(store_
                  ->AddIndividuals(
                      run_, {MakeIndividual(3, 0), MakeIndividual(1, 0),
                             MakeIndividual(2, 0), MakeIndividual(8, 1, {1})})
                  .ok());
  ASSERT_TRUE(
      store_
          ->RecordEvaluations(run_, {OkEvaluation(1, 0.5), FailedEvaluation(2),
                                     OkEvaluation(8, 9.0)})
          .ok());
  Result<std::vector<Score>> scores = store_->ScoresOf(run_, 0);
  ASSERT_TRUE(scores.ok());
  ASSERT_EQ(IdsOf(*scores), (std::vector<uint64_t>{1, 2, 3}));
  EXPECT_TRUE((*scores)[0].evaluated);
  EXPECT_EQ((*scores)[0].fitness, 0.5);
  EXPECT_TRUE((*scores)[1].evaluated);  // Failed: evaluated, no fitness.
  EXPECT_FALSE((*scores)[1].fitness.has_value());
  EXPECT_FALSE((*scores)[2].evaluated);
  EXPECT_FALSE((*scores)[2].fitness.has_value());
}

TEST_F(IndividualsTest, MemberScoresFollowMembershipNotGeneration) {
  // Generation 1 holds the elite 0 (made for generation 0) and children.
  ASSERT_TRUE(
      store_->AddIndividuals(run_, {MakeIndividual(0, 0), MakeIndividual(1, 0)})
          .ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1}).ok());
  ASSERT_TRUE(store_
                  ->AddGeneration(
                      run_, 1, {0, 3, 2},
                      {MakeIndividual(3, 1, {0}), MakeIndividual(2, 1, {1, 0})})
                  .ok());
  ASSERT_TRUE(store_
                  ->RecordEvaluations(
                      run_, {OkEvaluation(0, 4.0), OkEvaluation(3, 1.0)})
                  .ok());
  Result<std::vector<Score>> scores = store_->MemberScores(run_, 1);
  ASSERT_TRUE(scores.ok());
  ASSERT_EQ(IdsOf(*scores), (std::vector<uint64_t>{0, 2, 3}));
  EXPECT_EQ((*scores)[0].fitness, 4.0);
  EXPECT_FALSE((*scores)[1].evaluated);
  EXPECT_EQ((*scores)[2].fitness, 1.0);
  Result<std::vector<Score>> made = store_->ScoresOf(run_, 1);
  ASSERT_TRUE(made.ok());
  EXPECT_EQ(IdsOf(*made), (std::vector<uint64_t>{2, 3}));
}

TEST_F(IndividualsTest, UnknownIndividualIsNotFound) {
  Result<IndividualRow> row = store_->Individual(run_, 12);
  ASSERT_FALSE(row.ok());
  EXPECT_EQ(row.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(row.status().message(),
            "no individual 12 in run " + std::to_string(run_));
}

}  // namespace
}  // namespace animat::lineage
