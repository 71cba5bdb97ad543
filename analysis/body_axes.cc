#include "analysis/body_axes.h"

#include <cmath>
#include <string>

#include "analysis/spectrum.h"
#include "common/base/fast_math.h"

namespace animat::analysis {
namespace {

// The best-fit rotation (least squares) taking `from` onto `to`, both
// relative to their centres, in (−π, π].
double BestRotation(const Recording& r, int from, Vec2 from_centre, int to,
                    Vec2 to_centre) {
  double cross = 0;
  double dot = 0;
  for (int i = 0; i < r.cells; ++i) {
    const Vec2 a = r.at(from, i) - from_centre;
    const Vec2 b = r.at(to, i) - to_centre;
    cross += Cross(a, b);
    dot += Dot(a, b);
  }
  if (cross == 0 && dot == 0) return 0;
  return std::atan2(cross, dot);
}

Side Classify(double value, Side positive, Side negative) {
  if (value > kOnAxis) return positive;
  if (value < -kOnAxis) return negative;
  return Side::kNone;
}

}  // namespace

Vec2 Rotate(Vec2 v, double radians) {
  double s = 0;
  double c = 0;
  SinCos(WrapAngle(radians), &s, &c);
  return {c * v.x - s * v.y, s * v.x + c * v.y};
}

Vec2 BodyAxes::FrontAt(int k) const { return Rotate(front, rotation[k]); }
Vec2 BodyAxes::LeftAt(int k) const { return Rotate(left, rotation[k]); }

Result<BodyAxes> FindBodyAxes(const Recording& recording, Window window) {
  if (window.begin < 0 || window.end > recording.frames() ||
      window.size() < 2) {
    return Status::InvalidArgument(
        "the analysis window needs at least 2 frames of the " +
        std::to_string(recording.frames()) + " recorded, got frames [" +
        std::to_string(window.begin) + ", " + std::to_string(window.end) + ")");
  }
  BodyAxes axes;
  const int n = window.size();
  for (int k = 0; k < n; ++k) {
    axes.centre.push_back(recording.CentreOfMass(window.begin + k));
  }
  double previous = 0;
  for (int k = 0; k < n; ++k) {
    const double direct = BestRotation(recording, window.begin, axes.centre[0],
                                       window.begin + k, axes.centre[k]);
    const double unwrapped =
        k == 0 ? direct : axes.rotation.back() + WrapAngle(direct - previous);
    axes.rotation.push_back(unwrapped);
    previous = direct;
  }
  Vec2 drift;
  for (int k = 0; k + 1 < n; ++k) {
    const double mid = 0.5 * (axes.rotation[k] + axes.rotation[k + 1]);
    drift += Rotate(axes.centre[k + 1] - axes.centre[k], -mid);
  }
  axes.body_frame_distance = Length(drift);
  axes.displacement = Length(axes.centre[n - 1] - axes.centre[0]);
  if (!(axes.body_frame_distance > kMinDistance)) {
    return Status::InvalidArgument(
        "the centre of mass moves less than 1e-6 radii in the analysis "
        "window: there is no direction of motion");
  }
  axes.front = drift / axes.body_frame_distance;
  axes.left = Vec2(-axes.front.y, axes.front.x);
  for (int i = 0; i < recording.cells; ++i) {
    Vec2 mean;
    for (int k = 0; k < n; ++k) {
      mean += Rotate(recording.at(window.begin + k, i) - axes.centre[k],
                     -axes.rotation[k]);
    }
    mean = mean / static_cast<double>(n);
    axes.along_front.push_back(Dot(mean, axes.front));
    axes.along_left.push_back(Dot(mean, axes.left));
    axes.front_back.push_back(
        Classify(axes.along_front.back(), Side::kFront, Side::kBack));
    axes.left_right.push_back(
        Classify(axes.along_left.back(), Side::kLeft, Side::kRight));
  }
  return axes;
}

}  // namespace animat::analysis
