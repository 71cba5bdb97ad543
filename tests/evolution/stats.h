// Statistics helpers for the evolution tests: every check draws from fixed
// streams, so each test is deterministic; the bounds only say how far from
// the expectation a correct implementation could plausibly be.
#ifndef ANIMAT_TESTS_EVOLUTION_STATS_H_
#define ANIMAT_TESTS_EVOLUTION_STATS_H_

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace animat::testing {

// Pearson's chi-square statistic of `counts` against probabilities `p`.
inline double ChiSquare(const std::vector<int64_t>& counts,
                        const std::vector<double>& p) {
  int64_t total = 0;
  for (int64_t c : counts) total += c;
  double chi2 = 0.0;
  for (size_t i = 0; i < counts.size(); ++i) {
    const double expected = p[i] * static_cast<double>(total);
    const double d = static_cast<double>(counts[i]) - expected;
    chi2 += d * d / expected;
  }
  return chi2;
}

// Merges the last bins into one until every bin expects at least
// `min_expected` (the chi-square approximation needs that); bins are
// ordered so that the rare ones are last.
inline void PoolTail(std::vector<int64_t>* counts, std::vector<double>* p,
                     double min_expected) {
  int64_t total = 0;
  for (int64_t c : *counts) total += c;
  while (p->size() > 2 &&
         p->back() * static_cast<double>(total) < min_expected) {
    (*p)[p->size() - 2] += p->back();
    (*counts)[counts->size() - 2] += counts->back();
    p->pop_back();
    counts->pop_back();
  }
}

// A bound the statistic of a correct sampler exceeds with probability
// well below 1e-4: mean (df) plus six standard deviations (sqrt(2 df)).
inline double ChiSquareBound(size_t categories) {
  const double df = static_cast<double>(categories - 1);
  return df + 6.0 * std::sqrt(2.0 * df);
}

// Half-width of a 5-sigma interval for a proportion p over n trials.
inline double ProportionTolerance(double p, int64_t n) {
  return 5.0 * std::sqrt(p * (1.0 - p) / static_cast<double>(n));
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_EVOLUTION_STATS_H_
