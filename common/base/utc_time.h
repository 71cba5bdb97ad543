// UTC timestamps as text: "2026-11-21T14:03:07.123Z" (ISO 8601, to the
// millisecond, truncated), as in log lines (log.h) and the times the
// lineage store records (docs/lineage.md).
//
// Thread-safe: FormatUtc is a pure function; UtcNow reads the system
// clock, never for anything that reaches results.
#ifndef ANIMAT_COMMON_BASE_UTC_TIME_H_
#define ANIMAT_COMMON_BASE_UTC_TIME_H_

#include <chrono>
#include <string>

namespace animat {

// `time` in UTC. Times before 1970 count back (1 ms before the epoch is
// "1969-12-31T23:59:59.999Z"); years outside 0000-9999 print with more
// digits or a sign.
std::string FormatUtc(std::chrono::system_clock::time_point time);

// FormatUtc of the system clock's now.
std::string UtcNow();

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_UTC_TIME_H_
