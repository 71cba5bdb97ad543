// Tests of the Bullet backend: without contacts it agrees with the native
// semi-implicit Euler; with contacts cells collide as spheres; the config
// rejects combinations it cannot run; a full evaluation runs on it.
#include "common/physics/bullet/bullet_stepper.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "common/base/vec2.h"
#include "common/body/body.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/physics/physics_params.h"
#include "common/physics/soft_body.h"
#include "tests/test_genome.h"
#include "tests/test_util.h"

namespace animat {
namespace {

// Fixed-seed numbers, the same with every standard library.
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

// A body built on n random centres in [0, side)^2, no two closer than 0.6,
// with random radii in [0.5, 1.2].
Body RandomBody(Source& source, int n, double side) {
  std::vector<Vec2> points;
  std::vector<double> radii;
  while (static_cast<int>(points.size()) < n) {
    const Vec2 p{source.Uniform(0, side), source.Uniform(0, side)};
    bool far = true;
    for (const Vec2& q : points) far = far && Length(p - q) >= 0.6;
    if (far) {
      points.push_back(p);
      radii.push_back(source.Uniform(0.5, 1.2));
    }
  }
  Result<Body> body = BuildBody(points, radii);
  EXPECT_TRUE(body.ok()) << body.status().ToString();
  return body.ok() ? std::move(body).value() : Body{};
}

MotionState AtRest(const Body& body) {
  MotionState state;
  state.position = body.position;
  state.velocity.assign(body.position.size(), Vec2{});
  return state;
}

// Bullet without contacts, where it must agree with the native
// semi-implicit Euler.
PhysicsParams BulletParams() {
  PhysicsParams params;
  params.backend = PhysicsBackend::kBullet;
  params.integrator = Integrator::kSemiImplicitEuler;  // Bullet's own.
  params.contact_rule = ContactRule::kNone;
  return params;
}

struct Agreement {
  double position = 0.0;  // Largest |x_bullet - x_native| / scale.
  double velocity = 0.0;  // Largest |v_bullet - v_native| / scale.
};

// Runs the native integrator and Bullet side by side on random bodies with
// random initial velocities and a random actuation that changes every 50
// steps; every 7 steps both states' velocities are damped (as equilibration
// does between steps). Returns the worst relative disagreement; positions
// are scaled by the body's extent (at least 1), velocities by the largest
// native speed (at least 1).
Agreement CompareWithNative(const PhysicsParams& params, uint64_t seed,
                            int trials, int steps) {
  Source source(seed);
  Agreement worst;
  for (int trial = 0; trial < trials; ++trial) {
    const Body body = RandomBody(source, source.Int(3, 32), 8.0);
    const int n = body.nodes();
    SoftBody native(body, params);
    SoftBody forces(body, params);
    std::unique_ptr<MotionStepper> bullet = MakeBulletStepper(&forces, body);
    MotionState a = AtRest(body);
    for (Vec2& v : a.velocity) {
      v = {source.Uniform(-0.5, 0.5), source.Uniform(-0.5, 0.5)};
    }
    MotionState b = a;
    std::vector<double> expand(n), contract(n);
    for (int step = 0; step < steps; ++step) {
      if (step % 50 == 0) {
        for (int i = 0; i < n; ++i) {
          expand[i] = source.Uniform(0, 1);
          contract[i] = source.Uniform(0, 1);
        }
        native.SetActuation(expand, contract);
        forces.SetActuation(expand, contract);
      }
      if (step % 7 == 6) {
        for (Vec2& v : a.velocity) v = v * 0.9;
        for (Vec2& v : b.velocity) v = v * 0.9;
      }
      native.Step(&a);
      bullet->Step(&b);
    }
    EXPECT_EQ(CheckState(a, 1e6), "") << "trial " << trial;
    double extent = 1.0, speed = 1.0;
    for (int i = 0; i < n; ++i) {
      extent = std::max(extent, Length(a.position[i] - a.position[0]));
      speed = std::max(speed, Length(a.velocity[i]));
    }
    for (int i = 0; i < n; ++i) {
      worst.position = std::max(worst.position,
                                Length(b.position[i] - a.position[i]) / extent);
      worst.velocity = std::max(worst.velocity,
                                Length(b.velocity[i] - a.velocity[i]) / speed);
    }
  }
  std::printf("  worst relative difference: position %.3g, velocity %.3g\n",
              worst.position, worst.velocity);
  return worst;
}

// ---------------------------------------------------------------------------
// Without contacts: the native semi-implicit Euler, to rounding.
//
// Bullet computes v + (F (1/m)) h where we compute v + F / m h; x + v h is
// the same expression in both. With m = 1 the operations are identical and
// the measured difference is exactly 0; with m = 1.7, 1/m is rounded, each
// step differs by about an ulp of the velocity change, and after 500 steps
// the measured worst difference is 6e-14 (positions) and 2e-13
// (velocities) relative. The bound 1e-9 leaves room for other builds of
// Bullet (an FMA-contracting compiler, say) yet catches any real
// difference: updating x before v, for one, is off by F/m h^2 ~ 1e-3 F in
// the first step.

TEST(BulletStepperTest, AgreesWithNativeSemiImplicitEuler) {
  const Agreement worst = CompareWithNative(BulletParams(), 7, 20, 500);
  EXPECT_LE(worst.position, 1e-9);
  EXPECT_LE(worst.velocity, 1e-9);
}

TEST(BulletStepperTest, AgreesWithNativeWithSubsteps) {
  PhysicsParams params = BulletParams();
  params.substeps = 3;
  const Agreement worst = CompareWithNative(params, 8, 20, 500);
  EXPECT_LE(worst.position, 1e-9);
  EXPECT_LE(worst.velocity, 1e-9);
}

TEST(BulletStepperTest, AgreesWithNativeWithAMassThatIsNotOne) {
  PhysicsParams params = BulletParams();
  params.mass = 1.7;
  const Agreement worst = CompareWithNative(params, 9, 20, 500);
  EXPECT_LE(worst.position, 1e-9);
  EXPECT_LE(worst.velocity, 1e-9);
}

// ---------------------------------------------------------------------------
// Contacts.

// Two cells of radii 1 and 0.5, `start` apart on the x axis, joined by a
// damped spring of rest length 0.01 that drives them together. Returns the
// smallest and the final signed distance x_b - x_a over 600 steps
// (negative: they passed each other).
struct Approach {
  double closest = 0.0;
  double final = 0.0;
};
Approach RunApproach(ContactRule rule, double start) {
  Body body;
  body.position = {{0, 0}, {start, 0}};
  body.radius = {1.0, 0.5};
  body.springs.push_back({0, 1, 0.01});
  PhysicsParams params = BulletParams();
  params.contact_rule = rule;
  SoftBody forces(body, params);
  std::unique_ptr<MotionStepper> bullet = MakeBulletStepper(&forces, body);
  MotionState state = AtRest(body);
  Approach result{start, start};
  for (int step = 0; step < 600; ++step) {
    bullet->Step(&state);
    const double d = state.position[1].x - state.position[0].x;
    result.closest = std::min(result.closest, d);
    result.final = d;
    EXPECT_EQ(state.position[0].y, 0.0);  // Nothing pushes out of line.
    EXPECT_EQ(state.position[1].y, 0.0);
  }
  return result;
}

TEST(BulletStepperTest, WithContactsCellsStopAtTouching) {
  constexpr double kTouching = 1.0 + 0.5;
  // Bullet finds a sphere-sphere contact only once the spheres overlap, so
  // at impact they sink in by up to one step's approach before the contact
  // pushes them apart. From 6 apart they meet at a closing speed of about
  // 26 (1.3 per step); from 2 apart at about 3 (0.16 per step).
  const Approach fast = RunApproach(ContactRule::kAll, 6.0);
  const Approach slow = RunApproach(ContactRule::kAll, 2.0);
  std::printf("  from 6: closest %.6g, final %.9g (touching at 1.5)\n",
              fast.closest, fast.final);
  std::printf("  from 2: closest %.6g, final %.9g\n", slow.closest, slow.final);
  EXPECT_GT(fast.closest, 0.5 * kTouching);  // Measured: 1.12.
  EXPECT_GT(slow.closest, 0.9 * kTouching);  // Measured: 1.45.
  // At rest they touch: the spring's pull is held by the contact.
  EXPECT_NEAR(fast.final, kTouching, 0.01 * kTouching);
  EXPECT_NEAR(slow.final, kTouching, 0.01 * kTouching);
}

TEST(BulletStepperTest, WithoutContactsCellsPassThroughEachOther) {
  const Approach a = RunApproach(ContactRule::kNone, 6.0);
  std::printf("  no contacts: closest %.6g, final %.6g\n", a.closest, a.final);
  EXPECT_LT(a.closest, 0.0);           // Passed each other.
  EXPECT_LT(std::fabs(a.final), 0.5);  // Overlapping at the end.
}

TEST(BulletStepperTest, UnjoinedRuleFiltersOutTheCellsOfASpring) {
  // The two cells are joined by the spring: under UNJOINED Bullet makes no
  // contact for them, exactly as without contacts.
  const Approach none = RunApproach(ContactRule::kNone, 6.0);
  const Approach unjoined = RunApproach(ContactRule::kUnjoined, 6.0);
  EXPECT_EQ(unjoined.closest, none.closest);
  EXPECT_EQ(unjoined.final, none.final);
}

TEST(BulletStepperTest, UnjoinedRuleKeepsContactsOfUnjoinedCells) {
  // Three cells in a row, the outer two joined by a spring through the
  // middle one, which is joined to neither: the spring drives the outer
  // cells together and the middle cell stops them under UNJOINED.
  Body body;
  body.position = {{0, 0}, {3, 0}, {6, 0}};
  body.radius = {1.0, 1.0, 1.0};
  body.springs.push_back({0, 2, 0.01});
  for (const ContactRule rule : {ContactRule::kNone, ContactRule::kUnjoined}) {
    PhysicsParams params = BulletParams();
    params.contact_rule = rule;
    SoftBody forces(body, params);
    std::unique_ptr<MotionStepper> bullet = MakeBulletStepper(&forces, body);
    MotionState state = AtRest(body);
    for (int step = 0; step < 600; ++step) bullet->Step(&state);
    const double span = state.position[2].x - state.position[0].x;
    if (rule == ContactRule::kNone) {
      EXPECT_LT(span, 1.0) << "without contacts the ends meet";
    } else {
      EXPECT_GT(span, 0.9 * 4.0) << "the middle cell holds them apart";
    }
  }
}

TEST(BulletStepperTest, ContactsAreInternalForcesWithoutDrag) {
  // Contacts push pairs apart equally and oppositely: without drag the
  // centre of mass stays put while actuated cells press into each other.
  Source source(5);
  for (int trial = 0; trial < 6; ++trial) {
    const Body body = RandomBody(source, source.Int(3, 32), 6.0);
    const int n = body.nodes();
    PhysicsParams params = BulletParams();
    params.contact_rule =
        trial % 2 == 0 ? ContactRule::kAll : ContactRule::kUnjoined;
    params.drag_normal = 0.0;
    params.drag_tangential = 0.0;
    params.actuation_max = 0.45;
    SoftBody forces(body, params);
    std::unique_ptr<MotionStepper> bullet = MakeBulletStepper(&forces, body);
    MotionState state = AtRest(body);
    const Vec2 start = CentreOfMass(state);
    std::vector<double> expand(n), contract(n);
    for (int step = 0; step < 500; ++step) {
      if (step % 50 == 0) {
        for (int i = 0; i < n; ++i) {
          expand[i] = source.Uniform(0, 1);
          contract[i] = source.Uniform(0, 1);
        }
        forces.SetActuation(expand, contract);
      }
      bullet->Step(&state);
    }
    ASSERT_EQ(CheckState(state, 1e6), "") << "trial " << trial;
    EXPECT_LT(Length(CentreOfMass(state) - start), 1e-9)
        << "trial " << trial << " with " << n << " nodes";
  }
}

// ---------------------------------------------------------------------------
// Configuration.

TEST(BulletStepperTest, ConfigAcceptsBulletWithContacts) {
  v1::PhysicsConfig message;
  message.set_backend(v1::PhysicsConfig::BULLET);
  message.set_contact_rule(v1::PhysicsConfig::UNJOINED);
  message.set_integrator(v1::PhysicsConfig::SEMI_IMPLICIT_EULER);
  message.set_drag_update(v1::PhysicsConfig::EXPLICIT);
  message.set_substeps(4);
  PhysicsParams params;
  ASSERT_TRUE(PhysicsParamsFromProto(message, &params).ok());
  EXPECT_EQ(params.backend, PhysicsBackend::kBullet);
  EXPECT_EQ(params.contact_rule, ContactRule::kUnjoined);
  EXPECT_EQ(params.substeps, 4);
}

TEST(BulletStepperTest, ConfigRejectsOtherIntegratorsWithBullet) {
  for (const auto integrator :
       {v1::PhysicsConfig::RK4, v1::PhysicsConfig::VELOCITY_VERLET}) {
    v1::PhysicsConfig message;
    message.set_backend(v1::PhysicsConfig::BULLET);
    message.set_integrator(integrator);
    PhysicsParams params;
    const Status status = PhysicsParamsFromProto(message, &params);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.message().rfind("physics.integrator: the BULLET backend "
                                     "integrates with semi-implicit Euler "
                                     "only",
                                     0),
              0u)
        << status.message();
    EXPECT_NE(
        status.message().find(v1::PhysicsConfig::Integrator_Name(integrator)),
        std::string::npos)
        << status.message();
    EXPECT_EQ(params.backend, PhysicsBackend::kNative);  // Unchanged.
  }
}

TEST(BulletStepperTest, ConfigRejectsStableDragWithBullet) {
  v1::PhysicsConfig message;
  message.set_backend(v1::PhysicsConfig::BULLET);
  message.set_integrator(v1::PhysicsConfig::SEMI_IMPLICIT_EULER);
  message.set_drag_update(v1::PhysicsConfig::STABLE);
  PhysicsParams params;
  const Status status = PhysicsParamsFromProto(message, &params);
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().rfind("physics.drag_update: ", 0), 0u)
      << status.message();
  EXPECT_NE(status.message().find("BULLET"), std::string::npos)
      << status.message();
}

TEST(BulletStepperTest, ConfigFileRejectsRk4WithBulletNamingTheField) {
  v1::Config message;
  message.mutable_physics()->set_backend(v1::PhysicsConfig::BULLET);
  message.mutable_physics()->set_integrator(v1::PhysicsConfig::RK4);
  ModelConfig config;
  const Status status = ConfigFromProto(message, &config);
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("physics.integrator"), std::string::npos)
      << status.message();
}

// ---------------------------------------------------------------------------
// Lifetime: worlds are created and destroyed cleanly (the ASan build checks
// for leaks at exit).

TEST(BulletStepperTest, ManySteppersComeAndGoWithoutLeaks) {
  Source source(11);
  const Body body = RandomBody(source, 32, 8.0);
  for (int round = 0; round < 200; ++round) {
    PhysicsParams params = BulletParams();
    params.contact_rule = static_cast<ContactRule>(round % 3);
    SoftBody forces(body, params);
    std::unique_ptr<MotionStepper> bullet = MakeBulletStepper(&forces, body);
    MotionState state = AtRest(body);
    for (int step = 0; step < 5; ++step) bullet->Step(&state);
    ASSERT_EQ(CheckState(state, 1e6), "") << "round " << round;
  }
}

// ---------------------------------------------------------------------------
// A whole evaluation.

using testing::LoadGenome;

TEST(BulletStepperTest, EvaluationWithBulletMatchesNative) {
  const Genome genome = LoadGenome("seed-1198.json");
  ModelConfig config;
  config.evaluation.motion_steps = 300;
  config.physics.integrator = Integrator::kSemiImplicitEuler;
  config.physics.contact_rule = ContactRule::kNone;
  const EvaluationResult native = Evaluate(genome, config);
  config.physics.backend = PhysicsBackend::kBullet;
  const EvaluationResult bullet = Evaluate(genome, config);
  ASSERT_EQ(native.status, EvalStatus::kOk) << native.reason;
  ASSERT_EQ(bullet.status, EvalStatus::kOk) << bullet.reason;
  ASSERT_TRUE(bullet.fitness.has_value());
  EXPECT_EQ(bullet.cells, native.cells);
  EXPECT_EQ(bullet.steps, native.steps);
  std::printf("  fitness: native %.17g, bullet %.17g\n", *native.fitness,
              *bullet.fitness);
  EXPECT_NEAR(*bullet.fitness, *native.fitness, 1e-9 * *native.fitness);
}

}  // namespace
}  // namespace animat
