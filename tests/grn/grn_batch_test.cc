// Tests of the network dynamics (docs/model.md §3):
//   A_u = sum over u's regions r and all factors f of w(f, r) * c_f,
//   L_u <- clamp(L_u + (tanh(A_u / 2) - L_u) * 0.05, 0, 1),
// synchronous, per cell, with c_f the input value, the source's L or its
// morphogen signal M by the factor's kind.
//
// Expected trajectories are computed here with std::tanh and std::exp from
// the model's formulas, never with the code under test.
#include "common/grn/grn_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <vector>

#include "common/base/rng.h"
#include "common/genome/genome.h"
#include "common/genome/random_genome.h"
#include "common/grn/grn_params.h"
#include "common/grn/network.h"
#include "tests/genome_builder.h"

namespace animat {
namespace {

using Inputs = std::array<double, kInputChannels>;

constexpr double kDt = 0.05;  // model §3.
// Agreement between the code (its own exp and tanh) and std::exp/std::tanh.
constexpr double kTrajectoryTolerance = 1e-14;

using testing::GInt;
using testing::GMor;
using testing::In;
using testing::MakeGenome;
using testing::Out;
using testing::P;

Network Build(const Genome& genome) {
  const Status status = ValidateGenome(genome);
  EXPECT_TRUE(status.ok()) << status.ToString();
  return Network::Build(genome, GrnParams{});
}

// w(f, r) of model §2, written out independently.
double ModelAffinity(const Element& f, const Element& r) {
  const double dx = f.x - r.x;
  const double dy = f.y - r.y;
  const double d = std::sqrt(dx * dx + dy * dy);
  if (!(d < 3.0)) return 0.0;
  return f.sign * r.sign * 10.0 * std::exp(-d);
}

// One update of one level, as model §3.1 writes it.
double ModelStep(double level, double activation) {
  const double x = level + (std::tanh(activation / 2.0) - level) * kDt;
  return std::clamp(x, 0.0, 1.0);
}

constexpr Inputs kUniformOnly = {0.0, 0.0, 0.0, 1.0};

// A model-derived reference for any genome: weights from element pairs with
// the binding rules of §2, levels updated as in §3. Node parsing is taken
// from Network (tested in network_test.cc).
class ReferenceGrn {
 public:
  ReferenceGrn(const Genome& genome, const Network& net) : net_(net) {
    const std::vector<Element>& el = genome.elements;
    for (int u = 0; u < net.node_count(); ++u) {
      for (int r : net.nodes()[u].regions) {
        for (int s = 0; s < net.node_count(); ++s) {
          for (int f : net.nodes()[s].factors) {
            const bool compatible =
                el[f].IsG() || (el[f].type == ElementType::kSIn &&
                                el[r].type == ElementType::kP);
            if (!compatible) continue;
            const double w = ModelAffinity(el[f], el[r]);
            if (w != 0.0) terms_.push_back({u, s, el[f].type, w});
          }
        }
      }
    }
  }

  // levels: per node; signals: per morphogen index.
  void Step(std::vector<double>* levels,
            const std::vector<double>& signals) const {
    std::vector<double> a(levels->size(), 0.0);
    for (const Term& t : terms_) {
      double c = 0.0;
      switch (t.kind) {
        case ElementType::kSIn:
        case ElementType::kGInternal:
          c = (*levels)[t.source];
          break;
        default:
          c = signals[net_.nodes()[t.source].morphogen];
          break;
      }
      a[t.target] += t.w * c;
    }
    for (int u = 0; u < net_.node_count(); ++u) {
      if (net_.nodes()[u].kind == NodeKind::kInput) continue;
      (*levels)[u] = ModelStep((*levels)[u], a[u]);
    }
  }

 private:
  struct Term {
    int target;
    int source;
    ElementType kind;
    double w;
  };
  const Network& net_;
  std::vector<Term> terms_;
};

// The next random genome (10 units), scanning individuals of one seed in
// order from *individual, whose network has input sources and morphogen
// sources, so that freezing and signals matter. False if none of 200 does.
bool NextRandomGenomeWithMorphogens(uint64_t seed, uint64_t* individual,
                                    Genome* genome) {
  for (int tries = 0; tries < 200; ++tries, ++*individual) {
    RandomStream stream(seed, *individual, StreamPurpose::kRandomGenome);
    *genome = RandomGenome(stream);
    const Network net = Network::Build(*genome, GrnParams{});
    bool morphogen_source = false;
    for (const Source& s : net.sources()) {
      morphogen_source |= s.kind == SourceKind::kMorphogen;
    }
    if (morphogen_source && net.input_source_count() > 0) {
      ++*individual;
      return true;
    }
  }
  return false;
}

Inputs CellInputs(int cell) {
  return {0.2 + 0.1 * cell, 0.7 - 0.05 * cell, 0.33 + 0.02 * cell, 1.0};
}

// Signals that mix cells (as endogenous morphogens do), computed from the
// current levels: M_j(i) = min(1, sum_k exp(-|i - k| / 3) L_j(k)).
void SetMixedSignals(GrnBatch* batch) {
  const Network& net = batch->network();
  for (int m = 0; m < net.morphogen_count(); ++m) {
    const double* level = batch->level_row(net.morphogen_nodes()[m]);
    double* signal = batch->signal_row(m);
    for (int i = 0; i < batch->cells(); ++i) {
      double sum = 0.0;
      for (int k = 0; k < batch->cells(); ++k) {
        sum += std::exp(-std::abs(i - k) / 3.0) * level[k];
      }
      signal[i] = std::min(1.0, sum);
    }
  }
}

bool SameLevels(const GrnBatch& a, const GrnBatch& b) {
  if (a.cells() != b.cells()) return false;
  for (int v = 0; v < a.network().node_count(); ++v) {
    if (std::memcmp(a.level_row(v), b.level_row(v),
                    sizeof(double) * a.cells()) != 0) {
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------

TEST(GrnBatchTest, InitialLevelsAndSignalsAreZero) {
  uint64_t individual = 0;
  Genome genome;
  ASSERT_TRUE(NextRandomGenomeWithMorphogens(11, &individual, &genome));
  const Network net = Build(genome);
  GrnBatch batch(net, GrnParams{}, 3);
  EXPECT_EQ(batch.AddCell(), 0);
  EXPECT_EQ(batch.AddCell(), 1);
  EXPECT_EQ(batch.AddCell(), 2);
  EXPECT_EQ(batch.cells(), 3);
  for (int c = 0; c < 3; ++c) {
    for (int v = 0; v < net.node_count(); ++v)
      EXPECT_EQ(batch.level(c, v), 0.0);
    for (int m = 0; m < net.morphogen_count(); ++m) {
      EXPECT_EQ(batch.signal_row(m)[c], 0.0);
    }
    for (int ch = 0; ch < kOutputChannels; ++ch) {
      EXPECT_EQ(batch.Output(c, static_cast<OutputChannel>(ch)), 0.0);
    }
  }
}

TEST(GrnBatchTest, InputNodeHoldsItsInputValue) {
  const Genome genome = MakeGenome(
      {In(InputChannel::kMaternal0, 0, 0), In(InputChannel::kMaternal1, 0, 0.5),
       In(InputChannel::kMaternal2, 0.5, 0), P(0.5, 0.5), GInt(0.5, 0.5),
       In(InputChannel::kUniform, 0, 0), In(InputChannel::kUniform, 20, 20)});
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 6);
  GrnBatch batch(net, GrnParams{}, 2);
  batch.AddCell();
  batch.AddCell();
  const Inputs values = {0.125, 0.25, 0.375, 1.0};
  batch.SetInputs(0, values);
  batch.SetInputs(1, {0.5, 0.0, 0.75, 1.0});
  for (int step = 0; step <= 30; ++step) {
    if (step > 0) batch.Step();
    EXPECT_EQ(batch.level(0, 0), 0.125);
    EXPECT_EQ(batch.level(0, 1), 0.25);
    EXPECT_EQ(batch.level(0, 2), 0.375);
    EXPECT_EQ(batch.level(0, 4), 1.0);
    EXPECT_EQ(batch.level(0, 5), 1.0);
    EXPECT_EQ(batch.level(1, 0), 0.5);
    EXPECT_EQ(batch.level(1, 1), 0.0);
    EXPECT_EQ(batch.level(1, 2), 0.75);
  }
  EXPECT_GT(batch.level(0, 3), 0.0);  // The unit does see the inputs.
}

// One input (UNIFORM = 1) excites one unit; the unit inhibits itself and
// excites a DIVIDE output. Trajectory from the model's formula.
TEST(GrnBatchTest, TrajectoryFollowsModelFormula) {
  const Genome genome =
      MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(1, 2, -1),
                  Out(OutputChannel::kDivide, 1, 2.5, -1)});
  const std::vector<Element>& e = genome.elements;
  const double w_in = 10.0 * std::exp(-1.0);     // d = 1, + +
  const double w_self = -10.0 * std::exp(-2.0);  // d = 2, - +
  const double w_out = 10.0 * std::exp(-0.5);    // d = 0.5, - -
  ASSERT_EQ(ModelAffinity(e[0], e[1]), w_in);
  ASSERT_EQ(ModelAffinity(e[2], e[1]), w_self);
  ASSERT_EQ(ModelAffinity(e[2], e[3]), w_out);

  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 3);  // 0 input, 1 unit, 2 DIVIDE.
  EXPECT_NEAR(net.Weight(SourceKind::kInput, 0, 1), w_in, 1e-13);
  EXPECT_NEAR(net.Weight(SourceKind::kLevel, 1, 1), w_self, 1e-13);
  EXPECT_NEAR(net.Weight(SourceKind::kLevel, 1, 2), w_out, 1e-13);

  GrnBatch batch(net, GrnParams{}, 1);
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  double unit = 0.0, out = 0.0;
  for (int step = 1; step <= 20; ++step) {
    const double a_unit = w_in * 1.0 + w_self * unit;
    const double a_out = w_out * unit;
    unit = ModelStep(unit, a_unit);
    out = ModelStep(out, a_out);
    batch.Step();
    SCOPED_TRACE(::testing::Message() << "step " << step);
    EXPECT_NEAR(batch.level(0, 1), unit, kTrajectoryTolerance);
    EXPECT_NEAR(batch.level(0, 2), out, kTrajectoryTolerance);
    EXPECT_EQ(batch.level(0, 0), 1.0);
    EXPECT_EQ(batch.Output(0, OutputChannel::kDivide), batch.level(0, 2));
  }
  EXPECT_GT(unit, 0.3);
  EXPECT_GT(out, 0.1);
}

// Units A and B regulate each other (A excites B, B inhibits A); an input
// excites A. Every level must come from the previous step's values, in
// either node order.
TEST(GrnBatchTest, UpdateIsSynchronous) {
  const double w_in = 10.0 * std::exp(-1.0);
  const double w_ab = 10.0 * std::exp(-1.0);
  const double w_ba = -10.0 * std::exp(-2.0);
  const Element in = In(InputChannel::kUniform, 0, 0);
  const Element pa = P(1, 0), ga = GInt(10, 0);
  const Element pb = P(10, 1), gb = GInt(1, 2, -1);
  struct Order {
    Genome genome;
    int a, b;
  };
  for (const Order& order : {Order{MakeGenome({in, pa, ga, pb, gb}), 1, 2},
                             Order{MakeGenome({pb, gb, in, pa, ga}), 2, 0}}) {
    SCOPED_TRACE(::testing::Message() << "A is node " << order.a);
    const Network net = Build(order.genome);
    ASSERT_EQ(net.node_count(), 3);
    ASSERT_NEAR(net.Weight(SourceKind::kLevel, order.a, order.b), w_ab, 1e-13);
    ASSERT_NEAR(net.Weight(SourceKind::kLevel, order.b, order.a), w_ba, 1e-13);
    GrnBatch batch(net, GrnParams{}, 1);
    batch.AddCell();
    batch.SetInputs(0, kUniformOnly);

    batch.Step();
    // B's activation used A's previous level, 0: B is still exactly 0.
    EXPECT_EQ(batch.level(0, order.b), 0.0);
    double a = ModelStep(0.0, w_in), b = 0.0;
    EXPECT_NEAR(batch.level(0, order.a), a, kTrajectoryTolerance);
    for (int step = 2; step <= 20; ++step) {
      const double next_a = ModelStep(a, w_in + w_ba * b);
      const double next_b = ModelStep(b, w_ab * a);
      a = next_a;
      b = next_b;
      batch.Step();
      SCOPED_TRACE(::testing::Message() << "step " << step);
      EXPECT_NEAR(batch.level(0, order.a), a, kTrajectoryTolerance);
      EXPECT_NEAR(batch.level(0, order.b), b, kTrajectoryTolerance);
    }
    EXPECT_GT(b, 0.01);
  }
}

TEST(GrnBatchTest, StronglyInhibitedUnitStaysAtExactlyZero) {
  // A = -10 from the start: the proposed level is negative every step.
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(0, 0, -1),
                        GInt(30, 30), Out(OutputChannel::kDivide, 30, 30.5)}));
  GrnBatch batch(net, GrnParams{}, 1);
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  for (int step = 0; step < 100; ++step) {
    batch.Step();
    ASSERT_EQ(batch.level(0, 1), 0.0) << "step " << step;
    ASSERT_EQ(batch.level(0, 2), 0.0) << "step " << step;
  }
}

TEST(GrnBatchTest, LevelDrivenDownStopsAtExactlyZero) {
  // MATERNAL_0 excites the unit with +10, UNIFORM inhibits it with -10.
  const Network net = Build(MakeGenome({In(InputChannel::kMaternal0, 0, 0),
                                        In(InputChannel::kUniform, 20, 20),
                                        P(0, 0), P(20, 20, -1), GInt(40, 40)}));
  ASSERT_EQ(net.node_count(), 3);
  GrnBatch batch(net, GrnParams{}, 1);
  batch.AddCell();
  batch.SetInputs(0, {1.0, 0.0, 0.0, 0.0});
  double expected = 0.0;
  for (int step = 0; step < 40; ++step) {
    expected = ModelStep(expected, 10.0);
    batch.Step();
  }
  ASSERT_NEAR(batch.level(0, 2), expected, kTrajectoryTolerance);
  ASSERT_GT(expected, 0.8);

  batch.SetInputs(0, kUniformOnly);
  int steps_at_zero = 0;
  for (int step = 0; step < 100; ++step) {
    expected = ModelStep(expected, -10.0);
    batch.Step();
    const double level = batch.level(0, 2);
    ASSERT_GE(level, 0.0) << "step " << step;
    EXPECT_NEAR(level, expected, kTrajectoryTolerance);
    if (expected == 0.0) {
      EXPECT_EQ(level, 0.0) << "step " << step;
      ++steps_at_zero;
    }
  }
  EXPECT_GT(steps_at_zero, 50);
}

TEST(GrnBatchTest, StronglyExcitedLevelsStayWithinOne) {
  // A = 30 from the input plus 30 L of self-excitation; the output gets
  // 10 L. Both approach 1 but never leave [0, 1].
  const Network net = Build(
      MakeGenome({In(InputChannel::kUniform, 0, 0), P(0, 0), P(0, 0), P(0, 0),
                  GInt(0, 0), Out(OutputChannel::kExpand, 0, 0)}));
  ASSERT_EQ(net.node_count(), 3);
  GrnBatch batch(net, GrnParams{}, 1);
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  double previous = 0.0;
  for (int step = 0; step < 400; ++step) {
    batch.Step();
    const double unit = batch.level(0, 1);
    const double out = batch.level(0, 2);
    ASSERT_GE(unit, previous) << "step " << step;
    ASSERT_LE(unit, 1.0) << "step " << step;
    ASSERT_GE(out, 0.0) << "step " << step;
    ASSERT_LE(out, 1.0) << "step " << step;
    ASSERT_LE(batch.Output(0, OutputChannel::kExpand), 1.0);
    previous = unit;
  }
  EXPECT_GT(batch.level(0, 1), 0.9999);
  EXPECT_GT(batch.level(0, 2), 0.9999);
}

// Three DIVIDE outputs at distances 0.5, 1.5 and 2.5 from the unit's
// factor, in every genome order: the channel reads the largest level.
TEST(GrnBatchTest, OutputIsMaximumOverTheChannelsNodes) {
  std::array<double, 3> offsets = {0.5, 1.5, 2.5};
  do {
    SCOPED_TRACE(::testing::Message() << "offsets " << offsets[0] << " "
                                      << offsets[1] << " " << offsets[2]);
    const Network net = Build(
        MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 0),
                    Out(OutputChannel::kDivide, 10, offsets[0]),
                    Out(OutputChannel::kDivide, 10, offsets[1]),
                    Out(OutputChannel::kDivide, 10, offsets[2]),
                    Out(OutputChannel::kExpand, 10, -1),
                    Out(OutputChannel::kRotateLeft, 40, 40)}));
    ASSERT_EQ(net.node_count(), 7);
    GrnBatch batch(net, GrnParams{}, 1);
    batch.AddCell();
    batch.SetInputs(0, kUniformOnly);
    for (int step = 0; step < 50; ++step) batch.Step();
    // Nodes: 0 input, 1 unit, 2-4 DIVIDE, 5 EXPAND, 6 ROTATE_LEFT.
    const int nearest =
        2 + static_cast<int>(std::find(offsets.begin(), offsets.end(), 0.5) -
                             offsets.begin());
    const double top = batch.level(0, nearest);
    for (int v = 2; v < 5; ++v) {
      if (v != nearest) {
        ASSERT_LT(batch.level(0, v), top - 0.01);
      }
      ASSERT_GT(batch.level(0, v), 0.0);
    }
    EXPECT_EQ(batch.Output(0, OutputChannel::kDivide), top);
    EXPECT_EQ(batch.Output(0, OutputChannel::kExpand), batch.level(0, 5));
    EXPECT_GT(batch.level(0, 5), 0.0);
    // A channel whose node is never excited, and one with no node.
    EXPECT_EQ(batch.Output(0, OutputChannel::kRotateLeft), 0.0);
    EXPECT_EQ(batch.Output(0, OutputChannel::kSize), 0.0);
    EXPECT_EQ(batch.Output(0, OutputChannel::kContract), 0.0);
  } while (std::next_permutation(offsets.begin(), offsets.end()));
}

TEST(GrnBatchTest, ResetOutputZeroesTheChannelInOneCellOnly) {
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 0),
                        Out(OutputChannel::kDivide, 10, 0.5),
                        Out(OutputChannel::kDivide, 10, 1.5),
                        Out(OutputChannel::kExpand, 10, -1)}));
  ASSERT_EQ(net.node_count(), 5);  // 0 input, 1 unit, 2-3 DIVIDE, 4 EXPAND.
  GrnBatch batch(net, GrnParams{}, 2);
  batch.AddCell();
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  batch.SetInputs(1, kUniformOnly);
  for (int step = 0; step < 40; ++step) batch.Step();
  std::array<std::array<double, 5>, 2> before;
  for (int c = 0; c < 2; ++c) {
    for (int v = 0; v < 5; ++v) before[c][v] = batch.level(c, v);
  }
  ASSERT_GT(before[0][2], 0.1);
  ASSERT_GT(before[0][3], 0.1);

  batch.ResetOutput(0, OutputChannel::kDivide);
  EXPECT_EQ(batch.level(0, 2), 0.0);
  EXPECT_EQ(batch.level(0, 3), 0.0);
  EXPECT_EQ(batch.Output(0, OutputChannel::kDivide), 0.0);
  for (int v : {0, 1, 4}) EXPECT_EQ(batch.level(0, v), before[0][v]);
  for (int v = 0; v < 5; ++v) EXPECT_EQ(batch.level(1, v), before[1][v]);

  // The next step starts the reset nodes from 0.
  const double unit = batch.level(0, 1);
  batch.Step();
  for (int v : {2, 3}) {
    const double w = net.Weight(SourceKind::kLevel, 1, v);
    EXPECT_NEAR(batch.level(0, v), ModelStep(0.0, w * unit),
                kTrajectoryTolerance);
    EXPECT_LT(batch.level(0, v), batch.level(1, v));
  }
}

TEST(GrnBatchTest, CopyCellCopiesLevelsAndSignals) {
  uint64_t individual = 0;
  Genome genome;
  ASSERT_TRUE(NextRandomGenomeWithMorphogens(21, &individual, &genome));
  const Network net = Build(genome);
  GrnBatch batch(net, GrnParams{}, 3);
  batch.AddCell();
  batch.AddCell();
  batch.SetInputs(0, CellInputs(0));
  batch.SetInputs(1, CellInputs(1));
  for (int step = 0; step < 25; ++step) {
    batch.SetOwnSignals();
    batch.Step();
  }
  for (int m = 0; m < net.morphogen_count(); ++m) {
    batch.signal_row(m)[0] = 0.125 * (m + 1);
    batch.signal_row(m)[1] = 0.0;
  }
  std::vector<double> mother;
  for (int v = 0; v < net.node_count(); ++v)
    mother.push_back(batch.level(0, v));

  EXPECT_EQ(batch.CopyCell(0), 2);
  bool any_nonzero = false;
  for (int v = 0; v < net.node_count(); ++v) {
    EXPECT_EQ(batch.level(2, v), mother[v]);
    EXPECT_EQ(batch.level(0, v), mother[v]);
    any_nonzero |= mother[v] != 0.0 && net.nodes()[v].kind != NodeKind::kInput;
  }
  EXPECT_TRUE(any_nonzero);
  for (int m = 0; m < net.morphogen_count(); ++m) {
    EXPECT_EQ(batch.signal_row(m)[2], 0.125 * (m + 1));
  }
  // Mother and daughter then evolve identically (same inputs, levels).
  for (int step = 0; step < 25; ++step) {
    batch.SetOwnSignals();
    batch.Step();
    for (int v = 0; v < net.node_count(); ++v) {
      ASSERT_EQ(batch.level(2, v), batch.level(0, v)) << "step " << step;
    }
  }
}

TEST(GrnBatchTest, CellsEvolveIndependently) {
  uint64_t individual = 0;
  for (int g = 0; g < 3; ++g) {
    Genome genome;
    ASSERT_TRUE(NextRandomGenomeWithMorphogens(31, &individual, &genome));
    SCOPED_TRACE(::testing::Message() << "individual " << individual - 1);
    const Network net = Build(genome);
    constexpr int kCells = 4;
    GrnBatch together(net, GrnParams{}, kCells + 1);
    std::vector<GrnBatch> alone;
    for (int c = 0; c < kCells; ++c) {
      together.AddCell();
      together.SetInputs(c, CellInputs(c));
      alone.emplace_back(net, GrnParams{}, 1);
      alone.back().AddCell();
      alone.back().SetInputs(0, CellInputs(c));
    }
    GrnBatch late(net, GrnParams{}, 1);  // Added to `together` at step 50.
    late.AddCell();
    for (int step = 0; step < 100; ++step) {
      if (step == 50) {
        ASSERT_EQ(together.AddCell(), kCells);
        for (int v = 0; v < net.node_count(); ++v) {
          EXPECT_EQ(together.level(kCells, v), 0.0);
        }
      }
      together.SetOwnSignals();
      together.Step();
      for (GrnBatch& b : alone) {
        b.SetOwnSignals();
        b.Step();
      }
      if (step >= 50) {
        late.SetOwnSignals();
        late.Step();
      }
    }
    for (int v = 0; v < net.node_count(); ++v) {
      for (int c = 0; c < kCells; ++c) {
        EXPECT_EQ(together.level(c, v), alone[c].level(0, v))
            << "cell " << c << " node " << v;
      }
      EXPECT_EQ(together.level(kCells, v), late.level(0, v)) << "node " << v;
    }
    // Different inputs do lead to different states.
    bool differ = false;
    for (int v = 0; v < net.node_count(); ++v) {
      if (net.nodes()[v].kind == NodeKind::kInput) continue;
      differ |= together.level(0, v) != together.level(1, v);
    }
    EXPECT_TRUE(differ);
  }
}

TEST(GrnBatchTest, FreezeInputsIsBitIdenticalToNotFreezing) {
  uint64_t individual = 0;
  for (int g = 0; g < 3; ++g) {
    Genome genome;
    ASSERT_TRUE(NextRandomGenomeWithMorphogens(41, &individual, &genome));
    SCOPED_TRACE(::testing::Message() << "individual " << individual - 1);
    const Network net = Build(genome);
    constexpr int kCells = 5;
    GrnBatch plain(net, GrnParams{}, kCells);
    GrnBatch frozen(net, GrnParams{}, kCells);
    for (int c = 0; c < kCells; ++c) {
      plain.AddCell();
      frozen.AddCell();
      plain.SetInputs(c, CellInputs(c));
      frozen.SetInputs(c, CellInputs(c));
    }
    frozen.FreezeInputs();
    double peak = 0.0;
    for (int step = 0; step < 200; ++step) {
      // Own signals on even steps, cell-mixing signals on odd ones.
      if (step % 2 == 0) {
        plain.SetOwnSignals();
        frozen.SetOwnSignals();
      } else {
        SetMixedSignals(&plain);
        SetMixedSignals(&frozen);
      }
      plain.Step();
      frozen.Step();
      ASSERT_TRUE(SameLevels(plain, frozen)) << "step " << step;
      for (int v = 0; v < net.node_count(); ++v) {
        if (net.nodes()[v].kind == NodeKind::kInput) continue;
        for (int c = 0; c < kCells; ++c) {
          peak = std::max(peak, plain.level(c, v));
        }
      }
    }
    EXPECT_GT(peak, 0.01);  // The network did something.
  }
}

TEST(GrnBatchTest, InputChangesAfterFreezeTakeEffect) {
  uint64_t individual = 0;
  Genome genome;
  ASSERT_TRUE(NextRandomGenomeWithMorphogens(51, &individual, &genome));
  const Network net = Build(genome);
  GrnBatch plain(net, GrnParams{}, 2);
  GrnBatch frozen(net, GrnParams{}, 2);
  for (GrnBatch* b : {&plain, &frozen}) {
    b->AddCell();
    b->SetInputs(0, CellInputs(0));
  }
  frozen.FreezeInputs();
  for (int step = 0; step < 60; ++step) {
    if (step == 20) {
      plain.SetInputs(0, CellInputs(3));
      frozen.SetInputs(0, CellInputs(3));
    }
    if (step == 30) {
      frozen.FreezeInputs();
    }
    if (step == 40) {  // The daughter must see her inputs too.
      plain.CopyCell(0);
      frozen.CopyCell(0);
    }
    plain.SetOwnSignals();
    frozen.SetOwnSignals();
    plain.Step();
    frozen.Step();
    ASSERT_TRUE(SameLevels(plain, frozen)) << "step " << step;
  }
}

TEST(GrnBatchTest, SetOwnSignalsGivesEachCellsMorphogenLevels) {
  uint64_t individual = 0;
  Genome genome;
  ASSERT_TRUE(NextRandomGenomeWithMorphogens(61, &individual, &genome));
  const Network net = Build(genome);
  ASSERT_GT(net.morphogen_count(), 0);
  constexpr int kCells = 3;
  GrnBatch batch(net, GrnParams{}, kCells);
  for (int c = 0; c < kCells; ++c) {
    batch.AddCell();
    batch.SetInputs(c, CellInputs(c));
  }
  bool nonzero = false;
  for (int step = 0; step < 60; ++step) {
    batch.SetOwnSignals();
    for (int m = 0; m < net.morphogen_count(); ++m) {
      const int node = net.morphogen_nodes()[m];
      for (int c = 0; c < kCells; ++c) {
        ASSERT_EQ(batch.signal_row(m)[c], std::min(1.0, batch.level(c, node)))
            << "step " << step << " morphogen " << m << " cell " << c;
        nonzero |= batch.signal_row(m)[c] > 0.0;
      }
    }
    batch.Step();
  }
  EXPECT_TRUE(nonzero);
}

// A unit making only a morphogen: its factor acts with the signal M, not
// with the unit's level L.
TEST(GrnBatchTest, MorphogenFactorActsThroughTheSignal) {
  const Network net =
      Build(MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GMor(10, 0),
                        Out(OutputChannel::kDivide, 10, 1)}));
  ASSERT_EQ(net.node_count(), 3);
  ASSERT_EQ(net.morphogen_nodes(), (std::vector<int>{1}));
  const double w_in = 10.0 * std::exp(-1.0);
  const double w_out = 10.0 * std::exp(-1.0);
  GrnBatch batch(net, GrnParams{}, 1);
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  double unit = 0.0, out = 0.0;
  // Signals left at 0: the output gets nothing although L rises.
  for (int step = 0; step < 30; ++step) {
    batch.Step();
    unit = ModelStep(unit, w_in);
    EXPECT_EQ(batch.level(0, 2), 0.0);
  }
  EXPECT_NEAR(batch.level(0, 1), unit, kTrajectoryTolerance);
  ASSERT_GT(unit, 0.5);
  // A fixed signal of 0.25.
  batch.signal_row(0)[0] = 0.25;
  for (int step = 0; step < 20; ++step) {
    batch.Step();
    unit = ModelStep(unit, w_in);
    out = ModelStep(out, w_out * 0.25);
    EXPECT_NEAR(batch.level(0, 2), out, kTrajectoryTolerance);
  }
  // Own signals: M = min(1, L) of the previous step.
  for (int step = 0; step < 20; ++step) {
    batch.SetOwnSignals();
    batch.Step();
    const double signal = std::min(1.0, unit);
    unit = ModelStep(unit, w_in);
    out = ModelStep(out, w_out * signal);
    EXPECT_NEAR(batch.level(0, 1), unit, kTrajectoryTolerance);
    EXPECT_NEAR(batch.level(0, 2), out, kTrajectoryTolerance);
  }
}

// A unit making both kinds: internal factors act with L, morphogens with M.
TEST(GrnBatchTest, UnitMakingBothKindsUsesLevelAndSignal) {
  const Genome genome =
      MakeGenome({In(InputChannel::kUniform, 0, 0), P(1, 0), GInt(10, 0),
                  GMor(10, 2.5, -1), Out(OutputChannel::kDivide, 10, 1)});
  const std::vector<Element>& e = genome.elements;
  const double w_in = ModelAffinity(e[0], e[1]);
  const double w_int = ModelAffinity(e[2], e[4]);
  const double w_mor = ModelAffinity(e[3], e[4]);
  ASSERT_GT(w_int, 0.0);
  ASSERT_LT(w_mor, 0.0);
  const Network net = Build(genome);
  ASSERT_EQ(net.node_count(), 3);
  GrnBatch batch(net, GrnParams{}, 1);
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  batch.signal_row(0)[0] = 0.25;
  double unit = 0.0, out = 0.0;
  bool clamped = false;
  for (int step = 1; step <= 60; ++step) {
    const double a_out = w_int * unit + w_mor * 0.25;
    clamped |= out + (std::tanh(a_out / 2) - out) * kDt < 0.0;
    unit = ModelStep(unit, w_in);
    out = ModelStep(out, a_out);
    batch.Step();
    SCOPED_TRACE(::testing::Message() << "step " << step);
    EXPECT_NEAR(batch.level(0, 1), unit, kTrajectoryTolerance);
    EXPECT_NEAR(batch.level(0, 2), out, kTrajectoryTolerance);
  }
  EXPECT_TRUE(clamped);  // Early on the morphogen's inhibition wins.
  EXPECT_GT(out, 0.05);  // Later the unit's own level does.
}

// Random genomes against the model reference above: every level of every
// cell over 100 steps, with own signals. Some random networks stay silent
// (their inputs only inhibit), so activity is required of most, not all.
TEST(GrnBatchTest, RandomGenomesFollowTheModelReference) {
  uint64_t individual = 0;
  int active = 0;  // Genomes where some unit or output rises above 0.01.
  for (int g = 0; g < 8; ++g) {
    Genome genome;
    ASSERT_TRUE(NextRandomGenomeWithMorphogens(71, &individual, &genome));
    SCOPED_TRACE(::testing::Message() << "individual " << individual - 1);
    const Network net = Build(genome);
    const ReferenceGrn reference(genome, net);
    constexpr int kCells = 3;
    GrnBatch batch(net, GrnParams{}, kCells);
    std::vector<std::vector<double>> levels(
        kCells, std::vector<double>(net.node_count(), 0.0));
    for (int c = 0; c < kCells; ++c) {
      batch.AddCell();
      batch.SetInputs(c, CellInputs(c));
      for (int ch = 0; ch < kInputChannels; ++ch) {
        for (int v : net.input_nodes(ch)) levels[c][v] = CellInputs(c)[ch];
      }
    }
    double worst = 0.0, peak = 0.0;
    for (int step = 0; step < 100; ++step) {
      batch.SetOwnSignals();
      for (int c = 0; c < kCells; ++c) {
        std::vector<double> signals;
        for (int node : net.morphogen_nodes()) {
          signals.push_back(std::min(1.0, levels[c][node]));
        }
        reference.Step(&levels[c], signals);
      }
      batch.Step();
      for (int c = 0; c < kCells; ++c) {
        for (int v = 0; v < net.node_count(); ++v) {
          worst = std::max(worst, std::fabs(batch.level(c, v) - levels[c][v]));
          if (net.nodes()[v].kind != NodeKind::kInput) {
            peak = std::max(peak, levels[c][v]);
          }
        }
      }
    }
    EXPECT_LT(worst, kTrajectoryTolerance);  // Measured: about 2e-16.
    active += peak > 0.01;
  }
  EXPECT_GE(active, 5);
}

TEST(GrnBatchTest, GenomeWithoutUnitsStepsWithoutError) {
  const Network net = Build(MakeGenome({In(InputChannel::kUniform, 0, 0),
                                        Out(OutputChannel::kDivide, 0, 0),
                                        Out(OutputChannel::kExpand, 5, 5)}));
  ASSERT_EQ(net.node_count(), 3);
  GrnBatch batch(net, GrnParams{}, 1);
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  batch.FreezeInputs();
  for (int step = 0; step < 50; ++step) {
    batch.SetOwnSignals();
    batch.Step();
  }
  EXPECT_EQ(batch.level(0, 0), 1.0);
  EXPECT_EQ(batch.Output(0, OutputChannel::kDivide), 0.0);
  EXPECT_EQ(batch.Output(0, OutputChannel::kExpand), 0.0);
}

TEST(GrnBatchTest, EmptyGenomeStepsWithoutError) {
  const Network net = Build(Genome{});
  GrnBatch batch(net, GrnParams{}, 2);
  batch.AddCell();
  batch.SetInputs(0, kUniformOnly);
  batch.CopyCell(0);
  batch.FreezeInputs();
  for (int step = 0; step < 10; ++step) {
    batch.SetOwnSignals();
    batch.Step();
  }
  EXPECT_EQ(batch.cells(), 2);
  for (int ch = 0; ch < kOutputChannels; ++ch) {
    EXPECT_EQ(batch.Output(1, static_cast<OutputChannel>(ch)), 0.0);
  }
  batch.ResetOutput(0, OutputChannel::kDivide);
}

TEST(NetworkReachTest, NodesReachingFollowsTheBindingGraphBackwards) {
  // UNIFORM -> unit A -> EXPAND; unit B -> DIVIDE; A's factor is far from
  // DIVIDE and B's from EXPAND.
  const Genome genome = MakeGenome({
      In(InputChannel::kUniform, 0.0, 0.0),    // node 0
      P(0.5, 0.0), GInt(5.0, 0.0),             // node 1 (A)
      P(20.0, 20.0), GInt(30.0, 30.0),         // node 2 (B)
      Out(OutputChannel::kExpand, 5.5, 0.0),   // node 3
      Out(OutputChannel::kDivide, 30.5, 30.0)  // node 4
  });
  const Network net = Network::Build(genome, GrnParams{});
  ASSERT_EQ(net.node_count(), 5);
  constexpr OutputChannel kExpand[] = {OutputChannel::kExpand};
  EXPECT_EQ(net.NodesReaching(kExpand),
            (std::vector<bool>{true, true, false, true, false}));
  constexpr OutputChannel kDivide[] = {OutputChannel::kDivide};
  EXPECT_EQ(net.NodesReaching(kDivide),
            (std::vector<bool>{false, false, true, false, true}));
}

template <typename S>
void ExpectRestrictionKeepsNeededNodesBitIdentical(uint64_t seed) {
  uint64_t individual = 0;
  Genome genome;
  ASSERT_TRUE(NextRandomGenomeWithMorphogens(seed, &individual, &genome));
  const Network net = Network::Build(genome, GrnParams{});
  constexpr OutputChannel kMotion[] = {OutputChannel::kExpand,
                                       OutputChannel::kContract};
  const std::vector<bool> needed = net.NodesReaching(kMotion);
  GrnBatchT<S> full(net, GrnParams{}, 3);
  GrnBatchT<S> restricted(net, GrnParams{}, 3);
  for (GrnBatchT<S>* batch : {&full, &restricted}) {
    for (int c = 0; c < 3; ++c) {
      batch->AddCell();
      batch->SetInputs(c, {0.2 * c, 0.5, 0.9 - 0.1 * c, 1.0});
    }
    for (int step = 0; step < 50; ++step) {
      batch->SetOwnSignals();
      batch->Step();
    }
  }
  restricted.Restrict(needed);
  restricted.FreezeInputs();
  std::vector<double> frozen;
  for (int v = 0; v < net.node_count(); ++v)
    frozen.push_back(restricted.level(0, v));
  for (int step = 0; step < 200; ++step) {
    full.SetOwnSignals();
    full.Step();
    restricted.SetOwnSignals();
    restricted.Step();
    for (int v = 0; v < net.node_count(); ++v) {
      for (int c = 0; c < 3; ++c) {
        if (needed[v]) {
          ASSERT_EQ(restricted.level(c, v), full.level(c, v))
              << "node " << v << " step " << step;
        }
      }
      if (!needed[v]) {
        ASSERT_EQ(restricted.level(0, v), frozen[v]) << v;
      }
    }
  }
}

TEST(GrnBatchTest, RestrictionKeepsNeededNodesBitIdenticalInDouble) {
  ExpectRestrictionKeepsNeededNodesBitIdentical<double>(61);
  ExpectRestrictionKeepsNeededNodesBitIdentical<double>(62);
}

TEST(GrnBatchTest, RestrictionKeepsNeededNodesBitIdenticalInFloat) {
  ExpectRestrictionKeepsNeededNodesBitIdentical<float>(63);
}

TEST(GrnBatchTest, FloatTracksDouble) {
  uint64_t individual = 0;
  Genome genome;
  ASSERT_TRUE(NextRandomGenomeWithMorphogens(71, &individual, &genome));
  const Network net = Network::Build(genome, GrnParams{});
  GrnBatchT<double> wide(net, GrnParams{}, 2);
  GrnBatchT<float> narrow(net, GrnParams{}, 2);
  for (int c = 0; c < 2; ++c) {
    wide.AddCell();
    narrow.AddCell();
    wide.SetInputs(c, {0.3, 0.6 * c, 0.1, 1.0});
    narrow.SetInputs(c, {0.3, 0.6 * c, 0.1, 1.0});
  }
  for (int step = 0; step < 400; ++step) {
    wide.SetOwnSignals();
    wide.Step();
    narrow.SetOwnSignals();
    narrow.Step();
  }
  for (int v = 0; v < net.node_count(); ++v) {
    for (int c = 0; c < 2; ++c) {
      EXPECT_NEAR(narrow.level(c, v), wide.level(c, v), 1e-5) << v;
    }
  }
}

}  // namespace
}  // namespace animat
