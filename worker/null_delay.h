// How long a null-evaluation worker (animat-worker --null-evaluation) takes
// over an item, so that benchmarks of the master and its dispatch see
// evaluations of realistic, varying length without simulating anything.
//
// The delay of an item is a pure function of its genome's hash (the
// WorkItem's genome_hash): log-normal with the given mean and coefficient
// of variation, drawn from the counter-based stream of common/base/rng.h.
// So the same genome takes the same time on every worker, and two
// arrangements of the same runs (a campaign, or one master per run) are
// given the same work to do.
//
// Thread-safe: pure functions.
#ifndef ANIMAT_WORKER_NULL_DELAY_H_
#define ANIMAT_WORKER_NULL_DELAY_H_

#include <cstdint>

namespace animat {

struct NullDelay {
  double mean_ms = 0;  // Mean delay, milliseconds; 0: answer at once.
  double cv = 0;       // Standard deviation over mean; 0: always the mean.

  bool none() const { return mean_ms <= 0; }
};

// The delay, in seconds, of the item whose genome hashes to `genome_hash`:
// 0 when `delay.none()`; `delay.mean_ms` / 1000 when its cv is 0;
// otherwise a log-normal draw with that mean and cv. Preconditions:
// mean_ms and cv finite and >= 0 (the worker's options check them).
double NullDelaySeconds(const NullDelay& delay, uint64_t genome_hash);

}  // namespace animat

#endif  // ANIMAT_WORKER_NULL_DELAY_H_
