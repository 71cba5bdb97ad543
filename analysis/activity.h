// Cell activity as the paper defines it (Brainless Bodies, Fig. 4.2): the
// absolute change from the previous step of what the cell does to its
// springs' rest lengths, |Δ(e − c)| (model §7.2), here per simulation step:
// between frames k − 1 and k of a recording, |a(k) − a(k−1)| / stride with
// a = e − c. With one frame per step (stride 1) this is exactly the
// paper's quantity; a coarser recording gives the mean rate over each
// interval. Units: actuation (e − c, dimensionless) per step; at most 0.1
// (e and c each move at most Δt = 0.05 per step, model §3.1).
//
// Pure functions; thread-safe.
#ifndef ANIMAT_ANALYSIS_ACTIVITY_H_
#define ANIMAT_ANALYSIS_ACTIVITY_H_

#include <vector>

#include "analysis/body_axes.h"
#include "analysis/recording.h"

namespace animat::analysis {

// The activity of `cell` between frames `frame` − 1 and `frame` (>= 1).
double Activity(const Recording& recording, int frame, int cell);

// The mean activity of the cells on each side of the body, one value per
// frame of the window after the recording's first frame. A side without
// cells has an empty series.
struct ActivitySeries {
  std::vector<int> steps;  // The motion step each value ends at.
  std::vector<double> front, back, left, right;
  std::vector<double> all;  // Every cell.
};

ActivitySeries ActivityAlongAxes(const Recording& recording,
                                 const BodyAxes& axes, Window window);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_ACTIVITY_H_
