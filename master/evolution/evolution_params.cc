#include "master/evolution/evolution_params.h"

#include <limits>

#include "common/base/validate.h"
#include "common/genome/genome.h"
#include "common/io/proto_file.h"

namespace animat {
namespace {

constexpr long long kIntMax = std::numeric_limits<int32_t>::max();
// Upper bounds that only keep a mistyped value from exhausting memory or
// time: more cuts than the longest genome has elements add nothing, and a
// tournament of 10000 draws already picks the best of 300 with probability
// 1 - (299/300)^10000 > 1 - 1e-14 (and each tournament costs one draw per
// contestant).
constexpr long long kMaxCrossoverPoints = kMaxGenomeElements;
constexpr long long kMaxTournamentSize = 10000;
// Larger steps could overflow a coordinate to infinity (a Box-Muller
// deviate is at most 8.6 in magnitude), making the genome invalid.
constexpr double kMaxCoordinateSigma = 1e6;
// A random genome of u units has 2u + 10 elements (2u + 11 with the
// CHEMICAL input of guidance, checked by RunSettingsFromProto); it must
// stay within kMaxGenomeElements.
constexpr long long kMaxInitialUnits =
    (static_cast<long long>(kMaxGenomeElements) - kPaperInputChannels -
     kOutputChannels) /
    2;

Status MutationParamsFromProto(const v1::MutationConfig& m,
                               MutationParams* params) {
  MutationParams p = *params;
  if (m.has_type_rate()) p.type_rate = m.type_rate();
  if (m.has_sign_rate()) p.sign_rate = m.sign_rate();
  if (m.has_coordinate_rate()) p.coordinate_rate = m.coordinate_rate();
  if (m.has_coordinate_sigma()) p.coordinate_sigma = m.coordinate_sigma();
  if (m.has_duplication_rate()) p.duplication_rate = m.duplication_rate();
  if (m.has_deletion_rate()) p.deletion_rate = m.deletion_rate();
  if (m.has_max_run_length()) p.max_run_length = m.max_run_length();
  Status status = FirstError({
      RequireInRange("evolution.mutation.type_rate", p.type_rate, 0.0, 1.0),
      RequireInRange("evolution.mutation.sign_rate", p.sign_rate, 0.0, 1.0),
      RequireInRange("evolution.mutation.coordinate_rate", p.coordinate_rate,
                     0.0, 1.0),
      RequireInRange("evolution.mutation.coordinate_sigma", p.coordinate_sigma,
                     0.0, kMaxCoordinateSigma),
      RequireInRange("evolution.mutation.duplication_rate", p.duplication_rate,
                     0.0, 1.0),
      RequireInRange("evolution.mutation.deletion_rate", p.deletion_rate, 0.0,
                     1.0),
      RequireIntInRange("evolution.mutation.max_run_length", p.max_run_length,
                        1, kIntMax),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::MutationConfig MutationParamsToProto(const MutationParams& p) {
  v1::MutationConfig m;
  m.set_type_rate(p.type_rate);
  m.set_sign_rate(p.sign_rate);
  m.set_coordinate_rate(p.coordinate_rate);
  m.set_coordinate_sigma(p.coordinate_sigma);
  m.set_duplication_rate(p.duplication_rate);
  m.set_deletion_rate(p.deletion_rate);
  m.set_max_run_length(p.max_run_length);
  return m;
}

}  // namespace

Status EvolutionParamsFromProto(const v1::EvolutionConfig& m,
                                EvolutionParams* params) {
  EvolutionParams p = *params;
  if (m.has_seed()) p.seed = m.seed();
  if (m.has_population()) p.population = m.population();
  if (m.has_generations()) p.generations = m.generations();
  if (m.has_elite()) p.elite = m.elite();
  if (m.has_tournament_size()) p.tournament_size = m.tournament_size();
  if (m.has_crossover_fraction()) p.crossover_fraction = m.crossover_fraction();
  if (m.has_crossover_points()) p.crossover_points = m.crossover_points();
  if (m.has_initial_units()) p.initial_units = m.initial_units();
  if (m.has_initial_min_fitness()) {
    p.initial_min_fitness = m.initial_min_fitness();
  }
  if (m.has_max_elements()) p.max_elements = m.max_elements();
  Status status = FirstError({
      RequireIntInRange("evolution.population", p.population, 2, kIntMax),
      RequireIntInRange("evolution.generations", p.generations, 1, kIntMax),
      // Elite < population (population >= 2 is checked first, so the range
      // is never empty when this is reached).
      RequireIntInRange("evolution.elite", p.elite, 0, p.population - 1LL),
      RequireIntInRange("evolution.tournament_size", p.tournament_size, 1,
                        kMaxTournamentSize),
      RequireInRange("evolution.crossover_fraction", p.crossover_fraction, 0.0,
                     1.0),
      RequireIntInRange("evolution.crossover_points", p.crossover_points, 1,
                        kMaxCrossoverPoints),
      MutationParamsFromProto(m.mutation(), &p.mutation),
      RequireIntInRange("evolution.initial_units", p.initial_units, 1,
                        kMaxInitialUnits),
      RequireNonNegative("evolution.initial_min_fitness",
                         p.initial_min_fitness),
      RequireIntInRange("evolution.max_elements", p.max_elements, 1,
                        static_cast<long long>(kMaxGenomeElements)),
  });
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::EvolutionConfig EvolutionParamsToProto(const EvolutionParams& p) {
  v1::EvolutionConfig m;
  m.set_seed(p.seed);
  m.set_population(p.population);
  m.set_generations(p.generations);
  m.set_elite(p.elite);
  m.set_tournament_size(p.tournament_size);
  m.set_crossover_fraction(p.crossover_fraction);
  m.set_crossover_points(p.crossover_points);
  *m.mutable_mutation() = MutationParamsToProto(p.mutation);
  m.set_initial_units(p.initial_units);
  m.set_initial_min_fitness(p.initial_min_fitness);
  m.set_max_elements(p.max_elements);
  return m;
}

Status RunSettingsFromProto(const v1::RunConfig& message,
                            RunSettings* settings) {
  RunSettings s = *settings;
  Status status = FirstError({
      ConfigFromProto(message.model(), &s.model),
      EvolutionParamsFromProto(message.evolution(), &s.evolution),
  });
  if (!status.ok()) return status;
  // Guidance genomes may carry the CHEMICAL channel (docs/model.md §10.2);
  // without guidance every draw is the paper's.
  const bool guidance = s.model.guidance.enabled;
  if (guidance && 2LL * s.evolution.initial_units + kPaperInputChannels +
                          kOutputChannels + 1 >
                      static_cast<long long>(kMaxGenomeElements)) {
    return Status::InvalidArgument(
        "evolution.initial_units: with model.guidance.enabled a random "
        "genome has 2 * initial_units + 11 elements, at most " +
        std::to_string(kMaxGenomeElements) + ": must be at most " +
        std::to_string((kMaxGenomeElements - 11) / 2) + ", got " +
        std::to_string(s.evolution.initial_units));
  }
  s.evolution.chemical_input = guidance;
  s.evolution.mutation.input_channels =
      guidance ? kInputChannels : kPaperInputChannels;
  *settings = s;
  return Status::Ok();
}

v1::RunConfig RunSettingsToProto(const RunSettings& settings) {
  v1::RunConfig m;
  *m.mutable_model() = ConfigToProto(settings.model);
  *m.mutable_evolution() = EvolutionParamsToProto(settings.evolution);
  return m;
}

Result<RunSettings> ReadRunConfigFile(const std::string& path) {
  v1::RunConfig message;
  Status status = ReadProtoFile(path, &message);
  if (!status.ok()) {
    // Its fields are not a run configuration's; a model configuration's?
    v1::Config model;
    if (ReadProtoFile(path, &model).ok()) {
      return Status::InvalidArgument(
          path +
          ": a model configuration (animat.v1.Config), where a run "
          "configuration (animat.v1.RunConfig) is wanted: put it in a "
          "model { } block beside an evolution { } block (animat config "
          "defaults --run prints one)");
    }
    return status;
  }
  RunSettings settings;
  status = RunSettingsFromProto(message, &settings);
  if (!status.ok()) return status.WithPrefix(path);
  return settings;
}

}  // namespace animat
