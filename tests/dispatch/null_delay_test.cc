// The null-evaluation worker's delays (worker/null_delay.h) and the pool
// that sleeps them (worker/evaluation_pool.h).
#include "worker/null_delay.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <set>
#include <thread>
#include <vector>

#include "worker/evaluation_pool.h"

namespace animat {
namespace {

TEST(NullDelayTest, NoneIsZeroAndNoSpreadIsTheMean) {
  EXPECT_EQ(NullDelaySeconds({}, 42), 0);
  EXPECT_EQ(NullDelaySeconds({.mean_ms = 0, .cv = 1}, 42), 0);
  EXPECT_EQ(NullDelaySeconds({.mean_ms = 12.5, .cv = 0}, 42), 0.0125);
  EXPECT_EQ(NullDelaySeconds({.mean_ms = 12.5, .cv = 0}, 7), 0.0125);
}

TEST(NullDelayTest, APureFunctionOfTheGenomeHash) {
  const NullDelay delay{.mean_ms = 20, .cv = 0.5};
  EXPECT_EQ(NullDelaySeconds(delay, 1234), NullDelaySeconds(delay, 1234));
  std::set<double> distinct;
  for (uint64_t h = 0; h < 100; ++h)
    distinct.insert(NullDelaySeconds(delay, h));
  EXPECT_EQ(distinct.size(), 100u);
}

// Over many genomes the delays have the mean and coefficient of variation
// asked for (log-normal; the hashes are fixed, so the sample is too).
TEST(NullDelayTest, MeanAndSpreadAsAskedFor) {
  for (const double cv : {0.1, 0.5, 1.0}) {
    const NullDelay delay{.mean_ms = 10, .cv = cv};
    const int n = 200000;
    double sum = 0, sum2 = 0, least = 1e9;
    for (int i = 0; i < n; ++i) {
      const uint64_t hash = 0x9e3779b97f4a7c15ull * (i + 1);
      const double d = NullDelaySeconds(delay, hash);
      ASSERT_TRUE(std::isfinite(d));
      sum += d;
      sum2 += d * d;
      least = std::min(least, d);
    }
    const double mean = sum / n;
    const double sd = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, 0.010, 0.010 * 0.02) << "cv " << cv;
    EXPECT_NEAR(sd / mean, cv, cv * 0.08) << "cv " << cv;
    EXPECT_GT(least, 0) << "cv " << cv;
  }
}

// A null pool with a delay answers every item NOT_EVALUATED, each after at
// least its delay, measured as its wall time; the threads work at once.
TEST(NullDelayTest, PoolSleepsEachItemsDelayOnItsThreads) {
  const NullDelay delay{.mean_ms = 30, .cv = 0};
  EvaluationPool pool(4, /*null_evaluation=*/true, delay);
  auto config = std::make_shared<const ModelConfig>();
  for (uint64_t id = 1; id <= 4; ++id) {
    v1::WorkItem item;
    item.set_individual(id);
    item.set_genome_hash(id * 77);
    pool.Submit(item, config);
  }
  std::vector<v1::WorkResult> results;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (results.size() < 4 && std::chrono::steady_clock::now() < deadline) {
    for (v1::WorkResult& r : pool.TakeFinished()) results.push_back(r);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_EQ(results.size(), 4u);
  std::set<uint64_t> ids;
  for (const v1::WorkResult& r : results) {
    ids.insert(r.individual());
    EXPECT_EQ(r.genome_hash(), r.individual() * 77);
    EXPECT_EQ(r.result().status(), v1::EvaluationResult::NOT_EVALUATED);
    EXPECT_GE(r.wall_seconds(), 0.030);
  }
  EXPECT_EQ(ids, (std::set<uint64_t>{1, 2, 3, 4}));
  EXPECT_EQ(pool.in_flight(), 0);
}

// Without a delay nothing waits: the items are answered as they come.
TEST(NullDelayTest, PoolWithoutDelayAnswersAtOnce) {
  EvaluationPool pool(1, /*null_evaluation=*/true);
  auto config = std::make_shared<const ModelConfig>();
  v1::WorkItem item;
  item.set_individual(9);
  pool.Submit(item, config);
  const std::vector<v1::WorkResult> results = pool.TakeFinished();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].individual(), 9u);
  EXPECT_EQ(results[0].wall_seconds(), 0);
}

}  // namespace
}  // namespace animat
