// The trials of one animat under active guidance (docs/model.md §10.2): the
// path of its centre of mass in each trial, around that trial's chemical
// source, all in one picture in world axes.
//
// In the SVG each trial is a <g class="trial" data-trial="k"> holding one
// <circle class="source">, a faint <circle class="gradient"> disc of one
// decay length around it (inside the picture), and at most one <polyline
// class="path">; the start is one <circle class="start">. Pure function;
// thread-safe.
#ifndef ANIMAT_FIGURES_GUIDANCE_PLOT_H_
#define ANIMAT_FIGURES_GUIDANCE_PLOT_H_

#include <string>
#include <vector>

#include "common/base/vec2.h"

namespace animat::figures {

struct GuidanceTrialPath {
  Vec2 source;             // Radii, world axes.
  std::vector<Vec2> path;  // Centre of mass over the motion (radii).
  std::string caption;     // In the legend, e.g. "trial 0: ends 12.4 away".
};

struct GuidancePicture {
  std::string title;
  Vec2 start;                  // Centre of mass where motion starts.
  double decay_length = 10.0;  // lambda_c (radii), > 0.
  std::vector<GuidanceTrialPath> trials;
};

// The picture as an SVG document: one scale for both axes, fitting every
// source with its disc, every path and the start.
std::string GuidanceSvg(const GuidancePicture& picture);

}  // namespace animat::figures

#endif  // ANIMAT_FIGURES_GUIDANCE_PLOT_H_
