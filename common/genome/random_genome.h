// Random genomes for the initial population (docs/model.md §9).
//
// Deterministic: the genome is a pure function of the stream's key.
#ifndef ANIMAT_COMMON_GENOME_RANDOM_GENOME_H_
#define ANIMAT_COMMON_GENOME_RANDOM_GENOME_H_

#include "common/base/rng.h"
#include "common/genome/genome.h"

namespace animat {

// `units` regulatory units of one P and one G element each (G_INTERNAL or
// G_MORPHOGEN with equal chance), never split by an S element, plus one
// S_IN per input channel and one S_OUT per output channel; the units and S
// elements appear in a uniformly random order. Signs are +1 or -1 with
// equal chance; coordinates are uniform in [0, coordinate_max)^2.
// The S_IN elements are the paper's four channels (kPaperInputChannels).
// With `chemical` (a run with guidance, docs/model.md §10.2), one S_IN
// element of the CHEMICAL channel is then drawn (sign, coordinates) and
// inserted at a uniformly drawn boundary between units and S elements:
// every earlier draw is the same, so the genome is the one drawn without
// `chemical` plus that element. Precondition: units >= 0.
Genome RandomGenome(RandomStream& stream, int units = 10,
                    double coordinate_max = 10.0, bool chemical = false);

}  // namespace animat

#endif  // ANIMAT_COMMON_GENOME_RANDOM_GENOME_H_
