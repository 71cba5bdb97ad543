// The command line of the Google Benchmark tools (animat-bench,
// animat-eigen-bench), checked before the library reads it: Google
// Benchmark 1.7.1 takes many malformed values silently (a repetition count
// of -5, an empty minimum time, --benchmark_color=maybe) or prints its
// usage and exits 0 (--benchmark_format=xml). Thread-safe (pure).
#ifndef ANIMAT_BENCH_BENCHMARK_FLAGS_H_
#define ANIMAT_BENCH_BENCHMARK_FLAGS_H_

#include <string>
#include <vector>

namespace animat::bench {

// Checks every argument of `arguments` (argv without the program's name)
// that is a --benchmark_* or --v flag against the flags the library's
// usage lists (--help):
// - the flags written {true|false} (list_tests, enable_random_interleaving,
//   report_aggregates_only, display_aggregates_only, counters_tabular)
//   take no value or one of true, false, yes, no, on, off, 1, 0;
// - every other flag needs "=VALUE", and no value may be empty;
// - min_time is a finite number of seconds above 0, min_warmup_time one of
//   0 or more; repetitions a whole number from 1, v one from 0 (32 bits);
// - format and out_format are console, json or csv; time_unit ns, us, ms
//   or s; color auto or a {true|false} value;
// - context is KEY=VALUE pairs separated by commas, no key empty;
// - filter is at most 1000 bytes (std::regex recurses per character) and
//   compiles as the library compiles it (std::regex, extended syntax)
//   after one leading '-' (which negates the filter) is dropped.
// Returns "--flag: why" for the first malformed one (an unknown
// --benchmark_* flag included), or "" when all are well formed. Other
// arguments are left to the library (ReportUnrecognizedArguments).
std::string MalformedBenchmarkFlag(const std::vector<std::string>& arguments);

}  // namespace animat::bench

#endif  // ANIMAT_BENCH_BENCHMARK_FLAGS_H_
