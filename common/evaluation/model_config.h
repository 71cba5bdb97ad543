// The whole model configuration (animat.v1.Config) as plain structs with
// docs/model.md's defaults, and its conversion from and to protobuf.
#ifndef ANIMAT_COMMON_EVALUATION_MODEL_CONFIG_H_
#define ANIMAT_COMMON_EVALUATION_MODEL_CONFIG_H_

#include <string>
#include <vector>

#include "animat/v1/config.pb.h"
#include "common/base/status.h"
#include "common/development/development_params.h"
#include "common/grn/grn_params.h"
#include "common/io/param_table.h"
#include "common/physics/physics_params.h"

namespace animat {

// The evaluation schedule and failure checks (model §8).
// What selection maximises (docs/model.md §10.1).
enum class FitnessKind {
  kDistance,                    // The paper's.
  kDistanceWithinEnergyBudget,  // distance * min(1, budget / energy).
};
// "distance", "distance_within_energy_budget".
const char* FitnessKindName(FitnessKind kind);

struct EvaluationParams {
  int equilibration_steps = 200;       // Network stopped.
  double equilibration_damping = 0.9;  // v *= this after each such step.
  int motion_steps = 6000;             // Network running.
  double max_coordinate = 1e6;         // Beyond: numerical failure.
  int check_interval = 100;            // Steps between state checks.
  int min_chambers = 1;  // Fewer chambers: a degenerate body (model §6.5).
  FitnessKind fitness = FitnessKind::kDistance;
  // B of kDistanceWithinEnergyBudget, > 0: about the median work of
  // swimmers evolved for distance alone (docs/model.md §10.1).
  double energy_budget = 10000.0;
  // c_h, >= 0 (force per step): each motion step adds c_h times the sum
  // over springs of |L - L0| to the energy (docs/model.md §10.1). 0: the
  // energy is the work of changing rest lengths only.
  double holding_cost = 0.0;
};

// Active guidance toward a chemical source (docs/model.md §10.2); off by
// default, which is the paper's model.
inline constexpr int kMaxGuidanceTrials = 64;
struct GuidanceParams {
  bool enabled = false;
  int trials = 4;                 // K, in [1, kMaxGuidanceTrials].
  double source_distance = 30.0;  // D (radii), > 0.
  double decay_length = 10.0;     // lambda_c (radii), > 0.
  // Network steps with the chemical on before each trial's motion, the
  // body held still (docs/model.md §10.2), in [0, 100000].
  int lead_steps = 0;
};

struct ModelConfig {
  GrnParams grn;
  DevelopmentParams development;
  SignalParams signals;
  PhysicsParams physics;
  EvaluationParams evaluation;
  GuidanceParams guidance;
};

// Starts from `*config` (usually the defaults), overwrites the fields
// present in `message`, and checks every value. On error `*config` is
// unchanged and the message names the field ("physics.dt: must be ...").
Status ConfigFromProto(const v1::Config& message, ModelConfig* config);

// Every field set, defaults included.
v1::Config ConfigToProto(const ModelConfig& config);

// Every parameter's line ("physics.mass", ...) for `animat config
// defaults`, from the tables that convert and check them.
std::vector<ParamDoc> ModelParamDocs();
// Every table of the model names its message's fields (CheckParamTable).
Status CheckModelParamTables();

// Reads a configuration file (.json or .txtpb) over the defaults. Errors
// start with the path.
Result<ModelConfig> ReadConfigFile(const std::string& path);

}  // namespace animat

#endif  // ANIMAT_COMMON_EVALUATION_MODEL_CONFIG_H_
