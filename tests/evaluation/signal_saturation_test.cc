// The signal-saturation measurement (common/evaluation/signal_saturation.h;
// docs/analysis.md, "Signal saturation"): the counting by hand, the
// diameter and delay by hand, and a whole evaluation measured without
// changing its result.
#include "common/evaluation/signal_saturation.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "common/evaluation/evaluator.h"
#include "tests/test_genome.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using testing::LoadGenome;
using testing::ShortConfig;

TEST(SaturationCounterTest, CountsValuesAtTheCapPerMorphogenInNodeOrder) {
  testing::FpTrapsOff traps_off;  // A NaN signal is compared on purpose.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SaturationCounter counter;
  // Rows for units 7 and 3, three cells each.
  const std::vector<int> nodes = {7, 3};
  counter.OnSignals(1, nodes, 3,
                    std::vector<double>{1.0, 0.5, 1.0,  //
                                        0.0, nan, 1.0});
  counter.OnSignals(
      2, nodes, 3,
      std::vector<double>{std::nextafter(1.0, 0.0), 1.0, 0.2, 1.0, 1.0, 1.0});
  ASSERT_EQ(counter.morphogens().size(), 2u);
  const MorphogenSaturation& three = counter.morphogens()[0];
  const MorphogenSaturation& seven = counter.morphogens()[1];
  EXPECT_EQ(three.node, 3);
  EXPECT_EQ(three.values, 6);
  EXPECT_EQ(three.capped, 4);  // NaN is not at the cap.
  EXPECT_EQ(seven.node, 7);
  EXPECT_EQ(seven.values, 6);
  EXPECT_EQ(seven.capped, 3);  // Just below 1 is not.
  EXPECT_DOUBLE_EQ(seven.share(), 0.5);
  EXPECT_EQ(counter.steps(), 2);
  EXPECT_EQ(MorphogenSaturation{}.share(), 0.0);
}

TEST(SignalSaturationTest, DiameterIsTheWidestPair) {
  EXPECT_EQ(Diameter(std::vector<Vec2>{}), 0.0);
  EXPECT_EQ(Diameter(std::vector<Vec2>{{4.0, 4.0}}), 0.0);
  EXPECT_EQ(Diameter(std::vector<Vec2>{{0.0, 0.0}, {1.0, 1.0}, {3.0, 4.0}}),
            5.0);
}

TEST(SignalSaturationTest, KernelSumsIncludeTheCellItself) {
  SignalParams params;
  params.kernel_length = 2.0;
  const std::vector<double> sums =
      KernelSums(std::vector<Vec2>{{0.0, 0.0}, {2.0, 0.0}, {8.0, 0.0}}, params);
  ASSERT_EQ(sums.size(), 3u);
  EXPECT_DOUBLE_EQ(sums[0], 1.0 + std::exp(-1.0) + std::exp(-4.0));
  EXPECT_DOUBLE_EQ(sums[1], std::exp(-1.0) + 1.0 + std::exp(-3.0));
  EXPECT_DOUBLE_EQ(sums[2], std::exp(-4.0) + std::exp(-3.0) + 1.0);
}

TEST(SignalSaturationTest, DelayIsTheModelsTau) {
  const SignalParams params;  // delay_length 0.25, max_delay 127.
  EXPECT_EQ(SignalDelay(0.0, params), 0);
  EXPECT_EQ(SignalDelay(0.12, params), 0);   // floor(0.98)
  EXPECT_EQ(SignalDelay(0.125, params), 1);  // floor(1.0)
  EXPECT_EQ(SignalDelay(5.0, params), 20);
  EXPECT_EQ(SignalDelay(100.0, params), 127);
  SignalParams short_history = params;
  short_history.max_delay = 10;
  EXPECT_EQ(SignalDelay(5.0, short_history), 10);
}

// seed-1198 (the benchmark genome): 32 cells, four morphogens of its own.
TEST(SignalSaturationTest, MeasuresEveryMorphogenOverEveryMotionStep) {
  const Genome genome = LoadGenome("seed-1198.json");
  const ModelConfig config = ShortConfig();
  Result<SignalSaturation> s = MeasureSignalSaturation(genome, config);
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->motion_steps, 300);
  EXPECT_GT(s->cells, 2);
  ASSERT_FALSE(s->morphogens.empty());
  for (size_t k = 0; k < s->morphogens.size(); ++k) {
    const MorphogenSaturation& m = s->morphogens[k];
    if (k > 0) {
      EXPECT_LT(s->morphogens[k - 1].node, m.node);
    }
    EXPECT_EQ(m.values, 300LL * s->cells);
    EXPECT_LE(m.capped, m.values);
  }
  EXPECT_GT(s->diameter, 0.0);
  EXPECT_EQ(s->crossing_steps, SignalDelay(s->diameter, config.signals));
  EXPECT_GE(s->kernel_sum_mean, 1.0);
  EXPECT_GE(s->kernel_sum_max, s->kernel_sum_mean);
  EXPECT_LE(s->kernel_sum_max, s->cells);
}

TEST(SignalSaturationTest, WatchingChangesNoBitOfTheEvaluation) {
  const Genome genome = LoadGenome("seed-1198.json");
  const ModelConfig config = ShortConfig();
  const EvaluationResult alone = Evaluate(genome, config);
  SaturationCounter counter;
  const EvaluationResult watched = Evaluate(genome, config, &counter);
  ASSERT_EQ(alone.status, EvalStatus::kOk);
  EXPECT_EQ(watched.status, alone.status);
  EXPECT_EQ(std::bit_cast<uint64_t>(*watched.fitness),
            std::bit_cast<uint64_t>(*alone.fitness));
  EXPECT_EQ(watched.state_hash, alone.state_hash);
  EXPECT_EQ(counter.steps(), 300);
}

TEST(SignalSaturationTest, AFailedAnimatHasNothingToMeasure) {
  Result<SignalSaturation> s = MeasureSignalSaturation(
      LoadGenome("seed-2-too-few-cells.json"), ShortConfig());
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("too_few_cells"), std::string::npos)
      << s.status().message();
}

}  // namespace
}  // namespace animat
