// The check of the Google Benchmark tools' command line
// (bench/benchmark_flags.h): what Google Benchmark 1.7.1 would take
// silently or answer with its usage and exit 0 is refused, naming the flag.
#include "bench/benchmark_flags.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace animat::bench {
namespace {

std::string Check(const std::string& argument) {
  return MalformedBenchmarkFlag({argument});
}

TEST(BenchmarkFlagsTest, WellFormedFlagsAndOtherArgumentsPass) {
  EXPECT_EQ(MalformedBenchmarkFlag({}), "");
  for (const char* argument : {
           "--benchmark_list_tests",
           "--benchmark_list_tests=true",
           "--benchmark_list_tests=FALSE",
           "--benchmark_counters_tabular=yes",
           "--benchmark_enable_random_interleaving=off",
           "--benchmark_report_aggregates_only=1",
           "--benchmark_display_aggregates_only=0",
           "--benchmark_filter=BM_GrnStep<float>/isa:0$",
           "--benchmark_filter=-BM_Evaluate",
           "--benchmark_filter=all",
           "--benchmark_min_time=0.01",
           "--benchmark_min_time=2e-3",
           "--benchmark_min_warmup_time=0",
           "--benchmark_repetitions=1",
           "--benchmark_repetitions=2147483647",
           "--benchmark_format=json",
           "--benchmark_out_format=csv",
           "--benchmark_out=results.json",
           "--benchmark_color=auto",
           "--benchmark_color=no",
           "--benchmark_context=machine=ci,run=3",
           "--benchmark_context=empty=",
           "--benchmark_time_unit=us",
           "--v=0",
           "--v=3",
           // Not flags of the library's: left to it.
           "--help",
           "positional",
           "--vv",
           "--verbose",
           "-benchmark_filter=(",
       }) {
    EXPECT_EQ(Check(argument), "") << argument;
  }
}

TEST(BenchmarkFlagsTest, ABoolTakesOnlyABoolOrNothing) {
  EXPECT_EQ(Check("--benchmark_list_tests=maybe"),
            "--benchmark_list_tests: expected true, false, yes, no, on, off, "
            "1 or 0 (or no value: true), got \"maybe\"");
  EXPECT_EQ(Check("--benchmark_counters_tabular=2"),
            "--benchmark_counters_tabular: expected true, false, yes, no, "
            "on, off, 1 or 0 (or no value: true), got \"2\"");
}

TEST(BenchmarkFlagsTest, AnEmptyValueIsRefusedForEveryFlag) {
  for (const char* flag :
       {"--benchmark_list_tests", "--benchmark_filter", "--benchmark_min_time",
        "--benchmark_min_warmup_time", "--benchmark_repetitions",
        "--benchmark_enable_random_interleaving",
        "--benchmark_report_aggregates_only",
        "--benchmark_display_aggregates_only", "--benchmark_format",
        "--benchmark_out", "--benchmark_out_format", "--benchmark_color",
        "--benchmark_counters_tabular", "--benchmark_context",
        "--benchmark_time_unit", "--v"}) {
    EXPECT_EQ(Check(std::string(flag) + "="),
              std::string(flag) + ": an empty value");
  }
}

TEST(BenchmarkFlagsTest, AFlagThatIsNotABoolNeedsAValue) {
  EXPECT_EQ(Check("--benchmark_filter"),
            "--benchmark_filter: needs a value, as "
            "--benchmark_filter=VALUE");
  EXPECT_EQ(Check("--benchmark_color"),
            "--benchmark_color: needs a value, as --benchmark_color=VALUE");
  EXPECT_EQ(Check("--v"), "--v: needs a value, as --v=VALUE");
}

TEST(BenchmarkFlagsTest, TimesAreFiniteAndInRange) {
  for (const char* value :
       {"0", "-1", "abc", "nan", "inf", "1e999", "0.5s", "1,5"}) {
    EXPECT_EQ(Check(std::string("--benchmark_min_time=") + value),
              std::string("--benchmark_min_time: expected a finite number of "
                          "seconds above 0, got \"") +
                  value + "\"");
  }
  EXPECT_EQ(Check("--benchmark_min_warmup_time=-0.5"),
            "--benchmark_min_warmup_time: expected a finite number of "
            "seconds, 0 or more, got \"-0.5\"");
  EXPECT_NE(Check("--benchmark_min_warmup_time=nan"), "");
}

TEST(BenchmarkFlagsTest, CountsAreWholeNumbersIn32Bits) {
  for (const char* value :
       {"0", "-5", "1.5", "abc", "2147483648", "99999999999999999999", "3x"}) {
    EXPECT_EQ(Check(std::string("--benchmark_repetitions=") + value),
              std::string("--benchmark_repetitions: expected a whole number "
                          "from 1 to 2147483647, got \"") +
                  value + "\"");
  }
  EXPECT_EQ(Check("--v=-1"),
            "--v: expected a whole number from 0 to 2147483647, got \"-1\"");
}

TEST(BenchmarkFlagsTest, NamedValuesAreOnesTheLibraryKnows) {
  EXPECT_EQ(Check("--benchmark_format=xml"),
            "--benchmark_format: expected console, json or csv, got \"xml\"");
  EXPECT_NE(Check("--benchmark_out_format=JSON"), "");
  EXPECT_NE(Check("--benchmark_format=tabular"), "");
  EXPECT_EQ(Check("--benchmark_time_unit=yy"),
            "--benchmark_time_unit: expected ns, us, ms or s, got \"yy\"");
  EXPECT_EQ(Check("--benchmark_color=maybe"),
            "--benchmark_color: expected auto, true, false, yes, no, on, off, "
            "1 or 0, got \"maybe\"");
}

TEST(BenchmarkFlagsTest, AContextIsKeyValuePairsWithKeys) {
  for (const char* value : {"a", "=b", "a=b=c", "a=1,,b=2", "a=1,", ","}) {
    EXPECT_EQ(Check(std::string("--benchmark_context=") + value),
              std::string("--benchmark_context: expected KEY=VALUE pairs "
                          "separated by commas (no key empty), got \"") +
                  value + "\"");
  }
}

TEST(BenchmarkFlagsTest, AFilterMustCompileAsTheLibraryCompilesIt) {
  for (const char* value : {"(", "-(", "[", "a{2,1}", "*a"}) {
    const std::string why = Check(std::string("--benchmark_filter=") + value);
    EXPECT_EQ(why.rfind("--benchmark_filter: not an extended regular "
                        "expression as the library compiles it: ",
                        0),
              0u)
        << value << ": " << why;
  }
  // Only one '-' means "not": a second is part of the expression.
  EXPECT_EQ(Check("--benchmark_filter=--x"), "");
  // Extended syntax: a backreference is ECMAScript's, not POSIX's.
  EXPECT_NE(Check("--benchmark_filter=(a)\\1"), "");
}

TEST(BenchmarkFlagsTest, AFilterLongEnoughToOverflowTheStackIsRefused) {
  EXPECT_EQ(Check("--benchmark_filter=" + std::string(1000, 'a')), "");
  const std::string why =
      Check("--benchmark_filter=" + std::string(100000, 'a'));
  EXPECT_EQ(why,
            "--benchmark_filter: longer than 1000 bytes (std::regex "
            "would overflow the stack), got \"" +
                std::string(40, 'a') + "... (100000 bytes)\"");
}

TEST(BenchmarkFlagsTest, AnUnknownBenchmarkFlagIsRefused) {
  EXPECT_EQ(Check("--benchmark_nonsense=1"),
            "--benchmark_nonsense: not a flag of Google Benchmark 1.7.1's "
            "usage (see --help)");
  EXPECT_NE(Check("--benchmark_list_testsx"), "");
  EXPECT_NE(Check("--benchmark_"), "");
}

TEST(BenchmarkFlagsTest, TheFirstMalformedArgumentIsNamed) {
  const std::vector<std::string> arguments = {"--benchmark_list_tests", "other",
                                              "--benchmark_repetitions=0",
                                              "--benchmark_format=xml"};
  EXPECT_EQ(
      MalformedBenchmarkFlag(arguments).rfind("--benchmark_repetitions:", 0),
      0u);
}

TEST(BenchmarkFlagsTest, AHugeValueIsQuotedShort) {
  const std::string why =
      Check("--benchmark_time_unit=" + std::string(100000, 'x'));
  EXPECT_LT(why.size(), 200u) << why;
}

}  // namespace
}  // namespace animat::bench
