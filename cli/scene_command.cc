// animat scene --scene FILE --steps N [--trace FILE] [--every K]
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <string>

#include "animat/v1/trace.pb.h"
#include "cli/commands.h"
#include "common/base/hash.h"
#include "common/base/text.h"
#include "common/evaluation/model_config.h"
#include "common/evaluation/trace_recorder.h"
#include "common/io/proto_file.h"
#include "common/physics/bullet/bullet_stepper.h"
#include "common/physics/scene.h"
#include "common/physics/soft_body.h"

namespace animat::cli {
namespace {

struct Options {
  std::string scene;
  std::string trace;
  int steps = 0;
  int every = 1;
};

double KineticEnergy(const MotionState& state, double mass) {
  double energy = 0.0;
  for (const Vec2& v : state.velocity) energy += 0.5 * mass * Dot(v, v);
  return energy;
}

int Run(const Options& o) {
  v1::Scene message;
  Status status = ReadProtoFile(o.scene, &message);
  if (!status.ok()) return Fail(status.message());
  Result<Scene> scene = SceneFromProto(message);
  if (!scene.ok()) return Fail(scene.status().WithPrefix(o.scene).message());
  if (!o.trace.empty()) {
    Result<ProtoFormat> format = ProtoFormatForPath(o.trace);
    if (!format.ok()) return Fail(format.status().message());
  }

  const EvaluationParams checks;  // Bound and interval of docs/model.md §8.3.
  SoftBody body(scene->body, scene->params);
  body.SetActuation(scene->expand, scene->contract);
  std::unique_ptr<MotionStepper> bullet;
  if (scene->params.backend == PhysicsBackend::kBullet) {
    bullet = MakeBulletStepper(&body, scene->body);
  }
  MotionStepper& stepper = bullet ? *bullet : body;
  MotionState& state = scene->state;
  v1::Trace trace;
  *trace.mutable_config()->mutable_physics() =
      PhysicsParamsToProto(scene->params);
  *trace.mutable_body() = message.body();
  const Vec2 start = CentreOfMass(state);
  const bool tracing = !o.trace.empty();
  if (tracing) {
    AppendFrame(MotionPhase::kMotion, 0, state, scene->expand, scene->contract,
                &trace);
  }
  std::string problem;
  int done = 0;
  for (int step = 1; step <= o.steps; ++step) {
    stepper.Step(&state);
    done = step;
    if (step % checks.check_interval == 0 || step == o.steps) {
      problem = CheckState(state, checks.max_coordinate);
      if (!problem.empty()) {
        problem += " at step " + std::to_string(step);
        break;
      }
    }
    if (tracing && (step % o.every == 0 || step == o.steps)) {
      AppendFrame(MotionPhase::kMotion, step, state, scene->expand,
                  scene->contract, &trace);
    }
  }

  StateHash hash;
  HashMotionState(state, &hash);
  v1::EvaluationResult* result = trace.mutable_result();
  result->set_status(problem.empty() ? v1::EvaluationResult::OK
                                     : v1::EvaluationResult::NUMERICAL_FAILURE);
  result->set_reason(problem);
  result->set_cells(body.nodes());
  result->set_steps(done);
  result->set_state_hash(hash.value());
  if (tracing) {
    status = WriteProtoFile(o.trace, trace);
    if (!status.ok()) return Fail(status.message());
  }

  const Vec2 com = CentreOfMass(state);
  std::printf("status: %s\n", problem.empty() ? "ok" : "numerical_failure");
  if (!problem.empty()) std::printf("reason: %s\n", problem.c_str());
  std::printf("steps: %d\n", done);
  std::printf("centre_of_mass: %s %s\n", ShortestDouble(com.x).c_str(),
              ShortestDouble(com.y).c_str());
  std::printf("displacement: %s\n",
              ShortestDouble(Length(com - start)).c_str());
  std::printf("kinetic_energy: %s\n",
              ShortestDouble(KineticEnergy(state, scene->params.mass)).c_str());
  std::printf("state_hash: %016" PRIx64 "\n", hash.value());
  return 0;
}

}  // namespace

Command AddSceneCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "scene",
      "Run the motion physics alone on a body from a file, with constant "
      "actuation (docs/formats.md)");
  sub->add_option("--scene", options->scene, "Scene file (.json, .txtpb)")
      ->required();
  sub->add_option("--steps", options->steps, "Steps to run")
      ->check(CLI::Range(0, 100000000))
      ->required();
  sub->add_option("--trace", options->trace,
                  "Write the frames (.json, .txtpb, .binpb)");
  sub->add_option("--every", options->every, "Trace every K-th step")
      ->check(CLI::Range(1, 100000000))
      ->capture_default_str();
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
