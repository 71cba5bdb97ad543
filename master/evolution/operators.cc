#include "master/evolution/operators.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "common/genome/random_genome.h"
#include "master/evolution/gaussian.h"

namespace animat {
namespace {

constexpr int kElementTypes = 5;

// A failed evaluation, or one whose fitness is NaN (which no order can
// place among numbers): ranked after every success.
bool Failed(const Scored& s) {
  return !s.fitness.has_value() || std::isnan(*s.fitness);
}

// Cut position in a sequence of `length` elements for a fraction in (0, 1):
// the nearest integer to fraction * length (halves up). Non-decreasing in
// the fraction, and in [0, length].
size_t CutAt(double fraction, size_t length) {
  return static_cast<size_t>(
      std::floor(fraction * static_cast<double>(length) + 0.5));
}

// Run length for duplication and deletion: uniform in [1, max_run_length],
// then capped at `cap` (>= 1).
size_t RunLength(RandomStream& stream, int max_run_length, size_t cap) {
  const size_t length =
      1 +
      static_cast<size_t>(stream.Below(static_cast<uint64_t>(max_run_length)));
  return std::min(length, cap);
}

void ChangeType(Element& e, int input_channels, RandomStream& stream) {
  // One of the four other types, uniformly.
  const int type = (static_cast<int>(e.type) + 1 +
                    static_cast<int>(stream.Below(kElementTypes - 1))) %
                   kElementTypes;
  e.type = static_cast<ElementType>(type);
  switch (e.type) {
    case ElementType::kSIn:
      e.channel =
          static_cast<int>(stream.Below(static_cast<uint64_t>(input_channels)));
      break;
    case ElementType::kSOut:
      e.channel = static_cast<int>(stream.Below(kOutputChannels));
      break;
    default:
      e.channel = -1;
      break;
  }
}

}  // namespace

std::vector<Scored> Rank(std::vector<Scored> members) {
  std::stable_sort(members.begin(), members.end(),
                   [](const Scored& a, const Scored& b) {
                     const bool a_failed = Failed(a);
                     const bool b_failed = Failed(b);
                     if (a_failed != b_failed) return b_failed;
                     if (!a_failed && *a.fitness != *b.fitness) {
                       return *a.fitness > *b.fitness;
                     }
                     return a.id < b.id;
                   });
  return members;
}

size_t Tournament(size_t population, int size, RandomStream& stream) {
  assert(population > 0 && size > 0);
  size_t best = population;
  for (int i = 0; i < size; ++i) {
    best = std::min(best, static_cast<size_t>(stream.Below(population)));
  }
  return best;
}

Genome Crossover(const Genome& a, const Genome& b, int points,
                 RandomStream& stream) {
  assert(points > 0);
  std::vector<double> fractions;
  fractions.reserve(static_cast<size_t>(points));
  for (int i = 0; i < points; ++i) {
    double f;
    do {
      f = stream.NextDouble();
    } while (f == 0.0);  // (0, 1): a cut at 0 would be no cut.
    fractions.push_back(f);
  }
  std::sort(fractions.begin(), fractions.end());

  const Genome* parents[2] = {&a, &b};
  Genome child;
  // Segment i runs from cut i - 1 to cut i of parent i % 2 (from the start
  // for the first, to the end for the last).
  for (size_t segment = 0; segment <= fractions.size(); ++segment) {
    const std::vector<Element>& source = parents[segment % 2]->elements;
    const size_t begin =
        segment == 0 ? 0 : CutAt(fractions[segment - 1], source.size());
    const size_t end = segment == fractions.size()
                           ? source.size()
                           : CutAt(fractions[segment], source.size());
    child.elements.insert(child.elements.end(),
                          source.begin() + static_cast<ptrdiff_t>(begin),
                          source.begin() + static_cast<ptrdiff_t>(end));
  }
  return child;
}

Genome Mutate(const Genome& genome, const MutationParams& params,
              int max_elements, RandomStream& stream,
              std::vector<std::string>* applied) {
  Genome out = genome;
  std::vector<Element>& elements = out.elements;
  bool type_changed = false, sign_changed = false, coordinates_changed = false;
  // Element by element, in index order; for each, three decisions in a
  // fixed order (type, sign, coordinates), each one draw, then the draws
  // of the changes made.
  for (Element& e : elements) {
    if (stream.NextDouble() < params.type_rate) {
      ChangeType(e, params.input_channels, stream);
      type_changed = true;
    }
    if (stream.NextDouble() < params.sign_rate) {
      e.sign = -e.sign;
      sign_changed = true;
    }
    if (stream.NextDouble() < params.coordinate_rate) {
      double z0, z1;
      StandardNormalPair(stream, &z0, &z1);
      e.x += params.coordinate_sigma * z0;
      e.y += params.coordinate_sigma * z1;
      coordinates_changed = true;
    }
  }
  if (type_changed) applied->push_back("type");
  if (sign_changed) applied->push_back("sign");
  if (coordinates_changed) applied->push_back("coordinates");

  // Duplication: a copy of a run inserted right after it.
  if (stream.NextDouble() < params.duplication_rate && !elements.empty()) {
    const size_t length =
        RunLength(stream, params.max_run_length, elements.size());
    const size_t start =
        static_cast<size_t>(stream.Below(elements.size() - length + 1));
    const std::vector<Element> run(
        elements.begin() + static_cast<ptrdiff_t>(start),
        elements.begin() + static_cast<ptrdiff_t>(start + length));
    elements.insert(elements.begin() + static_cast<ptrdiff_t>(start + length),
                    run.begin(), run.end());
    applied->push_back("duplication");
  }
  // Deletion of a run; never of the whole genome.
  if (stream.NextDouble() < params.deletion_rate && elements.size() > 1) {
    const size_t length =
        RunLength(stream, params.max_run_length, elements.size() - 1);
    const size_t start =
        static_cast<size_t>(stream.Below(elements.size() - length + 1));
    elements.erase(elements.begin() + static_cast<ptrdiff_t>(start),
                   elements.begin() + static_cast<ptrdiff_t>(start + length));
    applied->push_back("deletion");
  }
  assert(max_elements >= 0);
  if (elements.size() > static_cast<size_t>(max_elements)) {
    elements.resize(static_cast<size_t>(max_elements));
  }
  return out;
}

Offspring MakeOffspring(uint64_t child, const std::vector<Scored>& ranked,
                        const std::function<const Genome&(uint64_t)>& genome_of,
                        const EvolutionParams& params) {
  assert(!ranked.empty());
  RandomStream selection(params.seed, child, StreamPurpose::kSelection);
  RandomStream variation(params.seed, child, StreamPurpose::kVariation);
  const bool crossover = variation.NextDouble() < params.crossover_fraction;

  Offspring offspring;
  const uint64_t first =
      ranked[Tournament(ranked.size(), params.tournament_size, selection)].id;
  offspring.parents.push_back(first);
  Genome genome;
  if (crossover) {
    const uint64_t second =
        ranked[Tournament(ranked.size(), params.tournament_size, selection)].id;
    offspring.parents.push_back(second);
    RandomStream cuts(params.seed, child, StreamPurpose::kCrossover);
    genome = Crossover(genome_of(first), genome_of(second),
                       params.crossover_points, cuts);
    offspring.operators.push_back("crossover");
  } else {
    genome = genome_of(first);
  }
  RandomStream mutation(params.seed, child, StreamPurpose::kMutation);
  offspring.genome = Mutate(genome, params.mutation, params.max_elements,
                            mutation, &offspring.operators);
  if (offspring.operators.empty()) offspring.operators.push_back("copy");
  return offspring;
}

Genome InitialCandidate(uint64_t index, const EvolutionParams& params) {
  RandomStream stream(params.seed, index, StreamPurpose::kRandomGenome);
  return RandomGenome(stream, params.initial_units, 10.0,
                      params.chemical_input);
}

}  // namespace animat
