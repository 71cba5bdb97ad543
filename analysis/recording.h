// The motion phase of one evaluation, as the analysis reads it: positions
// and actuation of every cell at evenly spaced steps, the cells' radii and
// the springs that join the cells.
//
// Built from an animat.v1.Trace (docs/formats.md): only its MOTION frames
// are used, those whose step is a multiple of the trace's spacing (a
// trace's irregular last frame is dropped). Plain value type; pure
// functions; thread-safe.
#ifndef ANIMAT_ANALYSIS_RECORDING_H_
#define ANIMAT_ANALYSIS_RECORDING_H_

#include <cstdint>
#include <vector>

#include "animat/v1/trace.pb.h"
#include "common/base/status.h"
#include "common/base/vec2.h"

namespace animat::analysis {

struct Spring {
  int a = 0;
  int b = 0;
  double rest_length = 0;  // L0 (radii).
};

struct Recording {
  int cells = 0;
  double dt = 0.05;            // Model time per simulation step.
  double actuation_max = 0.2;  // A_max (docs/model.md §7.2).
  int stride = 1;              // Simulation steps between two frames.
  std::vector<int> steps;      // Motion step of each frame, increasing.
  // Frame-major: value of cell i in frame k at [k * cells + i].
  std::vector<Vec2> position;    // Radii.
  std::vector<double> expand;    // e, in [0, 1].
  std::vector<double> contract;  // c, in [0, 1].
  std::vector<Spring> springs;   // The body's springs (may be empty).
  // Per cell (radii), > 0: the body node's radius, 1 where the trace has
  // none (body.proto's default; a trace without body nodes).
  std::vector<double> radius;

  int frames() const { return static_cast<int>(steps.size()); }
  Vec2 at(int frame, int cell) const {
    return position[static_cast<size_t>(frame) * cells + cell];
  }
  // e − c: the cell's term in its springs' rest lengths, which are
  // max(0.1, 1 + A_max·(a_i + a_j))·L0 with a = e − c (model §7.2).
  double actuation(int frame, int cell) const {
    const size_t i = static_cast<size_t>(frame) * cells + cell;
    return expand[i] - contract[i];
  }
  // Mean position of the cells (all masses are equal).
  Vec2 CentreOfMass(int frame) const;
};

// The recording of `trace`'s motion phase. kInvalidArgument, saying why,
// when the trace has fewer than 2 motion frames (a failed evaluation stops
// before motion), frames of different sizes, missing actuation, unevenly
// spaced frames, a value that is not finite, a body with another number of
// nodes than the frames' cells, or a radius that is not > 0.
Result<Recording> RecordingFromTrace(const v1::Trace& trace);

// The index of the first frame whose step is >= `step` (frames() if none).
int FrameAtOrAfter(const Recording& recording, int64_t step);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_RECORDING_H_
