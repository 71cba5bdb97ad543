// The genetic algorithm's settings (docs/model.md §9) and the run configuration
// that pairs them with the model's (animat.v1.RunConfig).
#ifndef ANIMAT_MASTER_EVOLUTION_EVOLUTION_PARAMS_H_
#define ANIMAT_MASTER_EVOLUTION_EVOLUTION_PARAMS_H_

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "animat/v1/evolution.pb.h"
#include "common/base/status.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome.h"

namespace animat {

// Defaults and their reasons: docs/evolution.md.
struct MutationParams {
  double type_rate = 0.01;         // Per element.
  double sign_rate = 0.01;         // Per element.
  double coordinate_rate = 0.05;   // Per element.
  double coordinate_sigma = 0.5;   // Normal step per axis.
  double duplication_rate = 0.05;  // Per genome.
  double deletion_rate = 0.05;     // Per genome.
  int max_run_length = 4;          // Runs of [1, max_run_length] elements.
  // Channels an S_IN whose type is redrawn may get: the paper's four, or
  // all five with guidance. Not in MutationConfig: RunSettingsFromProto
  // sets it from model.guidance.enabled.
  int input_channels = kPaperInputChannels;
};

struct EvolutionParams {
  uint64_t seed = 1;
  int population = 300;
  int generations = 100;
  int elite = 3;
  int tournament_size = 3;
  double crossover_fraction = 0.2;
  int crossover_points = 2;
  MutationParams mutation;
  int initial_units = 10;
  double initial_min_fitness = 1e-6;
  int max_elements = 1000;
  // A run still improving at `generations` goes on to extend_to (0:
  // never): EvolutionLength.
  int extend_to = 0;
  int extend_window = 20;
  // Initial genomes get a CHEMICAL S_IN (RandomGenome's `chemical`). Not in
  // EvolutionConfig: RunSettingsFromProto sets it from
  // model.guidance.enabled.
  bool chemical_input = false;
};

// Overwrites the fields present after checking them all; errors name the
// field ("evolution.elite: ...") and leave `params` unchanged.
Status EvolutionParamsFromProto(const v1::EvolutionConfig& message,
                                EvolutionParams* params);
// Every field set.
v1::EvolutionConfig EvolutionParamsToProto(const EvolutionParams& params);

// How many generations a run of `params` makes: `generations`, or
// `extend_to` when that is set and the run is still improving once it has
// made `generations`: `best_last`, its best fitness at generation
// generations - 1, is above `best_before`, its best at generation
// generations - 1 - extend_window (a generation without any ok member has
// no best: nullopt, below every fitness). The caller reads the two only
// when extend_to > generations (EvolutionExtends).
bool EvolutionExtends(const EvolutionParams& params);
int EvolutionLength(const EvolutionParams& params,
                    std::optional<double> best_last,
                    std::optional<double> best_before);
// The same from the bests of the generations completed so far
// (best_by_generation[g]: generation g's, from 0 on): `generations` until
// generation generations - 1 is among them.
int EvolutionLength(const EvolutionParams& params,
                    std::span<const std::optional<double>> best_by_generation);
// The most generations a run of `params` can make: extend_to when it
// extends, otherwise `generations`.
int EvolutionMaxLength(const EvolutionParams& params);

// Every parameter's line of a run configuration ("model.physics.mass",
// "evolution.elite", ...) for `animat config defaults --run`.
std::vector<ParamDoc> RunParamDocs();
// Every table of the run configuration names its message's fields.
Status CheckRunParamTables();

struct RunSettings {
  ModelConfig model;
  EvolutionParams evolution;
};

Status RunSettingsFromProto(const v1::RunConfig& message,
                            RunSettings* settings);
v1::RunConfig RunSettingsToProto(const RunSettings& settings);
// Reads a run configuration (.json or .txtpb) over the defaults; errors
// start with the path.
Result<RunSettings> ReadRunConfigFile(const std::string& path);

}  // namespace animat

#endif  // ANIMAT_MASTER_EVOLUTION_EVOLUTION_PARAMS_H_
