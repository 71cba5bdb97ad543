// What each cell does to its springs in a motion frame, as the paper's
// Fig. 4 colours it: expanding (red), contracting (blue) or neither
// (green).
//
// A cell's springs have rest length max(0.1, 1 + A_max·(e_i + e_j − c_i −
// c_j))·L0 (model §7.2), so the cell lengthens them while e − c rises and
// shortens them while it falls. The rate is the change of e − c between two
// recorded frames divided by the steps between them. Pure functions;
// thread-safe.
#ifndef ANIMAT_VIZ_ACTUATION_H_
#define ANIMAT_VIZ_ACTUATION_H_

#include <vector>

#include "animat/v1/trace.pb.h"

namespace animat::viz {

enum class Actuation { kNeutral, kExpanding, kContracting };

// A cell is neutral while |Δ(e − c)| per step stays below this: 1/1000 of
// the fastest change possible (e and c each move by at most 2·Δt = 0.1 per
// step, model §3.1). Measured: the cells of the sample genome change by
// 3e-4–4e-3 per step; those of a quickstart run's best by up to 4e-3.
inline constexpr double kDefaultNeutralRate = 2e-4;

// 'e' (expanding), 'c' (contracting) or 'n' (neutral).
char ActuationCode(Actuation actuation);

// The steps from `previous` to `current`: the difference of their steps
// within one phase; across phases (equilibration then motion, where e and
// c were frozen during equilibration) the steps of `current`'s phase,
// at least 1.
int StepsBetween(const v1::MotionFrame& previous,
                 const v1::MotionFrame& current);

// One entry per node of `current`: the sign of the rate of e − c since
// `previous`, neutral when its magnitude is below `neutral_rate`. With no
// `previous` (the first frame), or a node whose values are missing or not
// finite in either frame, the node is neutral. Preconditions: both frames
// have as many expand and contract values as nodes, or none, and `current`
// comes after `previous` (StepsBetween >= 1).
std::vector<Actuation> ClassifyActuation(const v1::MotionFrame* previous,
                                         const v1::MotionFrame& current,
                                         double neutral_rate);

}  // namespace animat::viz

#endif  // ANIMAT_VIZ_ACTUATION_H_
