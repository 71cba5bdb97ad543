#include "viz/actuation.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "tests/test_util.h"

namespace animat::viz {
namespace {

// A frame of one node per (expand, contract) pair.
v1::MotionFrame Frame(v1::MotionFrame::Phase phase, int step,
                      const std::vector<std::pair<double, double>>& ec) {
  v1::MotionFrame frame;
  frame.set_phase(phase);
  frame.set_step(step);
  for (const auto& [e, c] : ec) {
    frame.add_x(0);
    frame.add_y(0);
    frame.add_expand(e);
    frame.add_contract(c);
  }
  return frame;
}

constexpr v1::MotionFrame::Phase kMotion = v1::MotionFrame::MOTION;
constexpr v1::MotionFrame::Phase kEquilibration =
    v1::MotionFrame::EQUILIBRATION;

TEST(ActuationTest, RisingExpandIsExpandingAndRisingContractIsContracting) {
  const v1::MotionFrame before =
      Frame(kMotion, 10, {{0.2, 0.1}, {0.2, 0.1}, {0.2, 0.1}});
  const v1::MotionFrame after =
      Frame(kMotion, 20, {{0.3, 0.1}, {0.2, 0.2}, {0.2, 0.1}});
  const std::vector<Actuation> got =
      ClassifyActuation(&before, after, kDefaultNeutralRate);
  EXPECT_EQ(got, (std::vector<Actuation>{Actuation::kExpanding,
                                         Actuation::kContracting,
                                         Actuation::kNeutral}));
}

TEST(ActuationTest, FallingLevelsReverseTheColours) {
  const v1::MotionFrame before = Frame(kMotion, 0, {{0.5, 0.5}, {0.5, 0.5}});
  const v1::MotionFrame after = Frame(kMotion, 1, {{0.4, 0.5}, {0.5, 0.4}});
  EXPECT_EQ(
      ClassifyActuation(&before, after, kDefaultNeutralRate),
      (std::vector<Actuation>{Actuation::kContracting, Actuation::kExpanding}));
}

TEST(ActuationTest, EqualChangesOfExpandAndContractAreNeutral) {
  const v1::MotionFrame before = Frame(kMotion, 0, {{0.1, 0.3}});
  const v1::MotionFrame after = Frame(kMotion, 5, {{0.6, 0.8}});
  EXPECT_EQ(ClassifyActuation(&before, after, kDefaultNeutralRate)[0],
            Actuation::kNeutral);
}

TEST(ActuationTest, TheThresholdIsARatePerStep) {
  // A change of 0.02 is 2e-3 per step over 10 steps, 2e-4 over 100.
  const v1::MotionFrame start = Frame(kMotion, 0, {{0.5, 0.0}});
  const v1::MotionFrame soon = Frame(kMotion, 10, {{0.52, 0.0}});
  const v1::MotionFrame late = Frame(kMotion, 100, {{0.52, 0.0}});
  EXPECT_EQ(ClassifyActuation(&start, soon, 1e-3)[0], Actuation::kExpanding);
  EXPECT_EQ(ClassifyActuation(&start, late, 1e-3)[0], Actuation::kNeutral);
  EXPECT_EQ(ClassifyActuation(&start, late, 1e-4)[0], Actuation::kExpanding);
}

TEST(ActuationTest, AcrossPhasesTheMotionStepsCount) {
  const v1::MotionFrame equilibrated = Frame(kEquilibration, 200, {{0.5, 0}});
  const v1::MotionFrame moved = Frame(kMotion, 4, {{0.51, 0}});
  EXPECT_EQ(StepsBetween(equilibrated, moved), 4);
  EXPECT_EQ(StepsBetween(equilibrated, Frame(kMotion, 0, {{0.5, 0}})), 1);
  EXPECT_EQ(StepsBetween(Frame(kMotion, 30, {}), Frame(kMotion, 50, {})), 20);
  // 0.01 over 4 steps is 2.5e-3 per step.
  EXPECT_EQ(ClassifyActuation(&equilibrated, moved, 2.4e-3)[0],
            Actuation::kExpanding);
  EXPECT_EQ(ClassifyActuation(&equilibrated, moved, 2.6e-3)[0],
            Actuation::kNeutral);
}

TEST(ActuationTest, TheFirstFrameIsNeutral) {
  const v1::MotionFrame first = Frame(kEquilibration, 0, {{1, 0}, {0, 1}});
  EXPECT_EQ(ClassifyActuation(nullptr, first, 0),
            std::vector<Actuation>(2, Actuation::kNeutral));
}

TEST(ActuationTest, MissingOrNonFiniteValuesAreNeutral) {
  testing::FpTrapsOff traps;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const v1::MotionFrame before = Frame(kMotion, 0, {{0, 0}, {0, 0}, {0, 0}});
  const v1::MotionFrame after = Frame(kMotion, 1, {{nan, 0}, {inf, 0}, {1, 0}});
  EXPECT_EQ(ClassifyActuation(&before, after, 0),
            (std::vector<Actuation>{Actuation::kNeutral, Actuation::kNeutral,
                                    Actuation::kExpanding}));
  v1::MotionFrame bare = after;
  bare.clear_expand();
  bare.clear_contract();
  EXPECT_EQ(ClassifyActuation(&before, bare, 0),
            std::vector<Actuation>(3, Actuation::kNeutral));
}

TEST(ActuationTest, CodesAreOneLetterEach) {
  EXPECT_EQ(ActuationCode(Actuation::kExpanding), 'e');
  EXPECT_EQ(ActuationCode(Actuation::kContracting), 'c');
  EXPECT_EQ(ActuationCode(Actuation::kNeutral), 'n');
}

}  // namespace
}  // namespace animat::viz
