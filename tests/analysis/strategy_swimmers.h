// Hand-made swimmers of each strategy in the paper (Brainless Bodies,
// "Results and Analysis"), built by construction from its descriptions,
// and a few that follow none. Each takes options that undo one defining
// trait, so a test can check that the label depends on it.
#ifndef ANIMAT_TESTS_ANALYSIS_STRATEGY_SWIMMERS_H_
#define ANIMAT_TESTS_ANALYSIS_STRATEGY_SWIMMERS_H_

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "tests/analysis/prescribed_swimmer.h"

namespace animat::testing {

inline constexpr double kTwoPi = 2 * std::numbers::pi;

// The bodies keep their cells off the boundaries of the end quarters
// (StrategyFeatures::end_taper), where rounding would decide.
//
// Turtle: a core with two flippers on each side, actuated by a wave that runs
// from the back to the front (the front peaks 0.4 of a period after the
// back) and grows towards the back; left and right alike. The flippers
// paddle front to back. Variants undo or change one trait.
enum class TurtleVariant {
  kPaper,
  kWaveToBack,      // The wave runs from the front to the back.
  kSidesAntiphase,  // The right half's actuation half a period after the
                    // left's: alike in activity |Δ(e − c)|, not in e − c.
                    // Its core has no middle row: the flippers beating in
                    // antiphase yaw the body, and a cell on the axis would
                    // fall on a side.
};

inline PrescribedSwimmer Turtle(TurtleVariant variant = TurtleVariant::kPaper) {
  PrescribedSwimmer s;
  const bool antiphase = variant == TurtleVariant::kSidesAntiphase;
  s.body = GridBody(4, 3, 2);
  if (antiphase) {
    std::erase_if(s.body, [](Vec2 cell) { return cell.y == 0; });
  }
  for (double y : {-4.0, 4.0}) {
    s.body.push_back(Vec2(1, y));
    s.body.push_back(Vec2(-1, y));
  }
  const std::vector<Vec2> body = s.body;
  const double period = 80;
  const double direction = variant == TurtleVariant::kWaveToBack ? -1 : 1;
  auto phase = [=](int i) {
    const double side = antiphase && body[i].y < 0 ? 0.5 * kTwoPi : 0.0;
    return direction * 0.4 * kTwoPi * (body[i].x + 3) / 6 + side;
  };
  s.actuation = [=](int i, int step) {
    const double amplitude = 0.25 + 0.1 * (3 - body[i].x) / 6;
    return amplitude * std::cos(kTwoPi * step / period - phase(i));
  };
  s.offset = [=](int i, int step) {
    if (std::abs(body[i].y) < 3) return Vec2();
    return Vec2(0.5 * std::sin(kTwoPi * step / period - phase(i)), 0);
  };
  s.speed = [=](int step) {
    return 0.01 * (1 + 0.3 * std::cos(kTwoPi * step / period));
  };
  return s;
}

// Shark: a body whose actuation is alike front and back but runs from the
// left to the right (the right peaks a quarter period after the left),
// with a tail of two cells at the back that holds its expansion and swings
// from side to side at a high frequency. `still_tail` keeps the tail in
// place.
inline PrescribedSwimmer Shark(bool still_tail = false) {
  PrescribedSwimmer s;
  s.body = GridBody(4, 3, 2);
  const int tail = s.cells();
  s.body.push_back(Vec2(-5, 0));
  s.body.push_back(Vec2(-7, 0));
  const std::vector<Vec2> body = s.body;
  const double period = 40;
  s.actuation = [=](int i, int step) {
    if (i >= tail) return 0.5;
    const double phase = -0.125 * kTwoPi * body[i].y / 2;
    return 0.3 * std::cos(kTwoPi * step / period - phase);
  };
  if (!still_tail) {
    s.offset = [=](int i, int step) {
      if (i < tail) return Vec2();
      const double reach = i == tail ? 0.9 : 1.5;
      return Vec2(0, reach * std::sin(kTwoPi * step / period));
    };
  }
  return s;
}

// Worm: a body elongated across the motion (2 × 8 cells), undulating with
// a wave that runs from the left side to the right (half a period from end
// to end), stronger in the front column than the back; the wave's phase
// wanders at random, so its activity is irregular. `regular` keeps the
// phase still.
inline PrescribedSwimmer Worm(bool regular = false) {
  PrescribedSwimmer s;
  s.body = GridBody(2, 8, 2);
  const std::vector<Vec2> body = s.body;
  const double period = 80;
  auto wander = std::make_shared<std::vector<double>>();
  TestRandom random(12);
  double psi = 0;
  for (int step = 0; step <= s.steps; ++step) {
    wander->push_back(regular ? 0.0 : psi);
    psi += 0.3 * (random.Uniform() - 0.5);
  }
  auto phase = [=](int i, int step) {
    return kTwoPi * step / period - 0.5 * kTwoPi * (7 - body[i].y) / 14 +
           (*wander)[step];
  };
  s.actuation = [=](int i, int step) {
    const double amplitude = body[i].x > 0 ? 0.4 : 0.15;
    return amplitude * std::cos(phase(i, step));
  };
  s.offset = [=](int i, int step) {
    return Vec2(0.4 * std::sin(phase(i, step)), 0);
  };
  return s;
}

// The jellyfish's stroke over one period, at phase u in [0, 1): a slow
// expansion over 0.55 of it, a fast contraction over 0.15, and the
// contracted state held for the rest.
inline double JellyfishStroke(double u) {
  if (u < 0.55) return -0.4 + 0.8 * u / 0.55;
  if (u < 0.7) return 0.4 - 0.8 * (u - 0.55) / 0.15;
  return -0.4;
}

// A stroke that neither holds nor pauses: a slow expansion over 0.8 of
// the period and a fast contraction over the rest.
inline double SawtoothStroke(double u) {
  if (u < 0.8) return -0.4 + 0.8 * u / 0.8;
  return 0.4 - 0.8 * (u - 0.8) / 0.2;
}

enum class JellyfishVariant {
  kPaper,
  kSinusoidal,   // An even sinusoidal stroke, and no coasting.
  kBlunt,        // A rectangular body.
  kWrongStroke,  // The stroke reversed in time: a pointed back that
                 // expands fast and contracts slowly.
  kSteady,       // SawtoothStroke at a steady speed: no state held, no
                 // coasting (the traits of the paper's one individual).
  kDrift,        // No stroke: the body expands slowly over the whole
                 // motion, at a steady speed.
};

// Jellyfish: a bilaterally symmetric body with a blunt front and a pointed
// back whose cells all follow JellyfishStroke together; the body scales
// with it, and the centre of mass surges at each contraction and coasts,
// slowing down, until the next. Variants undo or change one trait.
inline PrescribedSwimmer Jellyfish(
    JellyfishVariant variant = JellyfishVariant::kPaper) {
  PrescribedSwimmer s;
  if (variant == JellyfishVariant::kBlunt) {
    s.body = GridBody(4, 4, 2);
  } else {
    for (int row = 0; row < 6; ++row) {
      const int width = 6 - row;  // 6 cells at the front, 1 at the back.
      for (int k = 0; k < width; ++k) {
        s.body.push_back(Vec2(5 - 2 * row, 2 * k - (width - 1)));
      }
    }
  }
  const std::vector<Vec2> body = s.body;
  const int period = 100;
  const double steps = s.steps;
  auto stroke = [=](int step) {
    const double u = static_cast<double>(step % period) / period;
    switch (variant) {
      case JellyfishVariant::kSinusoidal:
        return 0.4 * std::cos(kTwoPi * u);
      case JellyfishVariant::kWrongStroke:
        return JellyfishStroke(u > 0 ? 1 - u : 0.0);
      case JellyfishVariant::kSteady:
        return SawtoothStroke(u);
      case JellyfishVariant::kDrift:
        return -0.4 + 0.8 * step / steps;
      default:
        return JellyfishStroke(u);
    }
  };
  s.actuation = [=](int i, int step) {
    return (1 + 0.05 * body[i].x / 5) * stroke(step);
  };
  s.offset = [=](int i, int step) { return body[i] * (0.1 * stroke(step)); };
  const bool steady = variant == JellyfishVariant::kSinusoidal ||
                      variant == JellyfishVariant::kSteady ||
                      variant == JellyfishVariant::kDrift;
  s.speed = [=](int step) {
    if (steady) return 0.01;
    const double u = static_cast<double>(step % period) / period;
    if (u < 0.55) return 0.002;
    return 0.002 + 0.05 * std::exp(-(u - 0.55) / 0.08);
  };
  return s;
}

// Other: a square that breathes evenly, every cell in phase, at a steady
// speed.
inline PrescribedSwimmer Breather() {
  PrescribedSwimmer s;
  s.body = GridBody(4, 4, 2);
  const std::vector<Vec2> body = s.body;
  auto stroke = [](int step) { return 0.3 * std::cos(kTwoPi * step / 80.0); };
  s.actuation = [=](int, int step) { return stroke(step); };
  s.offset = [=](int i, int step) { return body[i] * (0.1 * stroke(step)); };
  return s;
}

// Other: a rigid square gliding at a steady speed while each cell's
// actuation is its own smoothed random noise.
inline PrescribedSwimmer Noise(uint64_t seed = 5) {
  PrescribedSwimmer s;
  s.body = GridBody(4, 4, 2);
  const int cells = s.cells();
  auto noise = std::make_shared<std::vector<double>>();
  TestRandom random(seed);
  std::vector<double> level(cells, 0.0);
  for (int step = 0; step <= s.steps; ++step) {
    for (int i = 0; i < cells; ++i) {
      level[i] = 0.9 * level[i] + 0.2 * (random.Uniform() - 0.5);
      noise->push_back(level[i]);
    }
  }
  s.actuation = [=](int i, int step) { return (*noise)[step * cells + i]; };
  return s;
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_ANALYSIS_STRATEGY_SWIMMERS_H_
