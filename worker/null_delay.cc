#include "worker/null_delay.h"

#include <cmath>
#include <numbers>

#include "common/base/rng.h"

namespace animat {

double NullDelaySeconds(const NullDelay& delay, uint64_t genome_hash) {
  if (delay.none()) return 0;
  const double mean = delay.mean_ms / 1000;
  if (delay.cv <= 0) return mean;
  // ln X ~ N(mu, sigma^2) with E[X] = mean and sd[X] / E[X] = cv.
  const double sigma2 = std::log1p(delay.cv * delay.cv);
  const double mu = std::log(mean) - sigma2 / 2;
  RandomStream stream(genome_hash, 0, StreamPurpose::kNullDelay);
  // Box–Muller; 1 - u is in (0, 1], so its logarithm is finite.
  const double u = stream.NextDouble();
  const double v = stream.NextDouble();
  const double normal =
      std::sqrt(-2 * std::log(1 - u)) * std::cos(2 * std::numbers::pi * v);
  return std::exp(mu + std::sqrt(sigma2) * normal);
}

}  // namespace animat
