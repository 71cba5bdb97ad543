// What the run loop reads and writes in bulk: a generation's members with
// their genomes in one query, the latest generation without its members,
// and individuals written from a genome serialised by the caller.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/protocol/genome_wire.h"
#include "master/lineage/store.h"
#include "tests/lineage/lineage_test_util.h"
#include "tests/lineage/store_test_peer.h"

namespace animat::lineage {
namespace {

using ::animat::testing::FailedEvaluation;
using ::animat::testing::MakeGenome;
using ::animat::testing::MakeIndividual;
using ::animat::testing::MakeRun;
using ::animat::testing::MemoryStore;
using ::animat::testing::OkEvaluation;
using ::animat::testing::Rows;

class RunLoopReadsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    store_ = MemoryStore();
    ASSERT_NE(store_, nullptr);
    run_ = MakeRun(*store_);
    std::vector<NewIndividual> made;
    for (uint64_t id = 0; id < 5; ++id) made.push_back(MakeIndividual(id, 0));
    ASSERT_TRUE(store_->AddIndividuals(run_, made).ok());
  }

  std::unique_ptr<Store> store_;
  int64_t run_ = 0;
};

TEST_F(RunLoopReadsTest, MemberGenomesAreTheMembersWithFitnessAndGenome) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {4, 1, 3}).ok());
  ASSERT_TRUE(
      store_
          ->RecordEvaluations(run_, {OkEvaluation(1, 0.5), FailedEvaluation(3),
                                     OkEvaluation(4, 0.125)})
          .ok());
  Result<std::vector<MemberGenome>> members = store_->MemberGenomes(run_, 0);
  ASSERT_TRUE(members.ok()) << members.status().ToString();
  ASSERT_EQ(members->size(), 3u);
  const std::vector<uint64_t> ids = {1, 3, 4};  // Increasing id.
  const std::vector<std::optional<double>> fitness = {0.5, std::nullopt, 0.125};
  for (size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ((*members)[i].id, ids[i]);
    EXPECT_EQ((*members)[i].fitness, fitness[i]) << "member " << ids[i];
    EXPECT_EQ((*members)[i].genome.SerializeAsString(),
              MakeGenome(3, ids[i]).SerializeAsString())
        << "member " << ids[i];
  }
  Result<std::vector<MemberGenome>> none = store_->MemberGenomes(run_, 1);
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->empty());
}

TEST_F(RunLoopReadsTest, MemberGenomesFailsNamingAnUnreadableGenome) {
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 2}).ok());
  ASSERT_TRUE(
      StoreTestPeer::Database(*store_)
          .Execute("UPDATE births SET genome = X'ffffffff' WHERE id = 2")
          .ok());
  Result<std::vector<MemberGenome>> members = store_->MemberGenomes(run_, 0);
  ASSERT_FALSE(members.ok());
  EXPECT_NE(members.status().message().find("individual 2"), std::string::npos)
      << members.status().ToString();
}

TEST_F(RunLoopReadsTest, LatestGenerationHeadIsTheLatestWithoutMembers) {
  Result<std::optional<GenerationRow>> empty =
      store_->LatestGenerationHead(run_);
  ASSERT_TRUE(empty.ok());
  EXPECT_FALSE(empty->has_value());
  ASSERT_TRUE(store_->AddGeneration(run_, 0, {0, 1, 2}).ok());
  GenerationStats stats;
  ASSERT_TRUE(store_->CompleteGeneration(run_, 0, {2, 0, 1}, stats).ok());
  ASSERT_TRUE(store_->AddGeneration(run_, 1, {2, 3}).ok());
  for (int pass = 0; pass < 2; ++pass) {
    Result<std::optional<GenerationRow>> head =
        store_->LatestGenerationHead(run_);
    Result<std::optional<GenerationRow>> full = store_->LatestGeneration(run_);
    ASSERT_TRUE(head.ok() && full.ok());
    ASSERT_TRUE(head->has_value() && full->has_value());
    EXPECT_EQ((*head)->generation, (*full)->generation);
    EXPECT_EQ((*head)->size, (*full)->size);
    EXPECT_EQ((*head)->complete, (*full)->complete);
    EXPECT_TRUE((*head)->members.empty());
    EXPECT_EQ((*head)->generation, 1);
    EXPECT_EQ((*head)->complete, pass == 1);
    ASSERT_TRUE(store_->CompleteGeneration(run_, 1, {3, 2}, stats).ok());
  }
}

TEST_F(RunLoopReadsTest, CallersSerializedGenomeIsStoredAsIs) {
  NewIndividual n = MakeIndividual(9, 0);
  n.genome = MakeGenome(4, 9);
  n.serialized = protocol::SerializeGenome(n.genome);
  NewIndividual plain = MakeIndividual(10, 0);
  plain.genome = n.genome;  // The same genome, serialised by the store.
  ASSERT_TRUE(store_->AddIndividuals(run_, {n, plain}).ok());
  const std::vector<std::vector<std::string>> rows =
      Rows(*store_,
           "SELECT hex(genome), genome_hash, elements FROM individuals"
           " WHERE id IN (9, 10) ORDER BY id");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], rows[1]);
  EXPECT_EQ(rows[0][1], Hex64(n.serialized->hash));
  EXPECT_EQ(rows[0][2], "4");
  Result<IndividualRow> read = store_->Individual(run_, 9);
  ASSERT_TRUE(read.ok());
  EXPECT_EQ(read->genome.SerializeAsString(), n.genome.SerializeAsString());
}

}  // namespace
}  // namespace animat::lineage
