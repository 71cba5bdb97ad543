// Order statistics over the animat set, and the Pareto front of speed
// against error.
//
// Pure functions. Values may be +infinity (a failed evaluation counts as an
// infinitely wrong one) but never NaN.
#ifndef ANIMAT_BENCH_ACCURACY_STATS_H_
#define ANIMAT_BENCH_ACCURACY_STATS_H_

#include <span>
#include <vector>

namespace animat::accuracy {

// The q-quantile (q in [0, 1]) with linear interpolation between the
// closest ranks (the "type 7" rule of R and NumPy): position q (n - 1) in
// the sorted values. Infinite values sort last; an interpolation that
// reaches one is infinite. NaN for an empty set.
double Quantile(std::vector<double> values, double q);

// Quantile(values, 0.5): the middle value, or the mean of the two middle
// values.
double Median(std::vector<double> values);
// Quantile(values, 0.9).
double Percentile90(std::vector<double> values);

// A candidate in the plane of cost (x, e.g. ms per evaluation) against
// error (y); smaller is better on both.
struct CostError {
  double cost = 0.0;
  double error = 0.0;
};

// Indices of the Pareto front: the points for which no other point is at
// least as good on both axes and strictly better on one. Points with a
// non-finite or negative coordinate are never on it. Equal points are all
// on it. Returned in order of increasing cost (then error, then index).
std::vector<int> ParetoFront(std::span<const CostError> points);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_STATS_H_
