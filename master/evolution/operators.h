// The genetic operators (docs/model.md §9): ranking, tournament selection,
// multipoint crossover, element-level mutation, duplication and deletion of
// runs of elements, initial random genomes, and the making of one
// offspring.
//
// Every random draw comes from a RandomStream keyed by (run seed, the
// individual being made, purpose), so an offspring is a pure function of
// the run seed, its id and the ranked previous generation: whatever the
// order results arrived in, whatever workers or restarts. Pure functions;
// thread-safe.
#ifndef ANIMAT_MASTER_EVOLUTION_OPERATORS_H_
#define ANIMAT_MASTER_EVOLUTION_OPERATORS_H_

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "common/base/rng.h"
#include "common/genome/genome.h"
#include "master/evolution/evolution_params.h"

namespace animat {

// A member of a generation with its evaluation's fitness (none when the
// evaluation failed).
struct Scored {
  uint64_t id = 0;
  std::optional<double> fitness;
};

// Best first: higher fitness first; every failure after every success;
// ties (and failures among themselves) by increasing id. A total order.
std::vector<Scored> Rank(std::vector<Scored> members);

// The winner of a tournament among `population` ranked individuals: `size`
// indices drawn uniformly with replacement, the lowest (best-ranked) wins.
// Preconditions: population > 0, size > 0.
size_t Tournament(size_t population, int size, RandomStream& stream);

// Multipoint crossover: `points` cut positions drawn as fractions in (0, 1)
// and sorted; each parent is cut at the same fractions of its own length;
// the child takes the segments alternately, starting with `a`'s.
Genome Crossover(const Genome& a, const Genome& b, int points,
                 RandomStream& stream);

// Mutations of one genome: per element type, sign and coordinate changes
// at their rates; per genome, a duplication and a deletion of a run at
// their rates. Appends the name of each kind applied, once per kind, in
// this order, to *applied: "type", "sign", "coordinates", "duplication",
// "deletion". The result is valid (ValidateGenome) and at most
// max_elements long (elements beyond are dropped).
Genome Mutate(const Genome& genome, const MutationParams& params,
              int max_elements, RandomStream& stream,
              std::vector<std::string>* applied);

// How an individual was made.
struct Offspring {
  Genome genome;
  std::vector<uint64_t> parents;       // In order: one, or two (crossover).
  std::vector<std::string> operators;  // E.g. {"crossover", "sign"};
                                       // {"copy"} when nothing changed.
};

// The offspring with id `child` of a ranked generation: with probability
// crossover_fraction, crossover of two tournament winners, else a copy of
// one; then mutation. `genome_of(id)` gives a ranked member's genome.
Offspring MakeOffspring(uint64_t child, const std::vector<Scored>& ranked,
                        const std::function<const Genome&(uint64_t)>& genome_of,
                        const EvolutionParams& params);

// Initial candidate number `index`: RandomGenome(initial_units) from the
// stream (seed, index, kRandomGenome).
Genome InitialCandidate(uint64_t index, const EvolutionParams& params);

}  // namespace animat

#endif  // ANIMAT_MASTER_EVOLUTION_OPERATORS_H_
