// The chemical of active guidance (docs/model.md §10.2): where a trial's
// source lies and what each cell senses of it.
//
// Pure functions of their arguments; thread-safe.
#ifndef ANIMAT_COMMON_EVALUATION_CHEMICAL_H_
#define ANIMAT_COMMON_EVALUATION_CHEMICAL_H_

#include <span>
#include <vector>

#include "common/base/vec2.h"
#include "common/body/body.h"

namespace animat {

// The source of guidance trial `trial` of `trials` (>= 1): `distance`
// (radii) from `start` in the direction at angle 2 pi (trial + 1/2) /
// trials of the world axes.
Vec2 GuidanceSource(Vec2 start, int trial, int trials, double distance);

// The cells that sense the chemical: those at an end of a skin edge of
// `body` (model §6.2), in increasing order.
std::vector<int> SkinCells(const Body& body);

// The CHEMICAL input of every cell at `position` (one per cell):
// exp(-|position[c] - source| / decay_length) for the cells in
// `skin_cells`, 0 for the others. `*values` is resized to position.size().
// Preconditions: decay_length > 0; every skin cell indexes `position`.
void SenseChemical(Vec2 source, double decay_length,
                   std::span<const int> skin_cells,
                   std::span<const Vec2> position, std::vector<double>* values);

}  // namespace animat

#endif  // ANIMAT_COMMON_EVALUATION_CHEMICAL_H_
