#include "figures/snapshot_strip.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/svg/svg.h"

namespace animat::figures {
namespace {

using analysis::Analysis;
using analysis::Recording;

constexpr double kPanel = 170;  // Pixels per snapshot, square.
constexpr double kTop = 52;     // Heading and step labels.
constexpr double kBottom = 44;  // Caption.

const char* CellColour(double rate, double neutral) {
  if (rate > neutral) return "#d62728";   // Expanding.
  if (rate < -neutral) return "#1f77b4";  // Contracting.
  return "#2ca02c";                       // Neutral.
}

// The cell's radius (radii); 1, body.proto's default, where none is given.
double CellRadius(const Recording& recording, int cell) {
  return static_cast<size_t>(cell) < recording.radius.size()
             ? recording.radius[cell]
             : 1.0;
}

}  // namespace

Result<std::vector<int>> CycleFrames(const Recording& recording,
                                     const Analysis& analysis,
                                     const StripOptions& options) {
  if (!analysis.period_steps) {
    // Another window helps only an animat that actuates somewhere.
    return Status::InvalidArgument(
        "the actuation has no dominant period in " +
        analysis::DescribeWindow(analysis) + ", so there is no cycle to show" +
        (analysis.actuation ? "; --from and --to choose another window" : ""));
  }
  if (options.snapshots < 1) {
    return Status::InvalidArgument("at least one snapshot is needed");
  }
  const int64_t start = options.start_step.value_or(analysis.from_step);
  const int first = analysis::FrameAtOrAfter(recording, start);
  const double period_frames = *analysis.period_steps / recording.stride;
  const int last = first + static_cast<int>(std::lround(period_frames));
  if (last >= recording.frames() || start < recording.steps.front()) {
    return Status::InvalidArgument(
        "a cycle of " + svg::Number(*analysis.period_steps, 1) +
        " steps from step " + std::to_string(start) +
        " does not fit in the motion recorded (steps " +
        std::to_string(recording.steps.front()) + " to " +
        std::to_string(recording.steps.back()) +
        "); window: " + analysis::DescribeWindow(analysis) +
        "; --start, --from and --to choose another");
  }
  if (options.snapshots > last - first) {
    return Status::InvalidArgument(
        std::to_string(options.snapshots) +
        " snapshots are more than the frames recorded in one cycle (" +
        std::to_string(last - first) + ")");
  }
  std::vector<int> frames;
  for (int j = 0; j < options.snapshots; ++j) {
    frames.push_back(first + static_cast<int>(std::lround(j * period_frames /
                                                          options.snapshots)));
  }
  frames.push_back(last);
  return frames;
}

namespace {

// World to the drawing frame: origin at the first centre of mass, front
// to the right.
struct DrawingFrame {
  Vec2 origin;
  double heading = 0.0;
  Vec2 operator()(Vec2 world) const {
    return analysis::Rotate(world - origin, -heading);
  }
};

// What every snapshot's cells cover in the drawing frame: the larger side
// (radii) and the middle.
struct Bounds {
  double extent = 0.0;
  Vec2 middle;
};

Bounds SnapshotBounds(const Recording& recording,
                      const std::vector<int>& frames,
                      const DrawingFrame& body) {
  double lo_x = std::numeric_limits<double>::infinity();
  double lo_y = lo_x;
  double hi_x = -lo_x;
  double hi_y = -lo_x;
  for (int k : frames) {
    for (int i = 0; i < recording.cells; ++i) {
      const Vec2 p = body(recording.at(k, i));
      const double r = CellRadius(recording, i);
      lo_x = std::min(lo_x, p.x - r);
      hi_x = std::max(hi_x, p.x + r);
      lo_y = std::min(lo_y, p.y - r);
      hi_y = std::max(hi_y, p.y + r);
    }
  }
  return {std::max(hi_x - lo_x, hi_y - lo_y),
          Vec2((lo_x + hi_x) / 2, (lo_y + hi_y) / 2)};
}

// Frame k's cells (discs of their radius, coloured by their actuation's
// rate), springs and centre of mass, in the panel whose left edge is
// `left`; `pixel` maps the drawing frame to pixels, `scale` pixels per
// radius.
template <typename Pixel>
void DrawSnapshot(const Recording& recording, const StripOptions& options,
                  const DrawingFrame& body, int k, int first, double left,
                  Pixel pixel, double scale, svg::SvgWriter* svg) {
  svg->Rect({left + 2, kTop}, kPanel - 4, kPanel, "none", "#cccccc");
  svg->Text(
      {left + kPanel / 2, kTop - 8},
      "t = " + std::to_string(recording.steps[k] - recording.steps[first]), 12,
      "middle");
  for (int i = 0; i < recording.cells; ++i) {
    const double rate =
        k > 0 ? (recording.actuation(k, i) - recording.actuation(k - 1, i)) /
                    recording.stride
              : 0.0;
    svg->Circle(pixel(body(recording.at(k, i))),
                CellRadius(recording, i) * scale,
                CellColour(rate, options.neutral_rate), "black", "cell");
  }
  for (const analysis::Spring& s : recording.springs) {
    svg->Line(pixel(body(recording.at(k, s.a))),
              pixel(body(recording.at(k, s.b))), "#444444", 1, "spring");
  }
  // The centre of mass at the cycle's start (cross) and now (dot).
  const Vec2 start = pixel({0, 0});
  svg->Line(start - Vec2(5, 0), start + Vec2(5, 0), "black", 1);
  svg->Line(start - Vec2(0, 5), start + Vec2(0, 5), "black", 1);
  svg->Circle(pixel(body(recording.CentreOfMass(k))), 2.5, "black", "");
}

}  // namespace

Result<std::string> SnapshotStripSvg(const Recording& recording,
                                     const Analysis& analysis,
                                     const StripOptions& options) {
  Result<std::vector<int>> frames = CycleFrames(recording, analysis, options);
  if (!frames.ok()) return frames.status();
  const int first = frames->front();
  const int last = frames->back();

  // The drawing frame: origin at the first centre of mass, front to the
  // right (the body's rotation at the first frame, from the analysis
  // window's nearest frame).
  const int in_window =
      std::clamp(first - analysis.window.begin, 0, analysis.window.size() - 1);
  const Vec2 front = analysis.axes.FrontAt(in_window);
  const DrawingFrame body{recording.CentreOfMass(first),
                          std::atan2(front.y, front.x)};

  // One scale for every snapshot: the extent of all of them.
  const Bounds bounds = SnapshotBounds(recording, *frames, body);
  const double extent = bounds.extent;
  const double scale = (kPanel - 16) / extent;  // Pixels per radius.
  const Vec2 middle = bounds.middle;

  const int snapshots = options.snapshots;
  const double width = snapshots * kPanel;
  svg::SvgWriter svg(width, kTop + kPanel + kBottom);
  const double cycle_steps = recording.steps[last] - recording.steps[first];
  svg.Title("One motion cycle (" + svg::Number(cycle_steps, 0) + " steps)");
  svg.Text({8, 18},
           "One cycle of " + svg::Number(cycle_steps, 0) +
               " steps from motion step " +
               std::to_string(recording.steps[first]) +
               "; red: expanding, blue: contracting, green: neutral",
           13);
  for (int j = 0; j < snapshots; ++j) {
    const int k = (*frames)[j];
    const double left = j * kPanel;
    // World (body frame) to pixels, y up.
    auto pixel = [&](Vec2 p) {
      return Vec2(left + kPanel / 2 + (p.x - middle.x) * scale,
                  kTop + kPanel / 2 - (p.y - middle.y) * scale);
    };
    svg.BeginGroup("snapshot",
                   "data-step=\"" + std::to_string(recording.steps[k]) + "\"");
    DrawSnapshot(recording, options, body, k, first, left, pixel, scale, &svg);
    if (j == snapshots - 1) {
      svg.Arrow(pixel({0, 0}), pixel(body(recording.CentreOfMass(last))),
                "black", 7, "distance");
    }
    svg.EndGroup();
  }
  const double moved =
      Length(recording.CentreOfMass(last) - recording.CentreOfMass(first));
  svg.Text({8, kTop + kPanel + 24},
           "Arrow (last panel): the centre of mass moves " +
               svg::Number(moved, 4) +
               " radii in the cycle (cross: where it started). Panels " +
               svg::Number(extent, 1) + " radii wide; front to the right.",
           12);
  return svg.Finish();
}

}  // namespace animat::figures
