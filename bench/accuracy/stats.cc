#include "bench/accuracy/stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace animat::accuracy {
namespace {

bool Usable(const CostError& p) {
  return std::isfinite(p.cost) && std::isfinite(p.error) && p.cost >= 0.0 &&
         p.error >= 0.0;
}

// a dominates b: at least as good on both axes, strictly better on one.
bool Dominates(const CostError& a, const CostError& b) {
  return a.cost <= b.cost && a.error <= b.error &&
         (a.cost < b.cost || a.error < b.error);
}

}  // namespace

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const double position = q * static_cast<double>(values.size() - 1);
  const size_t below = static_cast<size_t>(std::floor(position));
  const double fraction = position - static_cast<double>(below);
  const double lo = values[below];
  if (fraction == 0.0 || below + 1 >= values.size()) return lo;
  const double hi = values[below + 1];
  if (std::isinf(hi)) return hi;  // No inf - inf.
  return lo + fraction * (hi - lo);
}

double Median(std::vector<double> values) {
  return Quantile(std::move(values), 0.5);
}

double Percentile90(std::vector<double> values) {
  return Quantile(std::move(values), 0.9);
}

std::vector<int> ParetoFront(std::span<const CostError> points) {
  std::vector<int> front;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    if (!Usable(points[i])) continue;
    bool dominated = false;
    for (int j = 0; j < static_cast<int>(points.size()) && !dominated; ++j) {
      dominated =
          j != i && Usable(points[j]) && Dominates(points[j], points[i]);
    }
    if (!dominated) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](int a, int b) {
    if (points[a].cost != points[b].cost) {
      return points[a].cost < points[b].cost;
    }
    if (points[a].error != points[b].error) {
      return points[a].error < points[b].error;
    }
    return a < b;
  });
  return front;
}

}  // namespace animat::accuracy
