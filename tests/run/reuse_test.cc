// Copies are not simulated again: a run whose evaluations depend on the
// genome alone records, for an offspring whose genome a simulation cannot
// tell from a parent generation member's (the same evaluation key: the
// same bytes, or a change nothing reads), that member's evaluation instead
// of submitting it,
// and ends with the same lineage as a run that submits every offspring
// (both served by genome_scoring.h's stand-in for the workers).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/evaluation/evaluator.h"
#include "common/genome/genome_proto.h"
#include "master/lineage/store.h"
#include "master/run/evolution_run.h"
#include "tests/lineage/lineage_test_util.h"
#include "tests/run/genome_scoring.h"

namespace animat {
namespace {

using ::animat::testing::GenomeScoring;
using ::animat::testing::Rows;
using Table = std::vector<std::vector<std::string>>;

struct Finished {
  std::unique_ptr<lineage::Store> store;
  std::set<uint64_t> submitted;
};

Finished RunToEnd(bool follow_genome) {
  Finished out;
  out.store = ::animat::testing::MemoryStore();
  RunSettings settings;
  settings.evolution.seed = 5;
  settings.evolution.population = 20;
  settings.evolution.generations = 10;
  settings.evolution.elite = 2;
  Result<std::unique_ptr<EvolutionRun>> run =
      EvolutionRun::Start(out.store.get(), settings, [](std::string_view) {});
  EXPECT_TRUE(run.ok()) << run.status().ToString();
  if (!run.ok()) return out;
  GenomeScoring scoring(follow_genome);
  std::atomic<bool> stop{false};
  const Status status = (*run)->Run(&scoring, stop);
  EXPECT_TRUE(status.ok()) << status.ToString();
  EXPECT_TRUE((*run)->finished());
  out.submitted = scoring.submitted();
  return out;
}

// The evaluation key (EvaluationKey, default model) of a genome stored as
// hex; nullopt for one that is not valid.
std::optional<std::string> KeyOfHex(const std::string& hex) {
  std::string bytes;
  for (size_t i = 0; i + 1 < hex.size(); i += 2) {
    bytes.push_back(
        static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  }
  v1::Genome message;
  if (!message.ParseFromString(bytes)) return std::nullopt;
  Result<Genome> genome = GenomeFromProto(message);
  if (!genome.ok()) return std::nullopt;
  return EvaluationKey(*genome, ModelConfig{});
}

// What a lineage is, whether its copies were simulated or not: every
// offspring with its parents, operators, genome and evaluation, and every
// generation's ranked members and statistics. (Generation 0's candidates
// not chosen may still be on their way when a run ends.)
Table Lineage(lineage::Store& store) {
  Table all = Rows(store,
                   "SELECT id, generation, operators, genome_hash, status,"
                   " reason, fitness, cells, steps, state_hash, distance,"
                   " max_overlap FROM individuals WHERE generation > 0"
                   " ORDER BY id");
  for (const char* query :
       {"SELECT child, position, parent FROM parents ORDER BY 1, 2",
        "SELECT generation, id, rank FROM members ORDER BY 1, 2",
        "SELECT generation, size, evaluated, failed, best_id, best_fitness,"
        " mean_fitness, median_fitness FROM generation_statistics"
        " ORDER BY generation"}) {
    for (std::vector<std::string>& row : Rows(store, query)) {
      all.push_back(std::move(row));
    }
  }
  return all;
}

TEST(ReuseTest, CopiesTakeTheirParentsEvaluationAndTheLineageIsTheSame) {
  Finished reused = RunToEnd(/*follow_genome=*/true);
  Finished simulated = RunToEnd(/*follow_genome=*/false);
  ASSERT_NE(reused.store, nullptr);
  ASSERT_NE(simulated.store, nullptr);
  EXPECT_EQ(Lineage(*reused.store), Lineage(*simulated.store));
  EXPECT_EQ(Rows(*simulated.store,
                 "SELECT COUNT(*) FROM evaluations"
                 " WHERE reused_from IS NOT NULL"),
            (Table{{"0"}}));

  // Which offspring should have been reused: those with a member of the
  // generation before whose genome has the same evaluation key, the lowest
  // such member's evaluation naming the source (its own source, if
  // reused), unless it says nothing of the genome (crashed;
  // GenerationsTest covers that).
  std::map<std::string, std::optional<std::string>> key_of;  // By id.
  for (const std::vector<std::string>& row :
       Rows(*reused.store, "SELECT id, hex(genome) FROM births")) {
    key_of[row[0]] = KeyOfHex(row[1]);
  }
  Table expected;
  int unlike_bytes = 0;  // Reuses between genomes of different bytes.
  for (const std::vector<std::string>& o :
       Rows(*reused.store,
            "SELECT id, generation, genome FROM births WHERE generation > 0"
            " ORDER BY id")) {
    std::string source = "NULL";
    const std::optional<std::string>& key = key_of[o[0]];
    for (const std::vector<std::string>& m :
         Rows(*reused.store,
              "SELECT m.id, e.status, COALESCE(e.reused_from, e.id),"
              " p.genome = (SELECT genome FROM births WHERE id = " +
                  o[0] +
                  ") FROM members m JOIN births p ON p.run_id = m.run_id AND"
                  " p.id = m.id JOIN evaluations e ON e.run_id = m.run_id"
                  " AND e.id = m.id WHERE m.generation = " +
                  std::to_string(std::stoi(o[1]) - 1) + " ORDER BY m.id")) {
      if (!key || key_of[m[0]] != key) continue;
      if (m[1] != "crashed") {
        source = m[2];
        unlike_bytes += m[3] == "0";
      }
      break;  // The lowest member of the key.
    }
    expected.push_back({o[0], source});
  }
  EXPECT_GT(unlike_bytes, 0) << "no reuse between genomes of other bytes";
  const Table recorded =
      Rows(*reused.store,
           "SELECT b.id, e.reused_from FROM births b JOIN evaluations e"
           " ON e.run_id = b.run_id AND e.id = b.id WHERE b.generation > 0"
           " ORDER BY b.id");
  EXPECT_EQ(recorded, expected);
  int copies = 0;
  for (const std::vector<std::string>& row : recorded) {
    const uint64_t id = std::stoull(row[0]);
    if (row[1] == "NULL") {
      EXPECT_EQ(reused.submitted.count(id), 1u) << "individual " << id;
    } else {
      ++copies;
      EXPECT_EQ(reused.submitted.count(id), 0u) << "individual " << id;
    }
  }
  EXPECT_GT(copies, 5) << "the case is exercised";
  EXPECT_EQ(Rows(*reused.store,
                 "SELECT COUNT(*) FROM evaluations WHERE reused_from IS NOT"
                 " NULL AND (wall_seconds IS NOT NULL OR worker IS NOT NULL"
                 " OR isa IS NOT NULL)"),
            (Table{{"0"}}));
}

}  // namespace
}  // namespace animat
