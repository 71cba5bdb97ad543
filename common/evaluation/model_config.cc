#include "common/evaluation/model_config.h"

#include "animat/v1/evolution.pb.h"
#include "common/base/validate.h"
#include "common/io/proto_file.h"

namespace animat {
namespace {

using E = EvaluationParams;
using G = GuidanceParams;

// In the proto's order (docs/model.md §8, §10.1).
constexpr ParamRow<E> kEvaluation[] = {
    {"equilibration_steps", &E::equilibration_steps,
     ParamRange::Closed(0, 100000000), "steps with the network stopped"},
    {"equilibration_damping", &E::equilibration_damping,
     ParamRange::Closed(0.0, 1.0), "v *= this after each equilibration step"},
    {"motion_steps", &E::motion_steps, ParamRange::Closed(0, 100000000),
     "steps with the network running; fitness is measured over them"},
    {"max_coordinate", &E::max_coordinate, ParamRange::Positive(),
     "a coordinate beyond this magnitude fails (radii)"},
    {"check_interval", &E::check_interval, ParamRange::Closed(1, 100000000),
     "steps between the finiteness and coordinate checks"},
    {"min_chambers", &E::min_chambers, ParamRange::Closed(0, 1000),
     "fewer chambers fail as a degenerate body"},
    {"energy_budget", &E::energy_budget, ParamRange::Positive(),
     "B of DISTANCE_WITHIN_ENERGY_BUDGET (force times length)"},
    {"holding_cost", &E::holding_cost, ParamRange::NonNegative(),
     "c_h: each motion step adds c_h * sum |L - L0| to the energy"},
};

constexpr EnumPair kFitnessKinds[] = {
    {static_cast<int>(FitnessKind::kDistance), v1::EvaluationConfig::DISTANCE},
    {static_cast<int>(FitnessKind::kDistanceWithinEnergyBudget),
     v1::EvaluationConfig::DISTANCE_WITHIN_ENERGY_BUDGET},
};

constexpr EnumRow<E> kEvaluationEnums[] = {
    MakeEnumRow<&E::fitness>("fitness", kFitnessKinds,
                             "what selection maximises"),
};

// In the proto's order (docs/model.md §10.2).
constexpr ParamRow<G> kGuidance[] = {
    {"enabled", &G::enabled, ParamRange::Any(),
     "fitness is the guidance fitness (needs evaluation.fitness DISTANCE)"},
    {"trials", &G::trials, ParamRange::Closed(1, kMaxGuidanceTrials),
     "K, the trials per evaluation"},
    {"source_distance", &G::source_distance, ParamRange::Positive(),
     "D, the source's distance from the starting centre of mass (radii)"},
    {"decay_length", &G::decay_length, ParamRange::Positive(),
     "lambda_c: a skin cell reads exp(-d / decay_length) (radii)"},
    {"lead_steps", &G::lead_steps, ParamRange::Closed(0, 100000),
     "network steps with the chemical on before motion, the body held"},
};

Status EvaluationParamsFromProto(const v1::EvaluationConfig& m,
                                 EvaluationParams* params) {
  EvaluationParams p = *params;
  ReadParams<E>(m, kEvaluation, &p);
  Status status = FirstError({
      ReadEnums<E>("evaluation", m, kEvaluationEnums, &p),
      CheckParams<E>("evaluation", p, kEvaluation),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

Status GuidanceParamsFromProto(const v1::GuidanceConfig& m,
                               GuidanceParams* params) {
  GuidanceParams p = *params;
  ReadParams<G>(m, kGuidance, &p);
  Status status = CheckParams<G>("guidance", p, kGuidance);
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
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
  WriteParams<E>(c.evaluation, kEvaluation, m.mutable_evaluation(),
                 kEvaluationEnums);
  WriteParams<G>(c.guidance, kGuidance, m.mutable_guidance());
  return m;
}

std::vector<ParamDoc> ModelParamDocs() {
  std::vector<ParamDoc> docs = GrnParamDocs();
  auto append = [&docs](std::vector<ParamDoc> more) {
    for (ParamDoc& doc : more) docs.push_back(std::move(doc));
  };
  append(DevelopmentParamDocs());
  append(PhysicsParamDocs());
  append(DescribeParams<E>("evaluation", v1::EvaluationConfig(), kEvaluation,
                           kEvaluationEnums));
  append(DescribeParams<G>("guidance", v1::GuidanceConfig(), kGuidance));
  return docs;
}

Status CheckModelParamTables() {
  return FirstError({
      CheckParamTable<GrnParams>(v1::GrnConfig(), GrnParamTable(),
                                 GrnEnumTable()),
      CheckParamTable<DevelopmentParams>(v1::DevelopmentConfig(),
                                         DevelopmentParamTable()),
      CheckParamTable<SignalParams>(v1::SignalConfig(), SignalParamTable()),
      CheckParamTable<PhysicsParams>(v1::PhysicsConfig(), PhysicsParamTable(),
                                     PhysicsEnumTable()),
      CheckParamTable<E>(v1::EvaluationConfig(), kEvaluation, kEvaluationEnums),
      CheckParamTable<G>(v1::GuidanceConfig(), kGuidance),
  });
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
