// Wall and CPU time for the benchmarks' reports. Thread-safe.
#ifndef ANIMAT_BENCH_TIMING_H_
#define ANIMAT_BENCH_TIMING_H_

#include <sys/resource.h>

#include <chrono>

namespace animat::bench {

using Clock = std::chrono::steady_clock;

// Seconds of wall time since `start`.
inline double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// User + system CPU seconds of this process (RUSAGE_SELF), of the calling
// thread (RUSAGE_THREAD) or of the process's waited-for children
// (RUSAGE_CHILDREN).
inline double CpuSeconds(int who) {
  rusage usage = {};
  getrusage(who, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec +
                                    usage.ru_stime.tv_usec);
}

}  // namespace animat::bench

#endif  // ANIMAT_BENCH_TIMING_H_
