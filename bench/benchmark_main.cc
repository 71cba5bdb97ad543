// The main of the Google Benchmark tools (animat-bench, animat-eigen-bench):
// BENCHMARK_MAIN's steps, after the command line's --benchmark_* and --v
// values are checked (bench/benchmark_flags.h).
//
// Exit 0 after the run, --help or --benchmark_list_tests; 1 for an argument
// the library does not know (it names it), or an output file it cannot
// open; 2 for a malformed value ("PROGRAM: --flag: why" on stderr).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "bench/benchmark_flags.h"

int main(int argc, char** argv) {
  const std::string program =
      argc > 0 ? std::filesystem::path(argv[0]).filename().string()
               : std::string("benchmark");
  const std::vector<std::string> arguments(argv + (argc > 0 ? 1 : 0),
                                           argv + argc);
  if (const std::string why = animat::bench::MalformedBenchmarkFlag(arguments);
      !why.empty()) {
    std::cerr << program << ": " << why << "\nRun with --help for the flags.\n";
    return 2;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
