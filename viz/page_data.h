// The data a replay page shows, taken from a trace (animat.v1.Trace) and
// written as JSON: development snapshots, then equilibration and motion
// frames, the body's radii, springs and skin, each node's actuation, the
// result (with its deepest unjoined overlap where recorded), and with
// guidance the chemical sources and the recorded trial.
// docs/formats.md ("animat render") describes the JSON.
//
// Pure functions; thread-safe.
#ifndef ANIMAT_VIZ_PAGE_DATA_H_
#define ANIMAT_VIZ_PAGE_DATA_H_

#include <string>

#include "animat/v1/trace.pb.h"
#include "common/base/status.h"
#include "viz/actuation.h"

namespace animat::viz {

struct PageOptions {
  std::string title;  // Heading and window title (plain text).
  // Below this |Δ(e − c)| per step a cell is neutral (green); >= 0.
  double neutral_rate = kDefaultNeutralRate;
};

// Positions and development radii are written with 4 decimals (1e-4 cell
// radii); the body's radii, the fitness and the deepest overlap exactly; a
// non-finite position (the last frame of a numerical failure) becomes
// null. Strings are escaped so that the JSON can sit inside an HTML
// <script> element ('<', '>' and '&' as \u escapes).
//
// Fails with kInvalidArgument, saying where, when the trace has nothing to
// show (no snapshot and no frame: the message gives the result's status
// and reason), when arrays of one snapshot or frame disagree in length,
// a frame's node count differs from the body's, a body node's radius is
// not finite and > 0, a spring or skin edge names a node the body lacks,
// a frame's phase is unspecified, steps do not increase within a phase,
// the result's max_overlap is not in [0, 1], or the guidance part has no
// source, sources of unequal lengths or not finite, a trial out of range
// or a decay length that is not finite and > 0.
Result<std::string> PageDataJson(const v1::Trace& trace,
                                 const PageOptions& options);

}  // namespace animat::viz

#endif  // ANIMAT_VIZ_PAGE_DATA_H_
