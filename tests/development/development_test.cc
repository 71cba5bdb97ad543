// Tests of development from one cell (docs/model.md §4) and of its parameters.
//
// The genomes are made by hand so that the network's behaviour is known:
// UNIFORM excites one unit U (weight 10, so U rises towards tanh(5)), and
// U's internal factor excites the output regions at chosen distances. All
// cells then have the same levels, and the division times follow from the
// dynamics alone. Mechanics are checked on two- and four-cell embryos made
// by dividing with threshold 0 (every cell divides every step).
#include "common/development/development.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "common/base/rng.h"
#include "common/base/vec2.h"
#include "common/development/development_params.h"
#include "common/genome/genome.h"
#include "common/genome/random_genome.h"
#include "common/grn/grn_params.h"
#include "common/grn/network.h"
#include "tests/genome_builder.h"
#include "tests/test_util.h"

namespace animat {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

using testing::MakeElement;

Element Output(OutputChannel channel, double x, double y, int sign = 1) {
  return MakeElement(ElementType::kSOut, sign, x, y, static_cast<int>(channel));
}

// UNIFORM -> unit U (P at the origin, G_INTERNAL at (5, 5)) -> DIVIDE at
// distance `divide_distance` from U's factor (weight 10 exp(-distance)).
// With `steering`, U also drives ROTATE_RIGHT (distance 1), ROTATE_LEFT
// (distance 2) and SIZE (distance 0.5) to different levels, so daughters
// turn and grow.
Genome DividerGenome(double divide_distance, bool steering) {
  Genome g;
  g.elements.push_back(MakeElement(ElementType::kSIn, 1, 0, 0,
                                   static_cast<int>(InputChannel::kUniform)));
  g.elements.push_back(MakeElement(ElementType::kP, 1, 0, 0));
  g.elements.push_back(MakeElement(ElementType::kGInternal, 1, 5, 5));
  g.elements.push_back(Output(OutputChannel::kDivide, 5 + divide_distance, 5));
  if (steering) {
    g.elements.push_back(Output(OutputChannel::kRotateRight, 5, 6));
    g.elements.push_back(Output(OutputChannel::kRotateLeft, 5, 3));
    g.elements.push_back(Output(OutputChannel::kSize, 4.5, 5));
  }
  return g;
}

// DIVIDE driven hard: the first division at step 48, then every 45 steps,
// 32 cells at step 228.
Genome StrongDivider() { return DividerGenome(0.0, true); }
// DIVIDE driven to just above 0.9: division every 58 steps, the fifth
// (16 -> 32 cells) at step 305.
Genome LateDivider() { return DividerGenome(1.0, true); }
// DIVIDE repressed: never divides.
Genome NonDivider() {
  Genome g = DividerGenome(0.0, false);
  g.elements[3].sign = -1;
  return g;
}

// Everything the observer saw at the end of one step.
struct Snapshot {
  int step = 0;
  Embryo embryo;
  std::vector<std::vector<double>> levels;  // [cell][node]
};

struct Trace {
  DevelopmentOutcome outcome;
  std::vector<Snapshot> steps;
  Embryo final_embryo;
};

class DevelopmentTest : public ::testing::Test {
 protected:
  // Develops `genome` with `params`, keeping every step's state.
  Trace Develop(const Genome& genome, const DevelopmentParams& params,
                const SignalParams& signal_params = {}) {
    network_ = Network::Build(genome, GrnParams{});
    Development development(network_, GrnParams{}, params, signal_params);
    Trace trace;
    trace.outcome = development.Run([&](int step, const Development& d) {
      Snapshot s;
      s.step = step;
      s.embryo = d.embryo();
      for (int c = 0; c < d.embryo().cells(); ++c) {
        std::vector<double> row;
        for (int v = 0; v < network_.node_count(); ++v) {
          row.push_back(d.grn().level(c, v));
        }
        s.levels.push_back(row);
      }
      // Every cell's network and field state follows the embryo.
      EXPECT_EQ(d.grn().cells(), d.embryo().cells()) << "step " << step;
      EXPECT_EQ(d.field().cells(), d.embryo().cells()) << "step " << step;
      trace.steps.push_back(std::move(s));
    });
    trace.final_embryo = development.embryo();
    return trace;
  }

  // The channel's value (max over its nodes) in a snapshot.
  double Channel(const Snapshot& s, int cell, OutputChannel channel) const {
    double value = 0.0;
    for (int v : network_.output_nodes(static_cast<int>(channel))) {
      value = std::max(value, s.levels[cell][v]);
    }
    return value;
  }

  // The single unit U of the divider genomes.
  int Unit() const {
    for (int v = 0; v < network_.node_count(); ++v) {
      if (network_.nodes()[v].kind == NodeKind::kUnit) return v;
    }
    return -1;
  }

  Network network_;
};

// Two cells' distance.
double Gap(const Embryo& e, int i, int j) {
  return Length(e.position[j] - e.position[i]);
}

// Empty genome and threshold 0: DIVIDE reads 0 >= 0, so every cell that
// can divides at every step; radii stay 1 and orientations 0.
DevelopmentParams EveryStepDivision(int max_cells, int steps) {
  DevelopmentParams p;
  p.divide_threshold = 0.0;
  p.max_cells = max_cells;
  p.min_cells = 1;
  p.steps = steps;
  p.last_division_step = steps;
  return p;
}

// ---------------------------------------------------------------------------
// The zygote and the network inside development.

TEST_F(DevelopmentTest, ZygoteStartsAtOriginWithRadiusOneAndAngleZero) {
  DevelopmentParams params;
  params.steps = 3;
  params.last_division_step = 3;
  const Trace trace = Develop(NonDivider(), params);
  ASSERT_EQ(trace.steps.size(), 3u);
  for (const Snapshot& s : trace.steps) {
    ASSERT_EQ(s.embryo.cells(), 1);
    EXPECT_EQ(s.embryo.position[0], Vec2(0.0, 0.0));
    EXPECT_EQ(s.embryo.radius[0], 1.0);
    EXPECT_EQ(s.embryo.angle[0], 0.0);
  }
  // Levels start at 0 and the first update already sees UNIFORM = 1:
  // U = 0.05 tanh(10 / 2); DIVIDE, updated from U = 0, stays 0.
  const int unit = Unit();
  ASSERT_GE(unit, 0);
  EXPECT_NEAR(trace.steps[0].levels[0][unit], 0.05 * std::tanh(5.0), 1e-16);
  EXPECT_EQ(Channel(trace.steps[0], 0, OutputChannel::kDivide), 0.0);
  EXPECT_EQ(trace.outcome.steps_run, 3);
  EXPECT_EQ(trace.outcome.divisions, 0);
  EXPECT_EQ(trace.outcome.last_division, -1);
}

TEST_F(DevelopmentTest, MaternalInputsAreReadAtTheCellsPosition) {
  // MATERNAL_1 -> unit: at the origin the input is exp(-10/10), so after
  // the first update U = 0.05 tanh(10 exp(-1) / 2).
  Genome g;
  g.elements.push_back(MakeElement(ElementType::kSIn, 1, 0, 0,
                                   static_cast<int>(InputChannel::kMaternal1)));
  g.elements.push_back(MakeElement(ElementType::kP, 1, 0, 0));
  g.elements.push_back(MakeElement(ElementType::kGInternal, 1, 5, 5));
  // An output downstream, so the unit influences one and is computed.
  g.elements.push_back(Output(OutputChannel::kExpand, 5.5, 5));
  DevelopmentParams params;
  params.steps = 1;
  params.last_division_step = 1;
  params.min_cells = 1;
  const Trace trace = Develop(g, params);
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kOk);
  EXPECT_NEAR(trace.steps[0].levels[0][Unit()],
              0.05 * std::tanh(5.0 * std::exp(-1.0)), 1e-16);
}

TEST_F(DevelopmentTest, MorphogenSignalsUseHistoryAndStartOfStepPositions) {
  // UNIFORM -> unit M, which makes a morphogen; M's signal excites unit R
  // (weight 10 exp(-1)), DIVIDE (10) and ROTATE_RIGHT (10 exp(-1)). Each
  // cell's R follows model §3.1 with the signal of model §5.2 computed from the
  // positions at the start of the step and the history of M in every cell
  // (a daughter's history before her birth being her mother's).
  Genome g;
  g.elements.push_back(MakeElement(ElementType::kSIn, 1, 0, 0,
                                   static_cast<int>(InputChannel::kUniform)));
  g.elements.push_back(MakeElement(ElementType::kP, 1, 0, 0));
  g.elements.push_back(MakeElement(ElementType::kGMorphogen, 1, 5, 5));
  g.elements.push_back(MakeElement(ElementType::kP, 1, 5, 6));
  g.elements.push_back(MakeElement(ElementType::kGInternal, 1, 9, 9));
  g.elements.push_back(Output(OutputChannel::kDivide, 5, 5));
  g.elements.push_back(Output(OutputChannel::kRotateRight, 6, 5));
  // EXPAND (no effect on development) downstream of the receiving unit, so
  // it influences an output and is computed.
  g.elements.push_back(Output(OutputChannel::kExpand, 9.5, 9));
  DevelopmentParams params;
  params.steps = 200;
  params.last_division_step = 200;
  params.max_cells = 8;
  params.min_cells = 1;
  const Trace trace = Develop(g, params);
  ASSERT_EQ(network_.morphogen_count(), 1);
  const int m_node = network_.morphogen_nodes()[0];
  int r_node = -1;
  for (int v = 0; v < network_.node_count(); ++v) {
    if (network_.nodes()[v].kind == NodeKind::kUnit && v != m_node) r_node = v;
  }
  ASSERT_GE(r_node, 0);
  const int divide_node =
      network_.output_nodes(static_cast<int>(OutputChannel::kDivide))[0];
  const double w = network_.Weight(SourceKind::kMorphogen, m_node, r_node);
  ASSERT_NEAR(w, 10.0 * std::exp(-1.0), 1e-12);
  ASSERT_GE(trace.final_embryo.cells(), 4);

  // Mothers: the old cells whose DIVIDE was just reset (a cell that did not
  // divide has DIVIDE > 0 here, the signal being > 0).
  std::vector<int> mother(trace.final_embryo.cells(), -1);
  for (size_t t = 1; t < trace.steps.size(); ++t) {
    const Snapshot& before = trace.steps[t - 1];
    const Snapshot& now = trace.steps[t];
    int q = before.embryo.cells();
    for (int c = 0; c < before.embryo.cells(); ++c) {
      if (now.levels[c][divide_node] == 0.0) {
        ASSERT_LT(q, now.embryo.cells()) << "step " << t;
        mother[q++] = c;
      }
    }
    ASSERT_EQ(q, now.embryo.cells()) << "step " << t;
  }
  // M of cell k entering step t (0 before step 1: levels start at 0).
  auto history = [&](int k, int t) {
    if (t <= 0) return 0.0;
    while (k >= trace.steps[t - 1].embryo.cells()) k = mother[k];
    return trace.steps[t - 1].levels[k][m_node];
  };

  EXPECT_EQ(trace.steps[0].levels[0][r_node], 0.0);  // Signal 0 at step 0.
  int delayed_terms = 0;
  for (int s = 1; s < static_cast<int>(trace.steps.size()); ++s) {
    const Snapshot& before = trace.steps[s - 1];
    const Snapshot& now = trace.steps[s];
    const std::vector<Vec2>& x = before.embryo.position;
    for (int i = 0; i < before.embryo.cells(); ++i) {
      double sum = 0.0;
      for (int k = 0; k < before.embryo.cells(); ++k) {
        const double d = Length(x[k] - x[i]);
        const double kernel = i == k ? 1.0 : std::exp(-d / 3.0);
        const int tau =
            std::min(127, static_cast<int>(std::floor(d / 0.25 + 0.5)));
        if (tau > 0 && history(k, s - tau) != history(k, s)) ++delayed_terms;
        sum += kernel * history(k, s - tau);
      }
      const double signal = std::min(1.0, sum);
      const double r = before.levels[i][r_node];
      const double expected = r + (std::tanh(w * signal / 2.0) - r) * 0.05;
      ASSERT_NEAR(now.levels[i][r_node], std::clamp(expected, 0.0, 1.0), 1e-13)
          << "step " << s << " cell " << i;
    }
  }
  EXPECT_GT(delayed_terms, 100);  // The delays mattered.
}

// ---------------------------------------------------------------------------
// Division.

TEST_F(DevelopmentTest, DivisionPlacesOrientsAndSizesTheDaughter) {
  // No mechanics, so positions are exactly where division put them. Three
  // rounds: 1 -> 2 -> 4 -> 8 cells; the second and third rounds have
  // mothers that are themselves turned, larger daughters.
  DevelopmentParams params;
  params.mechanics_substeps = 0;
  params.steps = 160;
  params.last_division_step = 160;
  const Trace trace = Develop(StrongDivider(), params);
  const int unit = Unit();
  const int divide_node =
      network_.output_nodes(static_cast<int>(OutputChannel::kDivide))[0];
  const double divide_weight =
      network_.Weight(SourceKind::kLevel, unit, divide_node);
  ASSERT_GT(divide_weight, 9.0);
  ASSERT_EQ(trace.steps.back().embryo.cells(), 8);

  int rounds = 0;
  for (size_t t = 1; t < trace.steps.size(); ++t) {
    const Snapshot& before = trace.steps[t - 1];
    const Snapshot& now = trace.steps[t];
    const int old_cells = before.embryo.cells();
    const int born = now.embryo.cells() - old_cells;
    // Which old cells divided: DIVIDE predicted from last step's levels
    // (model §3) reaches 0.9.
    std::vector<int> mothers;
    for (int c = 0; c < old_cells; ++c) {
      const double d = before.levels[c][divide_node];
      const double a = divide_weight * before.levels[c][unit];
      const double predicted = d + (std::tanh(a / 2.0) - d) * 0.05;
      if (predicted >= 0.9) {
        mothers.push_back(c);
      } else {
        // Not a mother: not reset, nothing else changed.
        EXPECT_NEAR(now.levels[c][divide_node], predicted, 1e-14)
            << "step " << now.step << " cell " << c;
      }
    }
    ASSERT_EQ(born, static_cast<int>(mothers.size()))
        << "step " << now.step << ": daughters and cells at >= 0.9 differ";
    if (born == 0) continue;
    ++rounds;
    for (int q = 0; q < born; ++q) {
      const int m = mothers[q];
      const int d = old_cells + q;  // Daughters in the mothers' index order.
      SCOPED_TRACE("step " + std::to_string(now.step) + " mother " +
                   std::to_string(m) + " daughter " + std::to_string(d));
      const double turn = Channel(now, m, OutputChannel::kRotateRight) -
                          Channel(now, m, OutputChannel::kRotateLeft);
      ASSERT_GT(turn, 0.1);  // The test means something.
      const double angle = before.embryo.angle[m] + kTwoPi * turn;
      const double r_m = before.embryo.radius[m];
      EXPECT_NEAR(now.embryo.angle[d], angle, 1e-12);
      EXPECT_NEAR(now.embryo.radius[d],
                  1.0 + 0.5 * Channel(now, m, OutputChannel::kSize), 1e-15);
      EXPECT_NEAR(now.embryo.position[d].x,
                  before.embryo.position[m].x + r_m * std::cos(angle), 1e-12);
      EXPECT_NEAR(now.embryo.position[d].y,
                  before.embryo.position[m].y + r_m * std::sin(angle), 1e-12);
      // The mother keeps her place, radius and orientation.
      EXPECT_EQ(now.embryo.position[m], before.embryo.position[m]);
      EXPECT_EQ(now.embryo.radius[m], r_m);
      EXPECT_EQ(now.embryo.angle[m], before.embryo.angle[m]);
      // DIVIDE reset in both; every other level copied.
      EXPECT_EQ(now.levels[m][divide_node], 0.0);
      EXPECT_EQ(now.levels[d][divide_node], 0.0);
      for (int v = 0; v < network_.node_count(); ++v) {
        if (v != divide_node) {
          EXPECT_EQ(now.levels[d][v], now.levels[m][v]) << "node " << v;
        }
      }
    }
  }
  EXPECT_EQ(rounds, 3);
  EXPECT_EQ(trace.outcome.divisions, 7);
  // Cell 1 is larger than the zygote, so her daughters (cells 3 and 5)
  // were placed at her radius, not at 1.
  EXPECT_GT(trace.steps.back().embryo.radius[1], 1.4);
}

TEST_F(DevelopmentTest,
       FirstDivisionComesAtTheFirstStepDivideReachesThreshold) {
  // With the cap at one cell DIVIDE is never reset: its trajectory tells
  // when it first reaches the threshold.
  DevelopmentParams capped;
  capped.steps = 80;
  capped.last_division_step = 80;
  capped.max_cells = 1;
  capped.min_cells = 1;
  const Trace alone = Develop(StrongDivider(), capped);
  ASSERT_EQ(alone.final_embryo.cells(), 1);
  EXPECT_EQ(alone.outcome.divisions, 0);
  for (double threshold : {0.9, 0.95}) {
    int first_at_threshold = -1;
    for (const Snapshot& s : alone.steps) {
      if (Channel(s, 0, OutputChannel::kDivide) >= threshold) {
        first_at_threshold = s.step;
        break;
      }
    }
    ASSERT_GT(first_at_threshold, 0) << threshold;
    DevelopmentParams params = capped;
    params.max_cells = 32;
    params.divide_threshold = threshold;
    const Trace trace = Develop(StrongDivider(), params);
    EXPECT_EQ(trace.outcome.divisions, 1) << threshold;
    EXPECT_EQ(trace.outcome.last_division, first_at_threshold) << threshold;
    EXPECT_EQ(trace.steps[first_at_threshold - 1].embryo.cells(), 1);
    EXPECT_EQ(trace.steps[first_at_threshold].embryo.cells(), 2);
  }
}

TEST_F(DevelopmentTest, DaughterDoesNotDivideInTheStepSheIsBorn) {
  // Threshold 0: every existing cell divides each step, so the embryo
  // doubles per step (a daughter dividing at birth would give 32 at once).
  DevelopmentParams params = EveryStepDivision(32, 7);
  params.mechanics_substeps = 0;
  const Trace trace = Develop(Genome{}, params);
  const int expected[] = {2, 4, 8, 16, 32, 32, 32};
  for (int s = 0; s < 7; ++s) {
    EXPECT_EQ(trace.steps[s].embryo.cells(), expected[s]) << "step " << s;
  }
  EXPECT_EQ(trace.outcome.divisions, 31);
  EXPECT_EQ(trace.outcome.last_division, 4);
  // Daughter n + q of step s is the daughter of cell q, placed one radius
  // to its right (orientation 0).
  for (int s = 1; s < 5; ++s) {
    const Embryo& e = trace.steps[s].embryo;
    const int n = trace.steps[s - 1].embryo.cells();
    for (int q = 0; q < n; ++q) {
      EXPECT_EQ(e.position[n + q].x, e.position[q].x + 1.0) << s << "," << q;
      EXPECT_EQ(e.position[n + q].y, 0.0);
    }
  }
}

TEST_F(DevelopmentTest, CapBlocksDivisionWithoutResettingDivide) {
  DevelopmentParams params;
  params.max_cells = 2;
  params.min_cells = 2;
  params.steps = 150;
  params.last_division_step = 150;
  const Trace trace = Develop(StrongDivider(), params);
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kOk);
  EXPECT_EQ(trace.final_embryo.cells(), 2);
  EXPECT_EQ(trace.outcome.divisions, 1);
  EXPECT_EQ(trace.outcome.last_division, 48);
  // Both cells are past the threshold from step 93 on and stay there.
  const Snapshot& last = trace.steps.back();
  for (int c = 0; c < 2; ++c) {
    EXPECT_GE(Channel(last, c, OutputChannel::kDivide), 0.9) << c;
    EXPECT_GE(Channel(trace.steps[93], c, OutputChannel::kDivide), 0.9) << c;
  }
}

// ---------------------------------------------------------------------------
// Outcomes.

TEST_F(DevelopmentTest,
       StrongDividerGrowsToExactlyMaxCellsAndBlockedCellsAreNotLate) {
  const Trace trace = Develop(StrongDivider(), DevelopmentParams{});
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kOk)
      << trace.outcome.reason;
  EXPECT_EQ(trace.final_embryo.cells(), 32);
  EXPECT_EQ(trace.outcome.divisions, 31);
  EXPECT_EQ(trace.outcome.last_division, 228);
  EXPECT_EQ(trace.outcome.steps_run, 400);
  ASSERT_EQ(trace.steps.size(), 400u);
  // From step 300 on every cell wants to divide but the cap blocks it:
  // not a division, so not a late one.
  for (int c = 0; c < 32; ++c) {
    EXPECT_GE(Channel(trace.steps[300], c, OutputChannel::kDivide), 0.9) << c;
  }
  // The embryo holds together without coincident or non-finite cells.
  const Embryo& e = trace.final_embryo;
  for (int i = 0; i < 32; ++i) {
    EXPECT_TRUE(IsFinite(e.position[i])) << i;
    for (int j = i + 1; j < 32; ++j)
      EXPECT_GT(Gap(e, i, j), 0.1) << i << "," << j;
  }
}

TEST_F(DevelopmentTest, LateDividerFailsNamingTheStep) {
  const Trace trace = Develop(LateDivider(), DevelopmentParams{});
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kLateDivision);
  EXPECT_GE(trace.outcome.last_division, 300);
  EXPECT_EQ(trace.outcome.last_division, 305);
  EXPECT_TRUE(Contains(trace.outcome.reason,
                       "step " + std::to_string(trace.outcome.last_division)))
      << trace.outcome.reason;
}

TEST_F(DevelopmentTest, LateDividerIsOkWhenDivisionsMayGoOnLonger) {
  DevelopmentParams params;
  params.last_division_step = 400;
  const Trace trace = Develop(LateDivider(), params);
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kOk)
      << trace.outcome.reason;
  EXPECT_TRUE(trace.outcome.reason.empty());
  EXPECT_EQ(trace.final_embryo.cells(), 32);
  EXPECT_EQ(trace.outcome.last_division, 305);
  EXPECT_EQ(trace.outcome.steps_run, 400);
}

TEST_F(DevelopmentTest, DivisionAtExactlyLastDivisionStepIsLate) {
  DevelopmentParams params;
  params.last_division_step = 48;  // The strong divider's first division.
  const Trace trace = Develop(StrongDivider(), params);
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kLateDivision);
  EXPECT_EQ(trace.outcome.last_division, 48);
  EXPECT_TRUE(Contains(trace.outcome.reason, "step 48"))
      << trace.outcome.reason;

  params.last_division_step = 49;
  const Trace later = Develop(StrongDivider(), params);
  EXPECT_EQ(later.outcome.status, DevelopmentStatus::kLateDivision);
  EXPECT_EQ(later.outcome.last_division, 93);  // The second round is late.
}

TEST_F(DevelopmentTest, NonDividerHasTooFewCells) {
  const Trace trace = Develop(NonDivider(), DevelopmentParams{});
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kTooFewCells);
  EXPECT_FALSE(trace.outcome.reason.empty());
  EXPECT_EQ(trace.final_embryo.cells(), 1);
  EXPECT_EQ(trace.outcome.divisions, 0);
  EXPECT_EQ(trace.outcome.steps_run, 400);
}

TEST_F(DevelopmentTest, TwoCellsAreTooFewAndFourAreEnough) {
  DevelopmentParams params;
  params.steps = 60;  // One round of division (step 48).
  params.last_division_step = 60;
  const Trace two = Develop(StrongDivider(), params);
  EXPECT_EQ(two.final_embryo.cells(), 2);
  EXPECT_EQ(two.outcome.status, DevelopmentStatus::kTooFewCells);
  EXPECT_FALSE(two.outcome.reason.empty());

  params.steps = 100;  // Two rounds (steps 48 and 93).
  params.last_division_step = 100;
  const Trace four = Develop(StrongDivider(), params);
  EXPECT_EQ(four.final_embryo.cells(), 4);
  EXPECT_EQ(four.outcome.status, DevelopmentStatus::kOk);
}

TEST_F(DevelopmentTest, LateDivisionTakesPriorityOverTooFewCells) {
  // The first division (step 48) is already late and leaves 2 < 3 cells.
  DevelopmentParams params;
  params.last_division_step = 40;
  const Trace trace = Develop(StrongDivider(), params);
  EXPECT_EQ(trace.outcome.status, DevelopmentStatus::kLateDivision);
  EXPECT_EQ(trace.outcome.last_division, 48);
  EXPECT_LT(trace.final_embryo.cells(), 3);
  EXPECT_TRUE(Contains(trace.outcome.reason, "step 48"))
      << trace.outcome.reason;
}

// ---------------------------------------------------------------------------
// Mechanics.

TEST_F(DevelopmentTest, OverlappingCellsRepelUntilRadiiSumApart) {
  // The daughter is born 1 away from the zygote; s = 2. Each sub-step the
  // overlap shrinks by 1 - 2 k dt = 0.8, five sub-steps per step.
  const Trace trace = Develop(Genome{}, EveryStepDivision(2, 30));
  const Embryo& first = trace.steps[0].embryo;
  ASSERT_EQ(first.cells(), 2);
  EXPECT_NEAR(Gap(first, 0, 1), 2.0 - std::pow(0.8, 5), 1e-12);
  // Equal and opposite forces: the midpoint stays at (0.5, 0).
  EXPECT_NEAR(first.position[0].x + first.position[1].x, 1.0, 1e-12);
  EXPECT_EQ(first.position[0].y, 0.0);
  EXPECT_EQ(first.position[1].y, 0.0);
  EXPECT_LT(first.position[0].x, 0.0);
  EXPECT_GT(first.position[1].x, 1.0);
  for (const Snapshot& s : trace.steps) {
    EXPECT_LE(Gap(s.embryo, 0, 1), 2.0 + 1e-12) << "step " << s.step;
  }
  EXPECT_NEAR(Gap(trace.final_embryo, 0, 1), 2.0, 1e-9);
}

TEST_F(DevelopmentTest, RepulsionUsesBothRadii) {
  // A daughter of radius 1 + 0.5 SIZE settles at 1 + r_d from her mother.
  DevelopmentParams params;
  params.max_cells = 2;
  params.min_cells = 2;
  params.steps = 120;
  params.last_division_step = 120;
  const Trace trace = Develop(StrongDivider(), params);
  ASSERT_EQ(trace.final_embryo.cells(), 2);
  const double r_d = trace.final_embryo.radius[1];
  EXPECT_GT(r_d, 1.4);
  EXPECT_NEAR(Gap(trace.final_embryo, 0, 1), 1.0 + r_d, 1e-9);
}

TEST_F(DevelopmentTest, CellsAtOnePointOneSAttractWithAdhesionStiffness) {
  // One sub-step of dt 0.6 takes the newborn pair from d = 1 to
  // d = 1 + 2 * 0.6 = 2.2 = 1.1 s; the next pulls them together by
  // 2 * 0.3 k (d - s) dt.
  DevelopmentParams params = EveryStepDivision(2, 3);
  params.mechanics_substeps = 1;
  params.mechanics_dt = 0.6;
  const Trace trace = Develop(Genome{}, params);
  const double d0 = Gap(trace.steps[0].embryo, 0, 1);
  ASSERT_NEAR(d0, 2.2, 1e-12);
  const double d1 = Gap(trace.steps[1].embryo, 0, 1);
  EXPECT_NEAR(d1, d0 - 2.0 * 0.3 * 1.0 * (d0 - 2.0) * 0.6, 1e-12);
  EXPECT_LT(d1, d0);
  const double d2 = Gap(trace.steps[2].embryo, 0, 1);
  EXPECT_NEAR(d2, d1 - 2.0 * 0.3 * 1.0 * (d1 - 2.0) * 0.6, 1e-12);
}

TEST_F(DevelopmentTest, AdhesionScalesWithStiffnessAndRatio) {
  DevelopmentParams params = EveryStepDivision(2, 2);
  params.mechanics_substeps = 1;
  params.stiffness = 2.0;
  params.mechanics_dt = 0.3;  // 2 k dt = 1.2: d goes from 1 to 2.2.
  params.adhesion_ratio = 0.5;
  const Trace trace = Develop(Genome{}, params);
  const double d0 = Gap(trace.steps[0].embryo, 0, 1);
  ASSERT_NEAR(d0, 2.2, 1e-12);
  const double d1 = Gap(trace.steps[1].embryo, 0, 1);
  EXPECT_NEAR(d1, d0 - 2.0 * 0.5 * 2.0 * (d0 - 2.0) * 0.3, 1e-12);
}

TEST_F(DevelopmentTest, CellsBeyondOnePointTwoSDoNotInteract) {
  // One sub-step of dt 0.75 takes the pair to d = 2.5 = 1.25 s.
  DevelopmentParams params = EveryStepDivision(2, 5);
  params.mechanics_substeps = 1;
  params.mechanics_dt = 0.75;
  const Trace trace = Develop(Genome{}, params);
  const Embryo& first = trace.steps[0].embryo;
  ASSERT_NEAR(Gap(first, 0, 1), 2.5, 1e-12);
  for (const Snapshot& s : trace.steps) {
    EXPECT_EQ(s.embryo.position[0], first.position[0]) << "step " << s.step;
    EXPECT_EQ(s.embryo.position[1], first.position[1]) << "step " << s.step;
  }
}

TEST_F(DevelopmentTest, CoincidentCellsSeparateAlongTheYoungerOrientation) {
  // One sub-step of dt 1 (all orientations 0, all radii 1):
  //   step 0: 0 at 0, daughter 1 at 1 -> pushed to -1 and 2;
  //   step 1: daughters 2 at 0 and 3 at 3 -> the pairs 0-2 and 1-3 repel,
  //           leaving cells 1 and 2 both exactly at 1;
  //   step 2: (no divisions, the cap is 4) the coincident pair 1-2 is
  //           pushed apart along cell 2's orientation (+x), 2 forward and
  //           1 back, by k s dt = 2 each; every other pair is 3 apart.
  DevelopmentParams params = EveryStepDivision(4, 3);
  params.mechanics_substeps = 1;
  params.mechanics_dt = 1.0;
  const Trace trace = Develop(Genome{}, params);
  const Embryo& met = trace.steps[1].embryo;
  ASSERT_EQ(met.cells(), 4);
  ASSERT_LT(Gap(met, 1, 2), 1e-9);
  EXPECT_EQ(met.position[1], Vec2(1.0, 0.0));
  const Embryo& parted = trace.steps[2].embryo;
  for (int c = 0; c < 4; ++c) EXPECT_TRUE(IsFinite(parted.position[c])) << c;
  EXPECT_NEAR(parted.position[2].x, 3.0, 1e-12);   // Younger: forward.
  EXPECT_NEAR(parted.position[1].x, -1.0, 1e-12);  // Older: back.
  EXPECT_NEAR(parted.position[2].y, 0.0, 1e-12);
  EXPECT_NEAR(parted.position[1].y, 0.0, 1e-12);
  EXPECT_NEAR(parted.position[0].x, -2.0, 1e-12);
  EXPECT_NEAR(parted.position[3].x, 4.0, 1e-12);
}

// ---------------------------------------------------------------------------
// Determinism and robustness.

TEST_F(DevelopmentTest, SameGenomeDevelopsToBitIdenticalEmbryos) {
  RandomStream stream(139, 0, StreamPurpose::kRandomGenome);
  const Genome genome = RandomGenome(stream);
  const Trace a = Develop(genome, DevelopmentParams{});
  const Trace b = Develop(genome, DevelopmentParams{});
  ASSERT_GT(a.final_embryo.cells(), 8);  // A real embryo, not a lone cell.
  ASSERT_EQ(a.final_embryo.cells(), b.final_embryo.cells());
  EXPECT_EQ(a.outcome.status, b.outcome.status);
  EXPECT_EQ(a.outcome.divisions, b.outcome.divisions);
  for (int c = 0; c < a.final_embryo.cells(); ++c) {
    EXPECT_EQ(a.final_embryo.position[c], b.final_embryo.position[c]) << c;
    EXPECT_EQ(a.final_embryo.radius[c], b.final_embryo.radius[c]) << c;
    EXPECT_EQ(a.final_embryo.angle[c], b.final_embryo.angle[c]) << c;
    EXPECT_EQ(a.steps.back().levels[c], b.steps.back().levels[c]) << c;
  }
  // Running without an observer gives the same bits.
  const Network network = Network::Build(genome, GrnParams{});
  Development quiet(network, GrnParams{}, DevelopmentParams{}, SignalParams{});
  quiet.Run();
  ASSERT_EQ(quiet.embryo().cells(), a.final_embryo.cells());
  for (int c = 0; c < a.final_embryo.cells(); ++c) {
    EXPECT_EQ(quiet.embryo().position[c], a.final_embryo.position[c]) << c;
  }
}

TEST_F(DevelopmentTest, RandomGenomesDevelopToFiniteEmbryos) {
  // Seeds chosen to cover a lone cell (1), late division (80, 162) and a
  // full embryo (139); all make morphogens.
  for (uint64_t seed : {1u, 80u, 139u, 162u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    RandomStream stream(seed, 0, StreamPurpose::kRandomGenome);
    const Genome genome = RandomGenome(stream);
    ASSERT_TRUE(ValidateGenome(genome).ok());
    const Trace trace = Develop(genome, DevelopmentParams{});
    EXPECT_NE(trace.outcome.status, DevelopmentStatus::kNumericalFailure)
        << trace.outcome.reason;
    EXPECT_GT(network_.morphogen_count(), 0);
    const Embryo& e = trace.final_embryo;
    EXPECT_GE(e.cells(), 1);
    EXPECT_LE(e.cells(), 32);
    EXPECT_EQ(trace.outcome.divisions, e.cells() - 1);
    for (int c = 0; c < e.cells(); ++c) {
      EXPECT_TRUE(IsFinite(e.position[c])) << c;
      EXPECT_TRUE(std::isfinite(e.angle[c])) << c;
      EXPECT_GE(e.radius[c], 1.0) << c;
      EXPECT_LE(e.radius[c], 1.5) << c;
      for (double l : trace.steps.back().levels[c]) {
        EXPECT_GE(l, 0.0);
        EXPECT_LE(l, 1.0);
      }
    }
  }
}

// ---------------------------------------------------------------------------
// Parameters.

TEST(DevelopmentParamsTest, DefaultsAreModelValues) {
  DevelopmentParams p;
  ASSERT_TRUE(DevelopmentParamsFromProto(v1::DevelopmentConfig{}, &p).ok());
  EXPECT_EQ(p.steps, 400);
  EXPECT_EQ(p.max_cells, 32);
  EXPECT_EQ(p.divide_threshold, 0.9);
  EXPECT_EQ(p.last_division_step, 300);
  EXPECT_EQ(p.min_cells, 3);
  EXPECT_EQ(p.size_gain, 0.5);
  EXPECT_EQ(p.mechanics_substeps, 5);
  EXPECT_EQ(p.stiffness, 1.0);
  EXPECT_EQ(p.adhesion_ratio, 0.3);
  EXPECT_EQ(p.interaction_range, 1.2);
  EXPECT_EQ(p.mechanics_dt, 0.1);
}

TEST(DevelopmentParamsTest, PresentFieldsOverwriteAndRoundTrip) {
  v1::DevelopmentConfig m;
  m.set_steps(200);
  m.set_last_division_step(150);
  m.set_mechanics_dt(0.05);
  DevelopmentParams p;
  ASSERT_TRUE(DevelopmentParamsFromProto(m, &p).ok());
  EXPECT_EQ(p.steps, 200);
  EXPECT_EQ(p.last_division_step, 150);
  EXPECT_EQ(p.mechanics_dt, 0.05);
  EXPECT_EQ(p.max_cells, 32);

  DevelopmentParams q;
  ASSERT_TRUE(DevelopmentParamsFromProto(DevelopmentParamsToProto(p), &q).ok());
  EXPECT_EQ(q.steps, 200);
  EXPECT_EQ(q.last_division_step, 150);
  EXPECT_EQ(q.mechanics_dt, 0.05);
  EXPECT_EQ(q.divide_threshold, 0.9);
  EXPECT_EQ(q.adhesion_ratio, 0.3);
}

TEST(DevelopmentParamsTest, InvalidValuesAreRejectedNamingTheField) {
  testing::FpTrapsOff traps_off;  // NaN is compared on purpose.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    v1::DevelopmentConfig message;
    const char* field;
  };
  std::vector<Case> cases(10);
  cases[0].message.set_steps(0);
  cases[0].field = "development.steps";
  cases[1].message.set_mechanics_dt(0.0);
  cases[1].field = "development.mechanics_dt";
  cases[2].message.set_divide_threshold(nan);
  cases[2].field = "development.divide_threshold";
  cases[3].message.set_stiffness(nan);
  cases[3].field = "development.stiffness";
  cases[4].message.set_max_cells(0);
  cases[4].field = "development.max_cells";
  cases[5].message.set_mechanics_substeps(-1);
  cases[5].field = "development.mechanics_substeps";
  cases[6].message.set_interaction_range(0.0);
  cases[6].field = "development.interaction_range";
  cases[7].message.set_mechanics_dt(nan);
  cases[7].field = "development.mechanics_dt";
  cases[8].message.set_divide_threshold(1.5);
  cases[8].field = "development.divide_threshold";
  cases[9].message.set_adhesion_ratio(-0.1);
  cases[9].field = "development.adhesion_ratio";
  for (const Case& c : cases) {
    DevelopmentParams p;
    p.steps = 123;  // Left alone on error.
    p.last_division_step = 100;
    const Status status = DevelopmentParamsFromProto(c.message, &p);
    EXPECT_FALSE(status.ok()) << c.field;
    EXPECT_EQ(status.code(), StatusCode::kInvalidArgument) << c.field;
    EXPECT_TRUE(Contains(status.message(), c.field)) << status.message();
    EXPECT_EQ(p.steps, 123) << c.field;
  }
}

}  // namespace
}  // namespace animat
