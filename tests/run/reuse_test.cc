// Copies are not simulated again: a run whose evaluations depend on the
// genome alone records, for an offspring whose genome is a parent
// generation member's, that member's evaluation instead of submitting it,
// and ends with the same lineage as a run that submits every offspring.
//
// The service here stands in for the workers with a result that is a pure
// function of the genome's bytes (as a simulation's is), so that the two
// runs can be compared individual by individual in a fraction of a second;
// the real workers' determinism is tested in tests/master/.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/base/clock.h"
#include "common/protocol/genome_wire.h"
#include "master/dispatch/evaluation_service.h"
#include "master/lineage/store.h"
#include "master/run/evolution_run.h"
#include "tests/lineage/lineage_test_util.h"

namespace animat {
namespace {

using ::animat::testing::Rows;
using Table = std::vector<std::vector<std::string>>;

// FNV-1a of the bytes: the stand-in simulation.
uint64_t Fnv(const std::string& bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

// Evaluates each genome at once, its result a function of its bytes
// alone: one in 7 non-viable, one in 11 crashed (a status that says
// nothing about the genome), the rest ok with a fitness in [0, 1).
class GenomeScoring final : public EvaluationService {
 public:
  explicit GenomeScoring(bool follow_genome) : follow_genome_(follow_genome) {}

  void Submit(uint64_t individual, const v1::Genome& genome) override {
    Submit(individual, protocol::SerializeGenome(genome));
  }
  void Submit(uint64_t individual,
              const protocol::SerializedGenome& genome) override {
    queue_.emplace_back(individual, genome.bytes);
    submitted_.insert(individual);
  }
  std::vector<Completion> Poll(int) override {
    std::vector<Completion> done;
    for (const auto& [id, bytes] : queue_) {
      const uint64_t h = Fnv(bytes);
      Completion c;
      c.individual = id;
      c.worker = "stand-in:1";
      c.wall_seconds = 0.5;
      c.isa = "avx2";
      v1::EvaluationResult& r = c.result;
      if (h % 7 == 0) {
        r.set_status(v1::EvaluationResult::NON_VIABLE);
        r.set_reason("no path");
      } else if (h % 11 == 0) {
        r.set_status(v1::EvaluationResult::CRASHED);
        r.set_reason("signal 11");
      } else {
        r.set_status(v1::EvaluationResult::OK);
        r.set_fitness(static_cast<double>(h >> 11) * 0x1p-53);
        r.set_distance(r.fitness());
        r.set_max_overlap(0.0);
      }
      r.set_cells(static_cast<int>(h % 32));
      r.set_steps(100);
      r.set_state_hash(h);
      done.push_back(std::move(c));
    }
    queue_.clear();
    return done;
  }
  void Acknowledge(const std::vector<uint64_t>&) override {}
  size_t pending() const override { return queue_.size(); }
  const Clock& clock() const override { return RealClock(); }
  bool results_follow_genome() const override { return follow_genome_; }

  const std::set<uint64_t>& submitted() const { return submitted_; }

 private:
  bool follow_genome_;
  std::vector<std::pair<uint64_t, std::string>> queue_;
  std::set<uint64_t> submitted_;
};

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
  // generation before of the same genome, the lowest such member's
  // evaluation naming the source (its own source, if reused), unless it
  // says nothing of the genome (crashed; GenerationsTest covers that).
  const Table expected =
      Rows(*reused.store,
           "SELECT o.id, (SELECT CASE WHEN e.status = 'crashed' THEN NULL"
           " ELSE COALESCE(e.reused_from, e.id) END FROM members m"
           " JOIN births p ON p.run_id = m.run_id AND p.id = m.id"
           " JOIN evaluations e ON e.run_id = m.run_id AND e.id = m.id"
           " WHERE m.generation = o.generation - 1 AND p.genome = o.genome"
           " AND e.status <> 'crashed' ORDER BY m.id LIMIT 1)"
           " FROM births o WHERE o.generation > 0 ORDER BY o.id");
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
