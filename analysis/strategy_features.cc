#include "analysis/strategy_features.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/base/fast_math.h"

namespace animat::analysis {
namespace {

// Harmonics of the dominant period that count as regular.
constexpr int kHarmonics = 8;
// A lag sum below this (periods) is no travelling wave.
constexpr double kMinWave = 0.02;
// Actuation more irregular than this has no stroke (a drift, or noise).
constexpr double kAperiodic = 0.5;
// A step of the mean e − c below this share of its mean |step| holds still.
constexpr double kHold = 0.05;
// Forward speed below this share of the mean is coasting.
constexpr double kSlow = 0.5;
// Each end of the body is this share of its front–back length.
constexpr double kEnd = 0.25;
// Ends whose taper is below this are alike (rounding picks no end).
constexpr double kAlike = 1e-9;
// Ends that move less than this (radii, root mean square) keep still.
constexpr double kStill = 1e-6;

// 1 − |Z_x − Z_y| / (|Z_x| + |Z_y|) of the sides' components.
std::optional<double> Symmetry(const SideSummary& x, const SideSummary& y) {
  if (x.cells == 0 || y.cells == 0 || !x.actuation || !y.actuation) {
    return std::nullopt;
  }
  const double a = x.actuation->amplitude;
  const double b = y.actuation->amplitude;
  if (!(a + b > 0)) return std::nullopt;
  double s = 0;
  double c = 0;
  SinCos(WrapAngle(x.actuation->phase - y.actuation->phase), &s, &c);
  const double difference =
      std::sqrt(std::max(0.0, a * a + b * b - 2 * a * b * c));
  return 1 - difference / (a + b);
}

// 1 − ‖x − y‖ / (‖x‖ + ‖y‖) of two sides' activity curves less their
// means; undefined for a side without cells or two flat curves.
std::optional<double> RectifiedSymmetry(const std::vector<double>& x,
                                        const std::vector<double>& y) {
  if (x.empty() || x.size() != y.size()) return std::nullopt;
  double mean_x = 0;
  double mean_y = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    mean_x += x[k] / x.size();
    mean_y += y[k] / y.size();
  }
  double xx = 0;
  double yy = 0;
  double dd = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    const double u = x[k] - mean_x;
    const double v = y[k] - mean_y;
    xx += u * u;
    yy += v * v;
    dd += (u - v) * (u - v);
  }
  const double norms = std::sqrt(xx) + std::sqrt(yy);
  if (!(norms > 0)) return std::nullopt;
  return std::max(0.0, 1 - std::sqrt(dd) / norms);
}

void MeasureSides(const Analysis& a, StrategyFeatures* f) {
  f->lr_symmetry = Symmetry(a.left, a.right);
  f->fb_symmetry = Symmetry(a.front, a.back);
  f->lr_symmetry_rectified =
      RectifiedSymmetry(a.activity.left, a.activity.right);
  f->fb_symmetry_rectified =
      RectifiedSymmetry(a.activity.front, a.activity.back);
  if (a.front_to_back) f->fb_lag = a.front_to_back->periods;
  if (a.left_to_right) f->lr_lag = a.left_to_right->periods;
  if (a.front.actuation && a.back.actuation && a.front.cells > 0 &&
      a.back.cells > 0) {
    const double front = a.front.actuation->amplitude;
    const double back = a.back.actuation->amplitude;
    if (front + back > 0) {
      f->fb_amplitude_gradient = (back - front) / (front + back);
    }
  }
  if (f->fb_lag && f->lr_lag) {
    const double sum = std::abs(*f->lr_lag) + std::abs(*f->fb_lag);
    if (sum >= kMinWave) f->wave_across = std::abs(*f->lr_lag) / sum;
  }
}

// The share of the variance of the cells' e − c that the dominant period
// and its harmonics do not explain.
void MeasureIrregularity(const Recording& r, const Analysis& a,
                         StrategyFeatures* f) {
  if (!a.period_steps) return;
  const double frequency = r.stride / *a.period_steps;  // Per frame.
  const Window w = a.window;
  std::vector<double> signal(w.size());
  double variance = 0;
  double explained = 0;
  for (int i = 0; i < r.cells; ++i) {
    double mean = 0;
    for (int k = w.begin; k < w.end; ++k) {
      signal[k - w.begin] = r.actuation(k, i);
      mean += r.actuation(k, i) / w.size();
    }
    for (double x : signal) variance += (x - mean) * (x - mean) / w.size();
    for (int h = 1; h <= kHarmonics && h * frequency <= 0.5; ++h) {
      const double amplitude = ComponentAt(signal, h * frequency).amplitude;
      explained += amplitude * amplitude / 2;
    }
  }
  if (variance > 0) {
    f->irregularity = std::clamp(1 - explained / variance, 0.0, 1.0);
  }
}

// The stroke of the cells' mean e − c, `common`, frame by frame: how its
// changing steps divide into rising and falling, and how many hold still.
void MeasureStroke(const std::vector<double>& common, StrategyFeatures* f) {
  double mean_step = 0;
  for (size_t k = 1; k < common.size(); ++k) {
    mean_step += std::abs(common[k] - common[k - 1]);
  }
  mean_step /= static_cast<double>(common.size() - 1);
  if (!(mean_step > 0)) return;
  int rising = 0;
  int falling = 0;
  int still = 0;
  for (size_t k = 1; k < common.size(); ++k) {
    const double step = common[k] - common[k - 1];
    if (step > kHold * mean_step) {
      ++rising;
    } else if (step < -kHold * mean_step) {
      ++falling;
    } else {
      ++still;
    }
  }
  const double changing = rising + falling;  // > 0 since mean_step > 0.
  f->rise_fraction = rising / changing;
  f->stroke_asymmetry = std::abs(rising - falling) / changing;
  f->holding = still / static_cast<double>(rising + falling + still);
}

// Synchrony, and the stroke of the cells' mean e − c when the actuation
// is periodic (irregularity at most kAperiodic): a drift has no stroke.
void MeasureCommonMode(const Recording& r, const Analysis& a,
                       StrategyFeatures* f) {
  const Window w = a.window;
  const int cells = r.cells;
  std::vector<double> mean_of_cell(cells, 0.0);
  std::vector<double> common;
  for (int k = w.begin; k < w.end; ++k) {
    double sum = 0;
    for (int i = 0; i < cells; ++i) {
      mean_of_cell[i] += r.actuation(k, i);
      sum += r.actuation(k, i);
    }
    common.push_back(sum / cells);
  }
  for (double& m : mean_of_cell) m /= w.size();
  double common_power = 0;  // N Σ_t m̃(t)², m̃ the mean of x̃_i.
  double total_power = 0;   // Σ_i Σ_t x̃_i(t)².
  for (int k = w.begin; k < w.end; ++k) {
    double sum = 0;
    for (int i = 0; i < cells; ++i) {
      const double x = r.actuation(k, i) - mean_of_cell[i];
      sum += x;
      total_power += x * x;
    }
    common_power += sum * sum / cells;
  }
  if (total_power > 0) {
    f->synchrony = std::min(1.0, common_power / total_power);
  }
  if (f->irregularity && *f->irregularity <= kAperiodic) {
    MeasureStroke(common, f);
  }
}

// The share of the window's intervals whose forward speed is below kSlow
// of the mean.
void MeasureCoasting(const Analysis& a, StrategyFeatures* f) {
  const BodyAxes& axes = a.axes;
  const int intervals = static_cast<int>(axes.centre.size()) - 1;
  if (intervals < 1) return;
  std::vector<double> forward;
  double mean = 0;
  for (int k = 0; k < intervals; ++k) {
    const double mid = 0.5 * (axes.rotation[k] + axes.rotation[k + 1]);
    const double v =
        Dot(Rotate(axes.centre[k + 1] - axes.centre[k], -mid), axes.front);
    forward.push_back(v);
    mean += v / intervals;
  }
  if (!(mean > 0)) return;
  int slow = 0;
  for (double v : forward) slow += v < kSlow * mean ? 1 : 0;
  f->coasting = static_cast<double>(slow) / intervals;
}

// Elongation and end taper of the mean body.
void MeasureShape(const Analysis& a, StrategyFeatures* f) {
  const std::vector<double>& x = a.axes.along_front;
  const std::vector<double>& y = a.axes.along_left;
  const size_t n = x.size();
  if (n == 0) return;
  double mx = 0;
  double my = 0;
  for (size_t i = 0; i < n; ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double cxx = 0;
  double cyy = 0;
  double cxy = 0;
  for (size_t i = 0; i < n; ++i) {
    cxx += (x[i] - mx) * (x[i] - mx) / n;
    cyy += (y[i] - my) * (y[i] - my) / n;
    cxy += (x[i] - mx) * (y[i] - my) / n;
  }
  const double half_trace = 0.5 * (cxx + cyy);
  const double root = std::sqrt(0.25 * (cxx - cyy) * (cxx - cyy) + cxy * cxy);
  const double major = half_trace + root;
  const double minor = std::max(0.0, half_trace - root);
  if (major > 0) f->elongation = 1 - std::sqrt(minor / major);

  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double length = *hi - *lo;
  if (!(length > 0)) return;
  double front_min = 0, front_max = 0, back_min = 0, back_max = 0;
  bool front_seen = false;
  bool back_seen = false;
  for (size_t i = 0; i < n; ++i) {
    if (x[i] >= *hi - kEnd * length) {
      front_min = front_seen ? std::min(front_min, y[i]) : y[i];
      front_max = front_seen ? std::max(front_max, y[i]) : y[i];
      front_seen = true;
    }
    if (x[i] <= *lo + kEnd * length) {
      back_min = back_seen ? std::min(back_min, y[i]) : y[i];
      back_max = back_seen ? std::max(back_max, y[i]) : y[i];
      back_seen = true;
    }
  }
  const double front_width = front_max - front_min;
  const double back_width = back_max - back_min;
  f->end_taper = front_width + back_width > 0
                     ? (back_width - front_width) / (front_width + back_width)
                     : 0.0;
}

// How far the back quarter's cells move in the body frame against the
// front quarter's.
void MeasureBackProtrusion(const Recording& r, const Analysis& a,
                           StrategyFeatures* f) {
  const BodyAxes& axes = a.axes;
  const std::vector<double>& x = axes.along_front;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  const double length = *hi - *lo;
  if (!(length > 0)) return;
  const int cells = r.cells;
  const int n = a.window.size();
  std::vector<double> square(cells, 0.0);  // Σ_t |q_i(t) − q̄_i|².
  for (int k = 0; k < n; ++k) {
    const Vec2 front = axes.FrontAt(k);
    const Vec2 left = axes.LeftAt(k);
    for (int i = 0; i < cells; ++i) {
      const Vec2 d = r.at(a.window.begin + k, i) - axes.centre[k];
      const double along = Dot(d, front) - x[i];
      const double across = Dot(d, left) - axes.along_left[i];
      square[i] += along * along + across * across;
    }
  }
  double back = 0;
  double front = 0;
  int back_cells = 0;
  int front_cells = 0;
  for (int i = 0; i < cells; ++i) {
    const double rms = std::sqrt(square[i] / n);
    if (x[i] <= *lo + kEnd * length) {
      back += rms;
      ++back_cells;
    }
    if (x[i] >= *hi - kEnd * length) {
      front += rms;
      ++front_cells;
    }
  }
  back /= back_cells;
  front /= front_cells;
  if (back + front > kStill) f->back_protrusion = back / (back + front);
}

}  // namespace

StrategyFeatures MeasureStrategyFeatures(const Recording& recording,
                                         const Analysis& analysis) {
  StrategyFeatures f;
  MeasureSides(analysis, &f);
  MeasureIrregularity(recording, analysis, &f);
  MeasureCommonMode(recording, analysis, &f);
  MeasureCoasting(analysis, &f);
  MeasureShape(analysis, &f);
  MeasureBackProtrusion(recording, analysis, &f);
  if (f.rise_fraction && f.end_taper) {
    // (falling − rising) / changing = 1 − 2 × rise_fraction.
    const double t = *f.end_taper;
    const double sign = t > kAlike ? 1.0 : t < -kAlike ? -1.0 : 0.0;
    f.stroke_agreement = sign * (1 - 2 * *f.rise_fraction);
  }
  return f;
}

}  // namespace animat::analysis
