#include "common/base/log.h"

#include <cstdio>
#include <mutex>

#include "common/base/utc_time.h"

namespace animat {

void StderrSink(std::string_view line) {
  const std::string stamp = UtcNow();
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  std::fprintf(stderr, "%s %.*s\n", stamp.c_str(),
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
