// The paper's Fig. 4.1: snapshots of a swimming animat over one cycle of
// its dominant period, side by side, with the distance its centre of mass
// travels in the cycle.
//
// Every snapshot is drawn in the same frame: the centre of mass at the
// cycle's start is the origin and the body's front axis at that moment
// points right, so the body's drift shows from panel to panel and the
// arrow in the last panel is the centre of mass's displacement over the
// cycle, to scale. Cells are discs of their radius (Recording::radius), the
// springs drawn over them, coloured as in the paper by what they do to
// their springs at that moment: red while e − c rises (expanding), blue
// while it falls (contracting), green while its rate is below the neutral
// rate. In the SVG each snapshot is a <g class="snapshot"> holding one
// <circle class="cell"> per cell and one <line class="spring"> per spring;
// the arrow is a <g class="distance">. Pure functions; thread-safe.
#ifndef ANIMAT_FIGURES_SNAPSHOT_STRIP_H_
#define ANIMAT_FIGURES_SNAPSHOT_STRIP_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analyze.h"
#include "analysis/recording.h"
#include "common/base/status.h"

namespace animat::figures {

struct StripOptions {
  int snapshots = 6;  // >= 1.
  // The cycle's first motion step; default: the analysis window's start.
  std::optional<int64_t> start_step;
  // |Δ(e − c)| per step below which a cell is drawn neutral (green).
  double neutral_rate = 1e-3;
};

// The frames shown: `snapshots` frames evenly spread over one period from
// the frame at `start_step`, and last the frame one period after it (where
// the arrow ends). kInvalidArgument when the analysis has no period, or
// the cycle does not fit in the recording.
Result<std::vector<int>> CycleFrames(const analysis::Recording& recording,
                                     const analysis::Analysis& analysis,
                                     const StripOptions& options);

// The strip as an SVG document; errors as CycleFrames.
Result<std::string> SnapshotStripSvg(const analysis::Recording& recording,
                                     const analysis::Analysis& analysis,
                                     const StripOptions& options);

}  // namespace animat::figures

#endif  // ANIMAT_FIGURES_SNAPSHOT_STRIP_H_
