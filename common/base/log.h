// One-line log records: "2026-11-21T14:03:07.123Z worker: message".
//
// A LogSink is where a component's lines go; components take one in their
// options (default: standard error), so tests can capture them. Sinks must
// be callable from any thread; StderrSink is.
#ifndef ANIMAT_COMMON_BASE_LOG_H_
#define ANIMAT_COMMON_BASE_LOG_H_

#include <functional>
#include <string>
#include <string_view>

namespace animat {

using LogSink = std::function<void(std::string_view line)>;

// Writes the line, with a UTC timestamp in front, to standard error.
void StderrSink(std::string_view line);

// A sink that prefixes "<component>: " and forwards to `sink`.
LogSink Prefixed(std::string component, LogSink sink);

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_LOG_H_
