// Property: on random pedigrees, queries::Ancestors and the ancestry and
// line_of_descent views agree with a brute-force search in C++.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "common/base/rng.h"
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

constexpr int kPedigrees = 12;

struct Pedigree {
  int64_t run = 0;
  std::map<uint64_t, std::vector<uint64_t>> parents;  // Id -> parents.
  std::map<uint64_t, int> generation;
  std::map<uint64_t, std::optional<double>> fitness;
};

// A pedigree of 30 to 69 individuals with ids 5, 8, 11, ... (gaps), in
// generations of 6; each takes 0 to 3 parents (repeats allowed) from the
// 12 before it, the first 3 none. Most are evaluated, some fail, some are
// pending; fitness takes few values, so ties are common.
Pedigree MakePedigree(Store& store, int index) {
  RandomStream random(2024, static_cast<uint64_t>(index),
                      StreamPurpose::kSelection);
  Pedigree p;
  p.run = MakeRun(store, static_cast<uint64_t>(index));
  const int n = 30 + static_cast<int>(random.Below(40));
  std::vector<uint64_t> ids;
  std::vector<NewIndividual> batch;
  std::vector<Evaluation> results;
  for (int i = 0; i < n; ++i) {
    const uint64_t id = 5 + 3 * static_cast<uint64_t>(i);
    std::vector<uint64_t> parents;
    if (i >= 3) {
      const uint64_t count = random.Below(4);
      const uint64_t window = std::min<uint64_t>(12, ids.size());
      for (uint64_t k = 0; k < count; ++k) {
        parents.push_back(ids[ids.size() - 1 - random.Below(window)]);
      }
    }
    const int generation = i / 6;
    p.parents[id] = parents;
    p.generation[id] = generation;
    batch.push_back(MakeIndividual(id, generation, parents,
                                   {parents.empty() ? "random" : "sign"}));
    const uint64_t fate = random.Below(10);
    if (fate < 7) {
      const double fitness = 0.5 * static_cast<double>(random.Below(8));
      p.fitness[id] = fitness;
      results.push_back(OkEvaluation(id, fitness));
    } else if (fate < 9) {
      p.fitness[id] = std::nullopt;
      results.push_back(FailedEvaluation(id));
    }
    ids.push_back(id);
  }
  EXPECT_TRUE(store.AddIndividuals(p.run, batch).ok());
  EXPECT_TRUE(store.RecordEvaluations(p.run, results).ok());
  return p;
}

// Breadth-first search: every ancestor of `id` with its shortest distance,
// sorted by (distance, id).
std::vector<std::pair<int, uint64_t>> BruteForceAncestors(const Pedigree& p,
                                                          uint64_t id) {
  std::map<uint64_t, int> distance;
  std::deque<uint64_t> queue = {id};
  std::map<uint64_t, int> depth = {{id, 0}};
  while (!queue.empty()) {
    const uint64_t at = queue.front();
    queue.pop_front();
    for (uint64_t parent : p.parents.at(at)) {
      if (depth.count(parent)) continue;
      depth[parent] = depth[at] + 1;
      distance[parent] = depth[parent];
      queue.push_back(parent);
    }
  }
  std::vector<std::pair<int, uint64_t>> out;
  for (const auto& [ancestor, d] : distance) out.push_back({d, ancestor});
  std::sort(out.begin(), out.end());
  return out;
}

// The best (highest fitness, then lowest id) and its first parents.
std::vector<uint64_t> BruteForceLineOfDescent(const Pedigree& p) {
  std::optional<uint64_t> best;
  for (const auto& [id, fitness] : p.fitness) {
    if (!fitness) continue;
    if (!best || *fitness > *p.fitness.at(*best)) best = id;
  }
  std::vector<uint64_t> line;
  for (std::optional<uint64_t> at = best; at;) {
    line.push_back(*at);
    const std::vector<uint64_t>& parents = p.parents.at(*at);
    at = parents.empty() ? std::nullopt : std::optional<uint64_t>(parents[0]);
  }
  return line;
}

TEST(AncestorsPropertyTest, AgreesWithBruteForceOnRandomPedigrees) {
  std::unique_ptr<Store> store = MemoryStore();
  ASSERT_NE(store, nullptr);
  // All pedigrees share one store and the same ids, so a query that
  // forgets the run shows.
  std::vector<Pedigree> pedigrees;
  for (int k = 0; k < kPedigrees; ++k) {
    pedigrees.push_back(MakePedigree(*store, k));
  }
  int checked = 0, with_ancestors = 0;
  for (const Pedigree& p : pedigrees) {
    // queries::Ancestors for every individual.
    for (const auto& [id, parents] : p.parents) {
      Result<std::vector<Summary>> got = Ancestors(*store, p.run, id);
      ASSERT_TRUE(got.ok()) << got.status().ToString();
      std::vector<std::pair<int, uint64_t>> pairs;
      for (const Summary& s : *got) {
        pairs.push_back({s.distance, s.id});
        EXPECT_EQ(s.generation, p.generation.at(s.id));
      }
      EXPECT_EQ(pairs, BruteForceAncestors(p, id))
          << "run " << p.run << ", individual " << id;
      ++checked;
      if (!pairs.empty()) ++with_ancestors;
    }

    // The ancestry view, for the whole run at once.
    std::vector<std::tuple<uint64_t, int, uint64_t>> expected;
    for (const auto& [id, parents] : p.parents) {
      for (const auto& [d, ancestor] : BruteForceAncestors(p, id)) {
        expected.push_back({id, d, ancestor});
      }
    }
    std::sort(expected.begin(), expected.end());
    std::vector<std::tuple<uint64_t, int, uint64_t>> view;
    for (const std::vector<std::string>& row :
         Rows(*store,
              "SELECT descendant, distance, ancestor FROM ancestry WHERE "
              "run_id = " +
                  std::to_string(p.run) +
                  " ORDER BY descendant, distance, ancestor")) {
      view.push_back(
          {std::stoull(row[0]), std::stoi(row[1]), std::stoull(row[2])});
    }
    EXPECT_EQ(view, expected) << "run " << p.run;

    // The line of descent of the best.
    std::vector<uint64_t> line;
    for (const std::vector<std::string>& row :
         Rows(*store, "SELECT id FROM line_of_descent WHERE run_id = " +
                          std::to_string(p.run) + " ORDER BY step")) {
      line.push_back(std::stoull(row[0]));
    }
    EXPECT_EQ(line, BruteForceLineOfDescent(p)) << "run " << p.run;
  }
  // The pedigrees are not trivial.
  EXPECT_GT(checked, kPedigrees * 30);
  EXPECT_GT(with_ancestors, checked / 2);
}

}  // namespace
}  // namespace animat::lineage
