#include "common/base/log.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>

namespace animat {

void StderrSink(std::string_view line) {
  const auto now = std::chrono::system_clock::now();
  const std::time_t seconds = std::chrono::system_clock::to_time_t(now);
  const int millis =
      static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(
                           now.time_since_epoch())
                           .count() %
                       1000);
  std::tm utc;
  gmtime_r(&seconds, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%dT%H:%M:%S", &utc);
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  std::fprintf(stderr, "%s.%03dZ %.*s\n", stamp, millis,
               static_cast<int>(line.size()), line.data());
  std::fflush(stderr);
}

LogSink Prefixed(std::string component, LogSink sink) {
  return [component = std::move(component),
          sink = std::move(sink)](std::string_view line) {
    sink(component + ": " + std::string(line));
  };
}

}  // namespace animat
