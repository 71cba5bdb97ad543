#include "master/progress.h"

#include <cstdio>

namespace animat {

std::string FormatProgress(const GenerationReport& r) {
  char line[512];
  const lineage::GenerationStats& s = r.stats;
  int written = std::snprintf(
      line, sizeof(line), "generation %d/%d: ", r.generation, r.generations);
  if (s.best) {
    written += std::snprintf(
        line + written, sizeof(line) - written,
        "best %.6g (id %llu), mean %.6g, median %.6g, ", *s.best,
        static_cast<unsigned long long>(*s.best_id), *s.mean, *s.median);
  }
  written += std::snprintf(line + written, sizeof(line) - written,
                           "%d ok, %d failed | %.1f evaluations/s", s.evaluated,
                           s.failed, r.evaluations_per_second);
  if (r.seconds_left >= 0) {
    const long left = static_cast<long>(r.seconds_left + 0.5);
    std::snprintf(line + written, sizeof(line) - written,
                  " | ETA %02ld:%02ld:%02ld", left / 3600, left / 60 % 60,
                  left % 60);
  }
  return line;
}

}  // namespace animat
