// Bodies and states for the physics tests.
#ifndef ANIMAT_TESTS_PHYSICS_BODY_SOURCE_H_
#define ANIMAT_TESTS_PHYSICS_BODY_SOURCE_H_

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"

namespace animat::testing {

// Fixed-seed numbers; the double recipe (53 high bits) is written out so the
// cases are the same with every standard library.
class Source {
 public:
  explicit Source(uint64_t seed) : engine_(seed) {}
  double Uniform(double lo, double hi) {
    const double u = static_cast<double>(engine_() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * u;
  }
  int Int(int lo, int hi) {  // In [lo, hi].
    return lo +
           static_cast<int>(engine_() % static_cast<uint64_t>(hi - lo + 1));
  }

 private:
  std::mt19937_64 engine_;
};

inline Body MustBuild(const std::vector<Vec2>& centres) {
  Result<Body> body = BuildBody(centres);
  EXPECT_TRUE(body.ok()) << body.status().ToString();
  return body.ok() ? std::move(body).value() : Body{};
}

// A body built on n random centres in [0, side)^2, no two closer than 0.6
// (cells of radius about 1 end development about 1-2 apart).
inline Body RandomBody(Source& source, int n, double side) {
  std::vector<Vec2> points;
  while (static_cast<int>(points.size()) < n) {
    const Vec2 p{source.Uniform(0, side), source.Uniform(0, side)};
    bool far = true;
    for (const Vec2& q : points) far = far && Length(p - q) >= 0.6;
    if (far) points.push_back(p);
  }
  return MustBuild(points);
}

// Whether a spring joins cells i and j (in either order).
inline bool Joined(const Body& body, int i, int j) {
  for (const Spring& s : body.springs) {
    if ((s.a == i && s.b == j) || (s.a == j && s.b == i)) return true;
  }
  return false;
}

inline MotionState AtRest(const Body& body) {
  MotionState state;
  state.position = body.position;
  state.velocity.assign(body.position.size(), Vec2{});
  return state;
}

// A body, its starting state and a constant actuation.
struct Problem {
  Body body;
  MotionState start;
  std::vector<double> expand, contract;
};

// `steps` simulation steps of `p` under `params`; the final state.
inline MotionState Simulate(const Problem& p, const PhysicsParams& params,
                            int steps) {
  SoftBody body(p.body, params);
  body.SetActuation(p.expand, p.contract);
  MotionState state = p.start;
  for (int s = 0; s < steps; ++s) body.Step(&state);
  return state;
}

// The largest distance between a node's positions in a and in b.
inline double MaxDistance(const MotionState& a, const MotionState& b) {
  double worst = 0.0;
  for (size_t i = 0; i < a.position.size(); ++i) {
    worst = std::max(worst, Length(a.position[i] - b.position[i]));
  }
  return worst;
}

// Expects `bad` to be refused with a message starting with `prefix`, and
// returns the parameters the refused call was given (default ones), for
// the caller to check that they were left unchanged.
inline PhysicsParams ExpectRefused(const v1::PhysicsConfig& bad,
                                   const char* prefix) {
  PhysicsParams unchanged;
  const Status status = PhysicsParamsFromProto(bad, &unchanged);
  EXPECT_FALSE(status.ok()) << prefix;
  EXPECT_EQ(status.message().rfind(prefix, 0), 0u) << status.message();
  return unchanged;
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_PHYSICS_BODY_SOURCE_H_
