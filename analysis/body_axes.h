// The body's axes, found from its direction of motion as the paper does
// (Brainless Bodies, Fig. 4): the front–back axis points the way the
// centre of mass moves, the left–right axis is orthogonal to it (left is a
// quarter turn counter-clockwise from front).
//
// The paper's bodies swim straight; ours may turn. So the direction of
// motion is taken in the body's own frame: each frame's rotation θ is the
// best-fit rotation of the cells about the centre of mass, relative to the
// window's first frame, and the front is the direction of the sum of the
// centre of mass's steps, each turned back by its frame's θ. For a body
// that swims straight this is simply the direction of its net
// displacement. Each cell is put in front or back (left or right) by its
// mean position in that frame over the window; a cell on an axis (within
// kOnAxis, rounding) is on neither side. Lengths in radii, angles in
// radians. Pure functions; thread-safe.
#ifndef ANIMAT_ANALYSIS_BODY_AXES_H_
#define ANIMAT_ANALYSIS_BODY_AXES_H_

#include <vector>

#include "analysis/recording.h"
#include "common/base/status.h"
#include "common/base/vec2.h"

namespace animat::analysis {

// Frames [begin, end) of a recording.
struct Window {
  int begin = 0;
  int end = 0;
  int size() const { return end - begin; }
};

enum class Side { kNone, kFront, kBack, kLeft, kRight };

struct BodyAxes {
  // Unit vectors in the window's first frame, world coordinates.
  Vec2 front;
  Vec2 left;
  // Per frame of the window (index k − begin): the body's rotation since
  // the first frame (radians, unwrapped, counter-clockwise positive) and
  // the centre of mass.
  std::vector<double> rotation;
  std::vector<Vec2> centre;
  // Per cell: its mean position relative to the centre of mass, in the
  // body frame, along the front and the left axis (radii).
  std::vector<double> along_front;
  std::vector<double> along_left;
  std::vector<Side> front_back;  // kFront, kBack or kNone.
  std::vector<Side> left_right;  // kLeft, kRight or kNone.
  // The centre of mass's steps summed in the body frame (radii, >= 0),
  // and its straight-line displacement over the window (radii).
  double body_frame_distance = 0;
  double displacement = 0;

  // The front and left axes in world coordinates at window frame `k`.
  Vec2 FrontAt(int k) const;
  Vec2 LeftAt(int k) const;
};

// Less movement than this (radii) is rounding noise, not motion (the
// evolution's threshold for initial genomes, docs/model.md §9.3).
inline constexpr double kMinDistance = 1e-6;

// A cell's mean position this close to an axis (radii) is on the axis:
// rounding of the rotations would otherwise put it on a side at random.
inline constexpr double kOnAxis = 1e-9;

// The axes over `window` (at least 2 frames). kInvalidArgument when the
// window is out of range or too short, or when the centre of mass moves
// kMinDistance or less in the body frame (no direction of motion).
Result<BodyAxes> FindBodyAxes(const Recording& recording, Window window);

// `v` turned counter-clockwise by `radians`.
Vec2 Rotate(Vec2 v, double radians);

}  // namespace animat::analysis

#endif  // ANIMAT_ANALYSIS_BODY_AXES_H_
