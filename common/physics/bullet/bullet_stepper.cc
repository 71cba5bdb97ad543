#include "common/physics/bullet/bullet_stepper.h"

#include <btBulletDynamicsCommon.h>

#include <cassert>
#include <memory>
#include <vector>

#include "common/base/vec2.h"

namespace animat {
namespace {

// Collision filtering. Every body must be added to the world to be
// integrated, and btDiscreteDynamicsWorld::addRigidBody always gives it a
// broadphase proxy; a pair is kept only if (group_a & mask_b) and
// (group_b & mask_a) are both non-zero. Without contacts every body is in
// no group and accepts none, so the pair cache refuses every pair: no
// narrowphase, no contact manifold, no contact constraint ever exists, and
// the solver sees only our forces. (What remains is the broadphase refitting
// each sphere's bounding box every step, a small cost.) With contacts every
// cell is in one group that collides with itself; under the UNJOINED rule
// the two cells of every spring also ignore each other
// (setIgnoreCollisionCheck), so the dispatcher makes no contact for them.
constexpr int kNoGroup = 0;
constexpr int kCellGroup = 1;

// Contact material, used only with contacts. Cells are wet and soft: no
// bounce (restitution 0, so a cell driven into another stops at contact
// instead of rebounding) and no friction (friction 0: contact forces act
// along the line of centres only, like the model's springs and pressure,
// and since cells cannot rotate friction would only brake sliding cells).
constexpr double kRestitution = 0.0;
constexpr double kFriction = 0.0;

class BulletStepper final : public MotionStepper {
 public:
  BulletStepper(SoftBody* forces, const Body& body);
  ~BulletStepper() override;
  BulletStepper(const BulletStepper&) = delete;
  BulletStepper& operator=(const BulletStepper&) = delete;

  void Step(MotionState* state) override;

 private:
  SoftBody* forces_;  // Borrowed.
  int substeps_;
  double h_;  // Sub-step, dt / substeps.
  // The world and what it uses; built in this order, destroyed in reverse
  // (see the destructor).
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<std::unique_ptr<btSphereShape>> shapes_;  // One per node.
  std::vector<std::unique_ptr<btRigidBody>> bodies_;    // One per node.
  std::vector<Vec2> force_;                             // Scratch.
};

BulletStepper::BulletStepper(SoftBody* forces, const Body& body)
    : forces_(forces),
      substeps_(forces->params().substeps),
      // dt / 1 == dt: one sub-step is exactly the simulation step.
      h_(forces->params().dt / forces->params().substeps) {
  const PhysicsParams& params = forces->params();
  assert(params.integrator == Integrator::kSemiImplicitEuler);
  assert(params.drag_update == DragUpdate::kExplicit);
  assert(forces->nodes() == body.nodes());

  configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  world_ = std::make_unique<btDiscreteDynamicsWorld>(
      dispatcher_.get(), broadphase_.get(), solver_.get(),
      configuration_.get());
  // Before adding bodies: addRigidBody gives each the world's gravity.
  world_->setGravity(btVector3(0, 0, 0));

  const bool contacts = params.contact_rule != ContactRule::kNone;
  const int group = contacts ? kCellGroup : kNoGroup;
  const int mask = contacts ? kCellGroup : kNoGroup;
  const btScalar mass = params.mass;
  for (int i = 0; i < body.nodes(); ++i) {
    const double radius =
        static_cast<size_t>(i) < body.radius.size() ? body.radius[i] : 1.0;
    shapes_.push_back(std::make_unique<btSphereShape>(radius));
    btVector3 inertia(0, 0, 0);
    shapes_.back()->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(
        mass, /*motionState=*/nullptr, shapes_.back().get(), inertia);
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(
        btVector3(body.position[i].x, body.position[i].y, 0));
    info.m_linearDamping = 0;
    info.m_angularDamping = 0;
    info.m_friction = kFriction;
    info.m_rollingFriction = 0;
    info.m_spinningFriction = 0;
    info.m_restitution = kRestitution;
    info.m_linearSleepingThreshold = 0;
    info.m_angularSleepingThreshold = 0;
    bodies_.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* rb = bodies_.back().get();
    rb->setLinearFactor(btVector3(1, 1, 0));   // Held in the plane z = 0.
    rb->setAngularFactor(btVector3(0, 0, 0));  // Never rotates.
    // The angular velocity stays 0, so the gyroscopic term (on by default)
    // is 0; skip computing it.
    rb->setFlags(rb->getFlags() & ~BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
    rb->forceActivationState(DISABLE_DEACTIVATION);  // Never sleeps.
    world_->addRigidBody(rb, group, mask);
    rb->setGravity(btVector3(0, 0, 0));
  }
  if (params.contact_rule == ContactRule::kUnjoined) {
    for (const Spring& s : body.springs) {
      bodies_[s.a]->setIgnoreCollisionCheck(bodies_[s.b].get(), true);
      bodies_[s.b]->setIgnoreCollisionCheck(bodies_[s.a].get(), true);
    }
  }
}

BulletStepper::~BulletStepper() {
  // Bodies leave the world (which removes their broadphase proxies and any
  // contact pairs) before they, their shapes, and then the world and what it
  // uses are destroyed.
  for (auto& rb : bodies_) world_->removeRigidBody(rb.get());
  bodies_.clear();
  shapes_.clear();
  world_.reset();
  solver_.reset();
  broadphase_.reset();
  dispatcher_.reset();
  configuration_.reset();
}

void BulletStepper::Step(MotionState* state) {
  const int n = static_cast<int>(bodies_.size());
  assert(static_cast<int>(state->position.size()) == n &&
         static_cast<int>(state->velocity.size()) == n);
  for (int sub = 0; sub < substeps_; ++sub) {
    // The caller may have changed the state (the evaluator damps and zeroes
    // velocities between steps): the state, not the world, is the truth.
    for (int i = 0; i < n; ++i) {
      btRigidBody* rb = bodies_[i].get();
      const Vec2 x = state->position[i];
      const Vec2 v = state->velocity[i];
      rb->getWorldTransform().setOrigin(btVector3(x.x, x.y, 0));
      rb->setLinearVelocity(btVector3(v.x, v.y, 0));
    }
    forces_->ComputeForces(*state, &force_);
    for (int i = 0; i < n; ++i) {
      bodies_[i]->applyCentralForce(btVector3(force_[i].x, force_[i].y, 0));
    }
    // maxSubSteps 0: exactly one internal step of h_ (no fixed-step
    // accumulator, no interpolation). Forces are cleared afterwards.
    world_->stepSimulation(h_, 0);
    for (int i = 0; i < n; ++i) {
      const btRigidBody* rb = bodies_[i].get();
      const btVector3& x = rb->getWorldTransform().getOrigin();
      const btVector3& v = rb->getLinearVelocity();
      state->position[i] = {x.x(), x.y()};
      state->velocity[i] = {v.x(), v.y()};
    }
  }
}

}  // namespace

std::unique_ptr<MotionStepper> MakeBulletStepper(SoftBody* forces,
                                                 const Body& body) {
  return std::make_unique<BulletStepper>(forces, body);
}

}  // namespace animat
