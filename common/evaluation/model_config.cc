#include "common/evaluation/model_config.h"

#include "animat/v1/evolution.pb.h"
#include "common/base/validate.h"
#include "common/io/proto_file.h"

namespace animat {
namespace {

Status EvaluationParamsFromProto(const v1::EvaluationConfig& m,
                                 EvaluationParams* params) {
  EvaluationParams p = *params;
  if (m.has_equilibration_steps()) {
    p.equilibration_steps = m.equilibration_steps();
  }
  if (m.has_equilibration_damping()) {
    p.equilibration_damping = m.equilibration_damping();
  }
  if (m.has_motion_steps()) p.motion_steps = m.motion_steps();
  if (m.has_max_coordinate()) p.max_coordinate = m.max_coordinate();
  if (m.has_check_interval()) p.check_interval = m.check_interval();
  if (m.has_min_chambers()) p.min_chambers = m.min_chambers();
  if (m.has_fitness()) {
    switch (m.fitness()) {
      case v1::EvaluationConfig::FITNESS_UNSPECIFIED:
        break;
      case v1::EvaluationConfig::DISTANCE:
        p.fitness = FitnessKind::kDistance;
        break;
      case v1::EvaluationConfig::DISTANCE_WITHIN_ENERGY_BUDGET:
        p.fitness = FitnessKind::kDistanceWithinEnergyBudget;
        break;
      default:
        return Status::InvalidArgument("evaluation.fitness: unknown value " +
                                       std::to_string(m.fitness()));
    }
  }
  if (m.has_energy_budget()) p.energy_budget = m.energy_budget();
  Status status = FirstError({
      RequireIntInRange("evaluation.equilibration_steps", p.equilibration_steps,
                        0, 100000000),
      RequireInRange("evaluation.equilibration_damping",
                     p.equilibration_damping, 0.0, 1.0),
      RequireIntInRange("evaluation.motion_steps", p.motion_steps, 0,
                        100000000),
      RequirePositive("evaluation.max_coordinate", p.max_coordinate),
      RequireIntInRange("evaluation.check_interval", p.check_interval, 1,
                        100000000),
      RequireIntInRange("evaluation.min_chambers", p.min_chambers, 0, 1000),
      RequirePositive("evaluation.energy_budget", p.energy_budget),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

Status GuidanceParamsFromProto(const v1::GuidanceConfig& m,
                               GuidanceParams* params) {
  GuidanceParams p = *params;
  if (m.has_enabled()) p.enabled = m.enabled();
  if (m.has_trials()) p.trials = m.trials();
  if (m.has_source_distance()) p.source_distance = m.source_distance();
  if (m.has_decay_length()) p.decay_length = m.decay_length();
  Status status = FirstError({
      RequireIntInRange("guidance.trials", p.trials, 1, kMaxGuidanceTrials),
      RequirePositive("guidance.source_distance", p.source_distance),
      RequirePositive("guidance.decay_length", p.decay_length),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::GuidanceConfig GuidanceParamsToProto(const GuidanceParams& p) {
  v1::GuidanceConfig m;
  m.set_enabled(p.enabled);
  m.set_trials(p.trials);
  m.set_source_distance(p.source_distance);
  m.set_decay_length(p.decay_length);
  return m;
}

}  // namespace

const char* FitnessKindName(FitnessKind kind) {
  switch (kind) {
    case FitnessKind::kDistance:
      return "distance";
    case FitnessKind::kDistanceWithinEnergyBudget:
      return "distance_within_energy_budget";
  }
  return "?";
}

Status ConfigFromProto(const v1::Config& message, ModelConfig* config) {
  ModelConfig c = *config;
  Status status = FirstError({
      GrnParamsFromProto(message.grn(), &c.grn),
      DevelopmentParamsFromProto(message.development(), &c.development),
      SignalParamsFromProto(message.signals(), &c.signals),
      PhysicsParamsFromProto(message.physics(), &c.physics),
      EvaluationParamsFromProto(message.evaluation(), &c.evaluation),
      GuidanceParamsFromProto(message.guidance(), &c.guidance),
  });
  if (!status.ok()) return status;
  if (c.guidance.enabled && c.evaluation.fitness != FitnessKind::kDistance) {
    // The budget form scales a distance; a guidance score may be negative.
    return Status::InvalidArgument(
        std::string("guidance.enabled: the guidance fitness replaces "
                    "evaluation.fitness, which must then be DISTANCE, got ") +
        v1::EvaluationConfig::Fitness_Name(
            c.evaluation.fitness == FitnessKind::kDistance
                ? v1::EvaluationConfig::DISTANCE
                : v1::EvaluationConfig::DISTANCE_WITHIN_ENERGY_BUDGET));
  }
  *config = c;
  return Status::Ok();
}

v1::Config ConfigToProto(const ModelConfig& c) {
  v1::Config m;
  *m.mutable_grn() = GrnParamsToProto(c.grn);
  *m.mutable_development() = DevelopmentParamsToProto(c.development);
  *m.mutable_signals() = SignalParamsToProto(c.signals);
  *m.mutable_physics() = PhysicsParamsToProto(c.physics);
  v1::EvaluationConfig* e = m.mutable_evaluation();
  e->set_equilibration_steps(c.evaluation.equilibration_steps);
  e->set_equilibration_damping(c.evaluation.equilibration_damping);
  e->set_motion_steps(c.evaluation.motion_steps);
  e->set_max_coordinate(c.evaluation.max_coordinate);
  e->set_check_interval(c.evaluation.check_interval);
  e->set_min_chambers(c.evaluation.min_chambers);
  e->set_fitness(c.evaluation.fitness == FitnessKind::kDistance
                     ? v1::EvaluationConfig::DISTANCE
                     : v1::EvaluationConfig::DISTANCE_WITHIN_ENERGY_BUDGET);
  e->set_energy_budget(c.evaluation.energy_budget);
  *m.mutable_guidance() = GuidanceParamsToProto(c.guidance);
  return m;
}

Result<ModelConfig> ReadConfigFile(const std::string& path) {
  v1::Config message;
  Status status = ReadProtoFile(path, &message);
  if (!status.ok()) {
    // Its fields are not a model configuration's; a run configuration's?
    v1::RunConfig run;
    if (ReadProtoFile(path, &run).ok()) {
      return Status::InvalidArgument(
          path +
          ": a run configuration (animat.v1.RunConfig), where a model "
          "configuration (animat.v1.Config) is wanted: give what its "
          "model { } block holds (animat config defaults prints one)");
    }
    return status;
  }
  ModelConfig config;
  status = ConfigFromProto(message, &config);
  if (!status.ok()) return status.WithPrefix(path);
  return config;
}

}  // namespace animat
