#include "master/evolution/evolution_params.h"

#include <limits>
#include <vector>

#include "common/base/validate.h"
#include "common/genome/genome.h"
#include "common/io/param_table.h"
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

using M = MutationParams;
using P = EvolutionParams;

// In the proto's order (docs/evolution.md).
constexpr ParamRow<M> kMutation[] = {
    {"type_rate", &M::type_rate, ParamRange::Closed(0.0, 1.0),
     "per element: its type redrawn"},
    {"sign_rate", &M::sign_rate, ParamRange::Closed(0.0, 1.0),
     "per element: its sign flipped"},
    {"coordinate_rate", &M::coordinate_rate, ParamRange::Closed(0.0, 1.0),
     "per element: its coordinates stepped"},
    {"coordinate_sigma", &M::coordinate_sigma,
     ParamRange::Closed(0.0, kMaxCoordinateSigma),
     "the normal step per coordinate axis"},
    {"duplication_rate", &M::duplication_rate, ParamRange::Closed(0.0, 1.0),
     "per genome: a run of elements duplicated"},
    {"deletion_rate", &M::deletion_rate, ParamRange::Closed(0.0, 1.0),
     "per genome: a run of elements deleted"},
    {"max_run_length", &M::max_run_length, ParamRange::Closed(1, kIntMax),
     "runs of [1, max_run_length] elements"},
};

// In the checks' order; the elite's bound names the population and is
// checked after the table's.
constexpr ParamRow<P> kEvolution[] = {
    {"seed", &P::seed, ParamRange::Any(), "the run's random streams"},
    {"population", &P::population, ParamRange::Closed(2, kIntMax),
     "individuals per generation"},
    {"generations", &P::generations, ParamRange::Closed(1, kIntMax),
     "generations evaluated, the first included"},
    {"elite", &P::elite, ParamRange::Closed(0, kIntMax),
     "the best copied unchanged; less than population"},
    {"tournament_size", &P::tournament_size,
     ParamRange::Closed(1, kMaxTournamentSize), "contestants per tournament"},
    {"crossover_fraction", &P::crossover_fraction, ParamRange::Closed(0.0, 1.0),
     "children made by crossover"},
    {"crossover_points", &P::crossover_points,
     ParamRange::Closed(1, kMaxCrossoverPoints), "cuts per crossover"},
    {"initial_units", &P::initial_units,
     ParamRange::Closed(1, kMaxInitialUnits),
     "regulatory units of a random genome"},
    {"initial_min_fitness", &P::initial_min_fitness, ParamRange::NonNegative(),
     "generation 0 redraws a genome below this fitness"},
    {"max_elements", &P::max_elements,
     ParamRange::Closed(1, static_cast<double>(kMaxGenomeElements)),
     "a longer child is replaced by a copy of its parent"},
    {"extend_to", &P::extend_to, ParamRange::Closed(0, kIntMax),
     "a run still improving at `generations` goes on to this many; 0: never"},
    {"extend_window", &P::extend_window, ParamRange::Closed(1, kIntMax),
     "still improving: a new best in this many last generations"},
};

}  // namespace

Status EvolutionParamsFromProto(const v1::EvolutionConfig& m,
                                EvolutionParams* params) {
  EvolutionParams p = *params;
  ReadParams<P>(m, kEvolution, &p);
  ReadParams<M>(m.mutation(), kMutation, &p.mutation);
  Status status = FirstError({
      CheckParams<P>("evolution", p, kEvolution),
      // Elite < population (population >= 2 is checked first, so the range
      // is never empty when this is reached).
      RequireIntInRange("evolution.elite", p.elite, 0, p.population - 1LL),
      CheckParams<M>("evolution.mutation", p.mutation, kMutation),
  });
  // An extension looks back within `generations`. (An extend_to of at
  // most `generations` extends nothing; it is not refused, so that a run
  // resumed with more generations keeps a configuration that reads back.)
  if (status.ok() && EvolutionExtends(p)) {
    status = RequireIntInRange("evolution.extend_window", p.extend_window, 1,
                               p.generations - 1LL);
  }
  if (!status.ok()) return status;
  *params = p;
  return Status::Ok();
}

v1::EvolutionConfig EvolutionParamsToProto(const EvolutionParams& p) {
  v1::EvolutionConfig m;
  WriteParams<P>(p, kEvolution, &m);
  WriteParams<M>(p.mutation, kMutation, m.mutable_mutation());
  return m;
}

bool EvolutionExtends(const EvolutionParams& p) {
  return p.extend_to > p.generations;
}

int EvolutionMaxLength(const EvolutionParams& p) {
  return EvolutionExtends(p) ? p.extend_to : p.generations;
}

int EvolutionLength(const EvolutionParams& p, std::optional<double> best_last,
                    std::optional<double> best_before) {
  if (!EvolutionExtends(p) || !best_last) return p.generations;
  const bool improving = !best_before || *best_last > *best_before;
  return improving ? p.extend_to : p.generations;
}

int EvolutionLength(const EvolutionParams& p,
                    std::span<const std::optional<double>> best_by_generation) {
  const size_t last = static_cast<size_t>(p.generations) - 1;
  if (!EvolutionExtends(p) || best_by_generation.size() <= last) {
    return p.generations;
  }
  // extend_window < generations when extending (EvolutionParamsFromProto).
  return EvolutionLength(p, best_by_generation[last],
                         best_by_generation[last - p.extend_window]);
}

std::vector<ParamDoc> RunParamDocs() {
  std::vector<ParamDoc> docs;
  for (ParamDoc& doc : ModelParamDocs()) {
    doc.name = "model." + doc.name;
    docs.push_back(std::move(doc));
  }
  for (const std::vector<ParamDoc>& more :
       {DescribeParams<P>("evolution", v1::EvolutionConfig(), kEvolution),
        DescribeParams<M>("evolution.mutation", v1::MutationConfig(),
                          kMutation)}) {
    for (const ParamDoc& doc : more) docs.push_back(doc);
  }
  return docs;
}

Status CheckRunParamTables() {
  return FirstError({
      CheckModelParamTables(),
      CheckParamTable<P>(v1::EvolutionConfig(), kEvolution),
      CheckParamTable<M>(v1::MutationConfig(), kMutation),
  });
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
