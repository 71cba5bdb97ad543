// Tests of the maternal and endogenous morphogens (docs/model.md §5).
//
// Expected values are written from the model's words with libm (std::exp,
// std::cos), not with the project's fast_math, so a wrong constant or a
// wrong formula in the code shows up as a mismatch.
#include "common/development/signals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "common/base/vec2.h"
#include "common/development/development_params.h"
#include "common/genome/genome.h"
#include "common/grn/grn_batch.h"
#include "common/grn/grn_params.h"
#include "common/grn/network.h"
#include "tests/genome_builder.h"
#include "tests/test_util.h"

namespace animat {
namespace {

using testing::MakeElement;

// UNIFORM excites one unit whose only factor is a morphogen (placed far from
// every region, so it regulates nothing): the unit's level rises towards
// tanh(5) in a cell whose UNIFORM input is 1 and stays 0 where it is 0.
Genome MorphogenMakerGenome() {
  Genome g;
  g.elements.push_back(MakeElement(ElementType::kSIn, 1, 0, 0,
                                   static_cast<int>(InputChannel::kUniform)));
  g.elements.push_back(MakeElement(ElementType::kP, 1, 0, 0));
  g.elements.push_back(MakeElement(ElementType::kGMorphogen, 1, 8, 8));
  return g;
}

std::array<double, kInputChannels> Uniform(double value) {
  return {0.0, 0.0, 0.0, value};
}

double Distance(Vec2 a, Vec2 b) {
  const double dx = a.x - b.x;
  const double dy = a.y - b.y;
  return std::sqrt(dx * dx + dy * dy);
}

// ---------------------------------------------------------------------------
// Maternal morphogens.

TEST(MaternalSourcesTest, SitAtDistanceTenAtNinetyPlus120DegreeSteps) {
  const std::array<Vec2, 3> sources = MaternalSources(SignalParams{});
  const double half_sqrt3 = std::sqrt(3.0) / 2.0;
  // 90, 210 and 330 degrees.
  EXPECT_NEAR(sources[0].x, 0.0, 1e-12);
  EXPECT_NEAR(sources[0].y, 10.0, 1e-12);
  EXPECT_NEAR(sources[1].x, -10.0 * half_sqrt3, 1e-12);
  EXPECT_NEAR(sources[1].y, -5.0, 1e-12);
  EXPECT_NEAR(sources[2].x, 10.0 * half_sqrt3, 1e-12);
  EXPECT_NEAR(sources[2].y, -5.0, 1e-12);
  for (int k = 0; k < 3; ++k) {
    const double angle =
        std::numbers::pi / 2.0 + 2.0 * std::numbers::pi / 3.0 * k;
    EXPECT_NEAR(sources[k].x, 10.0 * std::cos(angle), 1e-12) << "k=" << k;
    EXPECT_NEAR(sources[k].y, 10.0 * std::sin(angle), 1e-12) << "k=" << k;
  }
}

TEST(MaternalSourcesTest, DistanceFollowsTheParameter) {
  SignalParams params;
  params.maternal_distance = 4.0;
  const std::array<Vec2, 3> sources = MaternalSources(params);
  EXPECT_NEAR(sources[0].x, 0.0, 1e-12);
  EXPECT_NEAR(sources[0].y, 4.0, 1e-12);
  EXPECT_NEAR(sources[1].x, -2.0 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(sources[1].y, -2.0, 1e-12);
}

TEST(InputValuesTest, MaternalDecayUniformIsOneChemicalIsZero) {
  const SignalParams params;
  const std::array<Vec2, 3> sources = MaternalSources(params);
  const std::vector<Vec2> points = {
      {0.0, 0.0}, {3.0, -4.0}, {-7.5, 2.25}, {0.0, 10.0}, {25.0, 30.0}};
  for (const Vec2& p : points) {
    const std::array<double, kInputChannels> v =
        InputValuesAt(p, sources, params);
    for (int k = 0; k < 3; ++k) {
      const double expected = std::exp(-Distance(p, sources[k]) / 10.0);
      EXPECT_NEAR(v[k], expected, 1e-14 * expected)
          << "k=" << k << " at (" << p.x << ", " << p.y << ")";
    }
    EXPECT_EQ(v[static_cast<int>(InputChannel::kUniform)], 1.0);
    // No chemical source outside guidance's motion (model §10.2).
    EXPECT_EQ(v[static_cast<int>(InputChannel::kChemical)], 0.0);
  }
}

TEST(InputValuesTest, OriginSeesEveryMaternalSourceAtOneOverE) {
  const SignalParams params;
  const std::array<double, kInputChannels> v =
      InputValuesAt({0.0, 0.0}, MaternalSources(params), params);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(v[k], std::exp(-1.0), 1e-15);
}

TEST(InputValuesTest, ValueAtASourceIsOne) {
  const SignalParams params;
  const std::array<Vec2, 3> sources = MaternalSources(params);
  const std::array<double, kInputChannels> v =
      InputValuesAt(sources[1], sources, params);
  EXPECT_NEAR(v[1], 1.0, 1e-15);
  // The others are sqrt(3) * 10 away.
  EXPECT_NEAR(v[0], std::exp(-std::sqrt(3.0)), 1e-14);
  EXPECT_NEAR(v[2], std::exp(-std::sqrt(3.0)), 1e-14);
}

// ---------------------------------------------------------------------------
// Kernel and delays.

class MorphogenGeometryTest : public ::testing::Test {
 protected:
  // Cell 0 at the origin and cell k at distance d_k along x.
  MorphogenField FieldWithDistances(const std::vector<double>& distances,
                                    const SignalParams& params = {}) {
    const int n = static_cast<int>(distances.size()) + 1;
    MorphogenField field(1, n, params);
    std::vector<Vec2> positions = {{0.0, 0.0}};
    for (double d : distances) positions.push_back({d, 0.0});
    for (int i = 0; i < n; ++i) field.AddCell();
    field.SetGeometry(positions);
    return field;
  }
};

TEST_F(MorphogenGeometryTest, KernelIsExpMinusDistanceOverThree) {
  const std::vector<double> distances = {0.5, 1.0, 2.0, 3.0, 7.25, 40.0};
  const MorphogenField field = FieldWithDistances(distances);
  for (size_t k = 0; k < distances.size(); ++k) {
    const double expected = std::exp(-distances[k] / 3.0);
    EXPECT_NEAR(field.kernel(0, k + 1), expected, 1e-14 * expected)
        << "d=" << distances[k];
  }
}

TEST_F(MorphogenGeometryTest, KernelOfACellWithItselfIsOneWithNoDelay) {
  const MorphogenField field = FieldWithDistances({1.0, 2.0, 50.0});
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(field.kernel(i, i), 1.0) << "cell " << i;
    EXPECT_EQ(field.delay(i, i), 0) << "cell " << i;
  }
}

TEST_F(MorphogenGeometryTest, DelayRoundsDistanceOverQuarterToNearestStep) {
  // tau(d) = min(127, floor(d / 0.25 + 0.5)).
  const MorphogenField field = FieldWithDistances(
      {0.12, 0.13, 0.375, 1.0, 2.0, 31.7, 31.875, 100.0, 31.4});
  EXPECT_EQ(field.delay(0, 1), 0);    // floor(0.98)
  EXPECT_EQ(field.delay(0, 2), 1);    // floor(1.02)
  EXPECT_EQ(field.delay(0, 3), 2);    // floor(1.5 + 0.5)
  EXPECT_EQ(field.delay(0, 4), 4);    // floor(4.5)
  EXPECT_EQ(field.delay(0, 5), 8);    // floor(8.5)
  EXPECT_EQ(field.delay(0, 6), 127);  // floor(127.3)
  EXPECT_EQ(field.delay(0, 7), 127);  // floor(128.0), capped
  EXPECT_EQ(field.delay(0, 8), 127);  // floor(400.5), capped
  EXPECT_EQ(field.delay(0, 9), 126);  // floor(126.1)
}

TEST_F(MorphogenGeometryTest, CoincidentCellsHaveKernelOneAndNoDelay) {
  const MorphogenField field = FieldWithDistances({0.0, 1e-12});
  EXPECT_EQ(field.kernel(0, 1), 1.0);
  EXPECT_EQ(field.delay(0, 1), 0);
  EXPECT_NEAR(field.kernel(0, 2), 1.0, 1e-12);
  EXPECT_EQ(field.delay(0, 2), 0);
}

TEST_F(MorphogenGeometryTest, MaxDelayParameterCapsTheDelay) {
  SignalParams params;
  params.max_delay = 5;
  const MorphogenField field = FieldWithDistances({1.0, 100.0}, params);
  EXPECT_EQ(field.delay(0, 1), 4);
  EXPECT_EQ(field.delay(0, 2), 5);
}

TEST(MorphogenFieldTest, KernelAndDelayAreSymmetric) {
  const std::vector<Vec2> positions = {
      {0.0, 0.0}, {1.3, -0.4}, {-2.2, 3.1}, {5.0, 5.0}, {0.1, 0.05}};
  const int n = static_cast<int>(positions.size());
  MorphogenField field(2, n, SignalParams{});
  for (int i = 0; i < n; ++i) field.AddCell();
  field.SetGeometry(positions);
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < n; ++k) {
      EXPECT_EQ(field.kernel(i, k), field.kernel(k, i)) << i << "," << k;
      EXPECT_EQ(field.delay(i, k), field.delay(k, i)) << i << "," << k;
      const double d = Distance(positions[i], positions[k]);
      EXPECT_NEAR(field.kernel(i, k), std::exp(-d / 3.0), 1e-14)
          << i << "," << k;
      const int tau =
          std::min(127, static_cast<int>(std::floor(d / 0.25 + 0.5)));
      EXPECT_EQ(field.delay(i, k), tau) << i << "," << k;
    }
  }
}

// ---------------------------------------------------------------------------
// Delays in action: Record, Apply and Step driven by hand.

class MorphogenDelayTest : public ::testing::Test {
 protected:
  MorphogenDelayTest()
      : genome_(MorphogenMakerGenome()),
        network_(Network::Build(genome_, GrnParams{})) {}

  void SetUp() override {
    ASSERT_EQ(network_.morphogen_count(), 1);
    unit_ = network_.morphogen_nodes()[0];
  }

  // Runs `steps` steps of the cells in `batch`: at each step records the
  // levels entering the step (entering[s][cell]), records them in the
  // field, applies the field and keeps the signals (signal[s][cell]), then
  // steps the network.
  void Run(int steps, MorphogenField* field, GrnBatch* batch,
           int first_step = 0) {
    for (int s = first_step; s < first_step + steps; ++s) {
      std::vector<double> levels, signals;
      for (int c = 0; c < batch->cells(); ++c) {
        levels.push_back(batch->level(c, unit_));
      }
      field->Record(s, *batch);
      field->Apply(s, batch);
      for (int c = 0; c < batch->cells(); ++c) {
        signals.push_back(batch->signal_row(0)[c]);
      }
      entering_.push_back(levels);
      signal_.push_back(signals);
      batch->Step();
    }
  }

  Genome genome_;
  Network network_;
  int unit_ = -1;
  std::vector<std::vector<double>> entering_;  // [step][cell]
  std::vector<std::vector<double>> signal_;    // [step][cell]
};

TEST_F(MorphogenDelayTest, NeighbourSignalIsKernelTimesLevelTauStepsAgo) {
  // Cell 1 makes the morphogen, cell 0 does not; distance 1: tau = 4.
  const double d = 1.0;
  const int tau = 4;
  GrnBatch batch(network_, GrnParams{}, 2);
  MorphogenField field(1, 2, SignalParams{});
  batch.AddCell();
  batch.AddCell();
  field.AddCell();
  field.AddCell();
  batch.SetInputs(0, Uniform(0.0));
  batch.SetInputs(1, Uniform(1.0));
  const std::vector<Vec2> positions = {{0.0, 0.0}, {d, 0.0}};
  field.SetGeometry(positions);
  ASSERT_EQ(field.delay(0, 1), tau);

  const int steps = 40;
  Run(steps, &field, &batch);
  const double kernel = std::exp(-d / 3.0);
  for (int s = 0; s < steps; ++s) {
    ASSERT_EQ(entering_[s][0], 0.0);  // Cell 0 makes nothing.
    const double expected = s - tau >= 0 ? kernel * entering_[s - tau][1] : 0.0;
    EXPECT_NEAR(signal_[s][0], expected, 1e-15) << "step " << s;
    // Self term: tau = 0, the level entering this step.
    EXPECT_DOUBLE_EQ(signal_[s][1], entering_[s][1]) << "step " << s;
  }
  // The test means something: the source was active from step 1 on, yet
  // cell 0 saw nothing until step tau + 1 (a delay one step short would
  // show the level entering step 1 at step tau).
  EXPECT_GT(entering_[1][1], 0.0);
  EXPECT_EQ(signal_[tau][0], 0.0);
  EXPECT_GT(signal_[tau + 1][0], 0.0);
  // And the level entering step s is the one after step s-1's update.
  EXPECT_EQ(entering_[0][1], 0.0);
  EXPECT_NEAR(entering_[1][1], 0.05 * std::tanh(5.0), 1e-15);
}

TEST_F(MorphogenDelayTest, LongestDelayReadsHistory127StepsBack) {
  const double d = 40.0;  // floor(160.5) capped at 127.
  GrnBatch batch(network_, GrnParams{}, 2);
  MorphogenField field(1, 2, SignalParams{});
  batch.AddCell();
  batch.AddCell();
  field.AddCell();
  field.AddCell();
  batch.SetInputs(0, Uniform(0.0));
  batch.SetInputs(1, Uniform(1.0));
  field.SetGeometry(std::vector<Vec2>{{0.0, 0.0}, {0.0, d}});
  ASSERT_EQ(field.delay(0, 1), 127);
  const int steps = 300;  // Wraps the history ring twice.
  Run(steps, &field, &batch);
  const double kernel = std::exp(-d / 3.0);
  for (int s = 0; s < steps; ++s) {
    const double expected = s >= 127 ? kernel * entering_[s - 127][1] : 0.0;
    EXPECT_NEAR(signal_[s][0], expected, 1e-14 * kernel) << "step " << s;
  }
}

TEST_F(MorphogenDelayTest, SumIsClampedToOne) {
  // Both cells make the morphogen; at distance 0.5 (tau = 2) the sum of the
  // own level and the neighbour's reaches 0.98 * (1 + exp(-1/6)) > 1.
  GrnBatch batch(network_, GrnParams{}, 2);
  MorphogenField field(1, 2, SignalParams{});
  batch.AddCell();
  batch.AddCell();
  field.AddCell();
  field.AddCell();
  batch.SetInputs(0, Uniform(1.0));
  batch.SetInputs(1, Uniform(1.0));
  field.SetGeometry(std::vector<Vec2>{{0.0, 0.0}, {0.5, 0.0}});
  ASSERT_EQ(field.delay(0, 1), 2);
  const int steps = 120;
  Run(steps, &field, &batch);
  const double kernel = std::exp(-0.5 / 3.0);
  int clamped = 0;
  for (int s = 0; s < steps; ++s) {
    for (int c = 0; c < 2; ++c) {
      const double sum =
          entering_[s][c] + (s >= 2 ? kernel * entering_[s - 2][1 - c] : 0.0);
      if (sum > 1.0 + 1e-12) {
        EXPECT_EQ(signal_[s][c], 1.0) << "step " << s << " cell " << c;
        ++clamped;
      } else if (sum < 1.0 - 1e-12) {
        EXPECT_NEAR(signal_[s][c], sum, 1e-14) << "step " << s << " cell " << c;
      }
      EXPECT_LE(signal_[s][c], 1.0);
    }
  }
  EXPECT_GT(clamped, 0);
  EXPECT_EQ(signal_[steps - 1][0], 1.0);
}

TEST_F(MorphogenDelayTest, CopiedCellInheritsHerMothersHistory) {
  // Cell 0 (silent) at the origin, cell 1 (the mother, active) at distance
  // 1 (tau 4). At step c cell 2 is copied from cell 1 and placed at
  // distance 2 from cell 0 (tau 8): the signal cell 0 receives from her
  // reads her mother's history from before she existed.
  GrnBatch batch(network_, GrnParams{}, 4);
  MorphogenField field(1, 4, SignalParams{});
  batch.AddCell();
  batch.AddCell();
  field.AddCell();
  field.AddCell();
  batch.SetInputs(0, Uniform(0.0));
  batch.SetInputs(1, Uniform(1.0));
  field.SetGeometry(std::vector<Vec2>{{0.0, 0.0}, {1.0, 0.0}});
  const int copy_step = 30;
  Run(copy_step, &field, &batch);
  ASSERT_EQ(batch.CopyCell(1), 2);
  field.CopyCell(1);
  ASSERT_EQ(field.cells(), 3);
  const std::vector<Vec2> positions = {{0.0, 0.0}, {1.0, 0.0}, {-2.0, 0.0}};
  field.SetGeometry(positions);
  ASSERT_EQ(field.delay(0, 1), 4);
  ASSERT_EQ(field.delay(0, 2), 8);
  ASSERT_EQ(field.delay(1, 2), 12);
  const int more = 20;
  Run(more, &field, &batch, copy_step);
  const double k1 = std::exp(-1.0 / 3.0);
  const double k2 = std::exp(-2.0 / 3.0);
  for (int s = copy_step; s < copy_step + more; ++s) {
    // Before the copy cell 2's history is cell 1's.
    const double l2 =
        s - 8 < copy_step ? entering_[s - 8][1] : entering_[s - 8][2];
    const double expected = std::min(1.0, k1 * entering_[s - 4][1] + k2 * l2);
    EXPECT_NEAR(signal_[s][0], expected, 1e-14) << "step " << s;
    // The daughter's self term and her mother's at distance 3 (tau 12).
    const double from_mother = std::exp(-1.0) * entering_[s - 12][1];
    const double own = entering_[s][2];
    EXPECT_NEAR(signal_[s][2], std::min(1.0, own + from_mother), 1e-14)
        << "step " << s;
  }
  // The test means something: right after the copy the sum is not clamped
  // and the inherited part is far from what an empty history would give.
  EXPECT_LT(signal_[copy_step][0], 1.0);
  EXPECT_GT(signal_[copy_step][0] - k1 * entering_[copy_step - 4][1], 0.1);
}

TEST_F(MorphogenDelayTest, AddedCellStartsWithEmptyHistory) {
  GrnBatch batch(network_, GrnParams{}, 3);
  MorphogenField field(1, 3, SignalParams{});
  batch.AddCell();
  field.AddCell();
  batch.SetInputs(0, Uniform(1.0));
  field.SetGeometry(std::vector<Vec2>{{0.0, 0.0}});
  const int first = 30;
  Run(first, &field, &batch);
  // A fresh cell at distance 2 (tau 8) with input 0: cell 1 reads 0 from
  // her, and she reads cell 0's history (which is not empty).
  batch.AddCell();
  field.AddCell();
  batch.SetInputs(1, Uniform(0.0));
  field.SetGeometry(std::vector<Vec2>{{0.0, 0.0}, {2.0, 0.0}});
  Run(10, &field, &batch, first);
  const double k = std::exp(-2.0 / 3.0);
  for (int s = first; s < first + 10; ++s) {
    EXPECT_DOUBLE_EQ(signal_[s][0], std::min(1.0, entering_[s][0])) << s;
    EXPECT_NEAR(signal_[s][1], k * entering_[s - 8][0], 1e-14) << s;
  }
}

// `count` units, each excited by UNIFORM with its own weight
// 10 exp(-0.3 j) and making one morphogen that binds nothing.
Genome ManyMorphogensGenome(int count) {
  Genome g;
  g.elements.push_back(MakeElement(ElementType::kSIn, 1, 0, 0,
                                   static_cast<int>(InputChannel::kUniform)));
  for (int j = 0; j < count; ++j) {
    g.elements.push_back(MakeElement(ElementType::kP, 1, 0, 0.3 * j));
    g.elements.push_back(
        MakeElement(ElementType::kGMorphogen, 1, 20.0 + 3.0 * j, 20.0));
  }
  return g;
}

class ManyMorphogensTest : public ::testing::TestWithParam<int> {};

TEST_P(ManyMorphogensTest, EverySignalFollowsTheKernelDelaySum) {
  const int count = GetParam();
  const Genome genome = ManyMorphogensGenome(count);
  const Network network = Network::Build(genome, GrnParams{});
  ASSERT_EQ(network.morphogen_count(), count);
  const std::vector<int>& nodes = network.morphogen_nodes();
  // Four cells with different inputs at pairwise different delays.
  const std::vector<Vec2> positions = {
      {0.0, 0.0}, {1.0, 0.0}, {0.0, 0.6}, {-2.5, -1.0}};
  const std::vector<double> uniform = {0.0, 1.0, 0.5, 0.8};
  const int n = static_cast<int>(positions.size());
  GrnBatch batch(network, GrnParams{}, n);
  MorphogenField field(count, n, SignalParams{});
  for (int c = 0; c < n; ++c) {
    batch.AddCell();
    field.AddCell();
    batch.SetInputs(c, Uniform(uniform[c]));
  }
  field.SetGeometry(positions);
  const int steps = 60;
  // entering[s][c][m], signal[s][c][m].
  std::vector<std::vector<std::vector<double>>> entering, signal;
  for (int s = 0; s < steps; ++s) {
    std::vector<std::vector<double>> levels(n), signals(n);
    for (int c = 0; c < n; ++c) {
      for (int m = 0; m < count; ++m) {
        levels[c].push_back(batch.level(c, nodes[m]));
      }
    }
    field.Record(s, batch);
    field.Apply(s, &batch);
    for (int c = 0; c < n; ++c) {
      for (int m = 0; m < count; ++m) {
        signals[c].push_back(batch.signal_row(m)[c]);
      }
    }
    entering.push_back(levels);
    signal.push_back(signals);
    batch.Step();
  }
  int clamped = 0;
  for (int s = 0; s < steps; ++s) {
    for (int i = 0; i < n; ++i) {
      for (int m = 0; m < count; ++m) {
        double sum = 0.0;
        for (int k = 0; k < n; ++k) {
          const double d = Distance(positions[i], positions[k]);
          const int tau = static_cast<int>(std::floor(d / 0.25 + 0.5));
          const double kernel = i == k ? 1.0 : std::exp(-d / 3.0);
          if (s - tau >= 0) sum += kernel * entering[s - tau][k][m];
        }
        if (sum > 1.0) ++clamped;
        EXPECT_NEAR(signal[s][i][m], std::min(1.0, sum), 1e-14)
            << "step " << s << " cell " << i << " morphogen " << m;
      }
    }
  }
  EXPECT_GT(clamped, 0);
  // The morphogens differ (each unit has its own input weight).
  if (count > 1) {
    EXPECT_NE(entering[steps - 1][1][0], entering[steps - 1][1][count - 1]);
  }
}

INSTANTIATE_TEST_SUITE_P(MorphogenCounts, ManyMorphogensTest,
                         ::testing::Values(1, 2, 5, 8, 9));

TEST(MorphogenFieldTest, FieldWithoutCellsOrMorphogensIsHarmless) {
  const Genome genome;  // No nodes at all.
  const Network network = Network::Build(genome, GrnParams{});
  GrnBatch batch(network, GrnParams{}, 2);
  MorphogenField field(0, 2, SignalParams{});
  batch.AddCell();
  field.AddCell();
  field.SetGeometry(std::vector<Vec2>{{0.0, 0.0}});
  field.Record(0, batch);
  field.Apply(0, &batch);
  EXPECT_EQ(field.cells(), 1);
  EXPECT_EQ(field.morphogens(), 0);
}

// ---------------------------------------------------------------------------
// Parameters.

TEST(SignalParamsTest, DefaultsAreModelValues) {
  const SignalParams p;
  EXPECT_EQ(p.maternal_distance, 10.0);
  EXPECT_EQ(p.maternal_length, 10.0);
  EXPECT_EQ(p.kernel_length, 3.0);
  EXPECT_EQ(p.delay_length, 0.25);
  EXPECT_EQ(p.max_delay, 127);
}

TEST(SignalParamsTest, EmptyMessageKeepsDefaults) {
  SignalParams p;
  ASSERT_TRUE(SignalParamsFromProto(v1::SignalConfig{}, &p).ok());
  EXPECT_EQ(p.maternal_distance, 10.0);
  EXPECT_EQ(p.maternal_length, 10.0);
  EXPECT_EQ(p.kernel_length, 3.0);
  EXPECT_EQ(p.delay_length, 0.25);
  EXPECT_EQ(p.max_delay, 127);
}

TEST(SignalParamsTest, PresentFieldsOverwriteAndRoundTrip) {
  v1::SignalConfig m;
  m.set_maternal_distance(7.0);
  m.set_max_delay(0);
  SignalParams p;
  ASSERT_TRUE(SignalParamsFromProto(m, &p).ok());
  EXPECT_EQ(p.maternal_distance, 7.0);
  EXPECT_EQ(p.max_delay, 0);
  EXPECT_EQ(p.kernel_length, 3.0);

  SignalParams q;
  ASSERT_TRUE(SignalParamsFromProto(SignalParamsToProto(p), &q).ok());
  EXPECT_EQ(q.maternal_distance, 7.0);
  EXPECT_EQ(q.maternal_length, 10.0);
  EXPECT_EQ(q.kernel_length, 3.0);
  EXPECT_EQ(q.delay_length, 0.25);
  EXPECT_EQ(q.max_delay, 0);
}

TEST(SignalParamsTest, InvalidValuesAreRejectedNamingTheField) {
  testing::FpTrapsOff traps_off;  // NaN is compared on purpose.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    v1::SignalConfig message;
    const char* field;
  };
  std::vector<Case> cases(7);
  cases[0].message.set_max_delay(128);
  cases[0].field = "signals.max_delay";
  cases[1].message.set_max_delay(-1);
  cases[1].field = "signals.max_delay";
  cases[2].message.set_kernel_length(0.0);
  cases[2].field = "signals.kernel_length";
  cases[3].message.set_kernel_length(nan);
  cases[3].field = "signals.kernel_length";
  cases[4].message.set_delay_length(0.0);
  cases[4].field = "signals.delay_length";
  cases[5].message.set_maternal_length(nan);
  cases[5].field = "signals.maternal_length";
  cases[6].message.set_maternal_distance(-1.0);
  cases[6].field = "signals.maternal_distance";
  for (const Case& c : cases) {
    SignalParams p;
    p.maternal_distance = 2.5;  // Left alone on error.
    const Status status = SignalParamsFromProto(c.message, &p);
    EXPECT_FALSE(status.ok()) << c.field;
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << c.field;
    EXPECT_NE(status.message().find(c.field), std::string::npos)
        << status.message();
    EXPECT_EQ(p.maternal_distance, 2.5) << c.field;
    EXPECT_EQ(p.max_delay, 127) << c.field;
  }
}

// Three morphogen makers excited by UNIFORM with different strengths.
Genome ThreeMorphogenGenome() {
  Genome g;
  g.elements.push_back(MakeElement(ElementType::kSIn, 1, 0, 0,
                                   static_cast<int>(InputChannel::kUniform)));
  for (int m = 0; m < 3; ++m) {
    g.elements.push_back(MakeElement(ElementType::kP, 1, 0.5 * m, 0));
    g.elements.push_back(MakeElement(ElementType::kGMorphogen, 1, 8, 8));
  }
  return g;
}

TEST(MorphogenFieldTest, RestrictionKeepsTheKeptSignalsAndTheirHistory) {
  const Network net = Network::Build(ThreeMorphogenGenome(), GrnParams{});
  ASSERT_EQ(net.morphogen_count(), 3);
  const std::vector<Vec2> positions = {{0, 0}, {1.3, 0.4}, {-2.0, 3.1}};
  GrnBatch grn_full(net, GrnParams{}, 3);
  GrnBatch grn_kept(net, GrnParams{}, 3);
  MorphogenField full(3, 3, SignalParams{});
  MorphogenField kept(3, 3, SignalParams{});
  for (int c = 0; c < 3; ++c) {
    grn_full.AddCell();
    grn_kept.AddCell();
    full.AddCell();
    kept.AddCell();
    grn_full.SetInputs(c, Uniform(0.4 * c + 0.2));
    grn_kept.SetInputs(c, Uniform(0.4 * c + 0.2));
  }
  full.SetGeometry(positions);
  kept.SetGeometry(positions);
  std::vector<double> dropped;  // Morphogen 1's signals when dropped.
  for (int step = 0; step < 300; ++step) {
    if (step == 40) {
      kept.Restrict({0, 2});
      for (int c = 0; c < 3; ++c) dropped.push_back(grn_kept.signal_row(1)[c]);
    }
    full.Record(step, grn_full);
    full.Apply(step, &grn_full);
    grn_full.Step();
    kept.Record(step, grn_kept);
    kept.Apply(step, &grn_kept);
    grn_kept.Step();
    for (int m : {0, 2}) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(grn_kept.signal_row(m)[c], grn_full.signal_row(m)[c])
            << "morphogen " << m << " step " << step;
      }
    }
  }
  EXPECT_EQ(kept.morphogens(), 2);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(grn_kept.signal_row(1)[c], dropped[c]);  // No longer applied.
  }
}

}  // namespace
}  // namespace animat
