// The actuators' work (SoftBody::actuation_work, docs/model.md §10.1).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"
#include "tests/physics/body_source.h"

namespace animat {
namespace {

using testing::AtRest;
using testing::RandomBody;
using testing::Source;

constexpr Integrator kIntegrators[] = {
    Integrator::kSemiImplicitEuler, Integrator::kVelocityVerlet,
    Integrator::kRk4, Integrator::kSsprk3, Integrator::kRalston3};

// Sum over springs of |k (l - L) dL| written out at `state`.
double WorkByHand(const Body& body, const PhysicsParams& params,
                  const MotionState& state, const std::vector<double>& before,
                  const std::vector<double>& after) {
  double work = 0.0;
  for (size_t s = 0; s < body.springs.size(); ++s) {
    const Spring& spring = body.springs[s];
    const double l =
        Length(state.position[spring.b] - state.position[spring.a]);
    work +=
        std::fabs(params.stiffness * (l - after[s]) * (after[s] - before[s]));
  }
  return work;
}

TEST(ActuationWorkTest, AConstantActuationCostsNothingAfterItsFirstStep) {
  Source source(3);
  const Body body = RandomBody(source, 10, 4.0);
  const std::vector<double> expand(body.nodes(), 0.4);
  const std::vector<double> contract(body.nodes(), 0.1);
  for (Integrator integrator : kIntegrators) {
    PhysicsParams params;
    params.integrator = integrator;
    SoftBody soft(body, params);
    MotionState state = AtRest(body);
    const std::vector<double> rest0 = soft.rest_lengths();
    soft.SetActuation(expand, contract);
    const double first =
        WorkByHand(body, params, state, rest0, soft.rest_lengths());
    soft.Step(&state);
    EXPECT_GT(first, 0.0);
    EXPECT_EQ(soft.actuation_work(), first) << IntegratorName(integrator);
    for (int step = 0; step < 50; ++step) {
      soft.SetActuation(expand, contract);  // The same values again.
      soft.Step(&state);
    }
    EXPECT_EQ(soft.actuation_work(), first) << IntegratorName(integrator);
    soft.ResetActuationWork();
    EXPECT_EQ(soft.actuation_work(), 0.0);
  }
}

// Every cell's EXPAND is a (1 + sin(w t)) / 2 for `steps` steps: the work
// summed by SoftBody, and the same sum written out.
struct Driven {
  double work = 0.0;
  double by_hand = 0.0;
};

Driven Drive(double amplitude, double frequency, Integrator integrator) {
  Source source(7);
  const Body body = RandomBody(source, 12, 5.0);
  PhysicsParams params;
  params.integrator = integrator;
  SoftBody soft(body, params);
  MotionState state = AtRest(body);
  const std::vector<double> contract(body.nodes(), 0.0);
  Driven d;
  for (int step = 0; step < 400; ++step) {
    const double e = amplitude * 0.5 * (1.0 + std::sin(frequency * step));
    const std::vector<double> before = soft.rest_lengths();
    soft.SetActuation(std::vector<double>(body.nodes(), e), contract);
    d.by_hand += WorkByHand(body, params, state, before, soft.rest_lengths());
    soft.Step(&state);
  }
  d.work = soft.actuation_work();
  return d;
}

TEST(ActuationWorkTest, WorkIsTheFormulasSumAndGrowsWithAmplitudeAndFrequency) {
  for (Integrator integrator : kIntegrators) {
    SCOPED_TRACE(IntegratorName(integrator));
    const Driven base = Drive(0.5, 0.05, integrator);
    // The sum of |k (l - L) dL| over springs and steps, to its rounding
    // (SoftBody sums each step apart before adding it).
    EXPECT_NEAR(base.work, base.by_hand, 1e-12 * base.by_hand);
    EXPECT_GT(base.work, 0.0);
    // Twice the amplitude: twice each dL and about twice the tension it
    // works against; twice the frequency: twice as much dL per step.
    const double amplitude = Drive(1.0, 0.05, integrator).work / base.work;
    const double frequency = Drive(0.5, 0.1, integrator).work / base.work;
    EXPECT_GT(amplitude, 2.5);
    EXPECT_LT(amplitude, 5.0);
    EXPECT_GT(frequency, 1.5);
    EXPECT_LT(frequency, 5.0);
    EXPECT_EQ(Drive(0.0, 0.05, integrator).work, 0.0);
  }
}

TEST(ActuationWorkTest, ForcesAreTheSameWithAndWithoutAChargedStep) {
  // Charging the work changes no force: the same bits as a body whose
  // charge was already taken.
  Source source(11);
  const Body body = RandomBody(source, 9, 4.0);
  const std::vector<double> expand(body.nodes(), 0.3);
  const std::vector<double> contract(body.nodes(), 0.2);
  SoftBody charged(body, PhysicsParams{});
  SoftBody plain(body, PhysicsParams{});
  charged.SetActuation(expand, contract);
  plain.SetActuation(expand, contract);
  MotionState state = AtRest(body);
  std::vector<Vec2> first, ignored, second;
  plain.ComputeForces(state, &ignored);  // Takes plain's charge.
  charged.ComputeForces(state, &first);
  plain.ComputeForces(state, &second);
  ASSERT_EQ(first.size(), second.size());
  for (size_t i = 0; i < first.size(); ++i) EXPECT_EQ(first[i], second[i]);
  EXPECT_EQ(charged.actuation_work(), plain.actuation_work());
}

}  // namespace
}  // namespace animat
