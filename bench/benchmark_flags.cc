#include "bench/benchmark_flags.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <regex>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "common/base/text.h"

namespace animat::bench {
namespace {

enum class Kind {
  kBool,
  kFilter,
  kPositiveSeconds,
  kSeconds,
  kRepetitions,
  kVerbosity,
  kFormat,
  kPath,
  kColor,
  kContext,
  kTimeUnit,
};

struct FlagKind {
  std::string_view name;
  Kind kind;
};

// The flags of Google Benchmark 1.7.1's usage, in its order.
constexpr FlagKind kFlags[] = {
    {"benchmark_list_tests", Kind::kBool},
    {"benchmark_filter", Kind::kFilter},
    {"benchmark_min_time", Kind::kPositiveSeconds},
    {"benchmark_min_warmup_time", Kind::kSeconds},
    {"benchmark_repetitions", Kind::kRepetitions},
    {"benchmark_enable_random_interleaving", Kind::kBool},
    {"benchmark_report_aggregates_only", Kind::kBool},
    {"benchmark_display_aggregates_only", Kind::kBool},
    {"benchmark_format", Kind::kFormat},
    {"benchmark_out", Kind::kPath},
    {"benchmark_out_format", Kind::kFormat},
    {"benchmark_color", Kind::kColor},
    {"benchmark_counters_tabular", Kind::kBool},
    {"benchmark_context", Kind::kContext},
    {"benchmark_time_unit", Kind::kTimeUnit},
    {"v", Kind::kVerbosity},
};

bool IsBool(std::string_view value) {
  std::string lower(value);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  for (const char* word :
       {"true", "false", "yes", "no", "on", "off", "1", "0"}) {
    if (lower == word) return true;
  }
  return false;
}

bool IsOneOf(std::string_view value,
             std::initializer_list<std::string_view> words) {
  return std::find(words.begin(), words.end(), value) != words.end();
}

// Why `value` is not a whole number from `min` to INT32_MAX, or "".
std::string WhyNotCount(std::string_view value, int64_t min) {
  int64_t number = 0;
  const char* end = value.data() + value.size();
  const std::from_chars_result result =
      std::from_chars(value.data(), end, number);
  if (result.ec != std::errc() || result.ptr != end || number < min ||
      number > std::numeric_limits<int32_t>::max()) {
    return "expected a whole number from " + std::to_string(min) + " to " +
           std::to_string(std::numeric_limits<int32_t>::max());
  }
  return std::string();
}

// Why `value` is not a finite number of seconds above 0 (`positive`) or of
// 0 or more, or "".
std::string WhyNotSeconds(std::string_view value, bool positive) {
  double number = 0;
  const char* end = value.data() + value.size();
  const std::from_chars_result result =
      std::from_chars(value.data(), end, number);
  const bool in_range = positive ? number > 0 : number >= 0;
  if (result.ec != std::errc() || result.ptr != end || !std::isfinite(number) ||
      !in_range) {
    return positive ? "expected a finite number of seconds above 0"
                    : "expected a finite number of seconds, 0 or more";
  }
  return std::string();
}

// Why `value` is not KEY=VALUE pairs separated by commas, or "".
std::string WhyNotContext(std::string_view value) {
  size_t start = 0;
  while (true) {
    const size_t comma = value.find(',', start);
    const std::string_view pair = value.substr(
        start, comma == std::string_view::npos ? comma : comma - start);
    const size_t equals = pair.find('=');
    if (equals == 0 || equals == std::string_view::npos ||
        pair.find('=', equals + 1) != std::string_view::npos) {
      return "expected KEY=VALUE pairs separated by commas (no key empty)";
    }
    if (comma == std::string_view::npos) return std::string();
    start = comma + 1;
  }
}

// The longest filter taken: std::regex compiles and matches recursively,
// about a frame per character, and a filter of 100,000 characters overflows
// the stack (benchmark names are under 100).
constexpr size_t kMaxFilterBytes = 1000;

// Why the library cannot compile `value` as a filter, or "".
std::string WhyNotFilter(std::string_view value) {
  if (value.size() > kMaxFilterBytes) {
    return "longer than " + std::to_string(kMaxFilterBytes) +
           " bytes (std::regex would overflow the stack)";
  }
  // A leading '-' makes the filter negative; the rest is the expression.
  if (!value.empty() && value.front() == '-') value.remove_prefix(1);
  try {
    const std::regex compiled(value.begin(), value.end(),
                              std::regex_constants::extended);
  } catch (const std::regex_error& error) {
    return std::string(
               "not an extended regular expression as the library compiles "
               "it: ") +
           error.what();
  }
  return std::string();
}

// Why `value` is malformed for a flag of `kind`, or "".
std::string WhyMalformed(Kind kind, std::string_view value) {
  switch (kind) {
    case Kind::kBool:
      return IsBool(value) ? ""
                           : "expected true, false, yes, no, on, off, 1 "
                             "or 0 (or no value: true)";
    case Kind::kColor:
      return value == "auto" || IsBool(value)
                 ? ""
                 : "expected auto, true, false, yes, no, on, off, 1 or 0";
    case Kind::kFilter:
      return WhyNotFilter(value);
    case Kind::kPositiveSeconds:
      return WhyNotSeconds(value, /*positive=*/true);
    case Kind::kSeconds:
      return WhyNotSeconds(value, /*positive=*/false);
    case Kind::kRepetitions:
      return WhyNotCount(value, 1);
    case Kind::kVerbosity:
      return WhyNotCount(value, 0);
    case Kind::kFormat:
      return IsOneOf(value, {"console", "json", "csv"})
                 ? ""
                 : "expected console, json or csv";
    case Kind::kTimeUnit:
      return IsOneOf(value, {"ns", "us", "ms", "s"})
                 ? ""
                 : "expected ns, us, ms or s";
    case Kind::kContext:
      return WhyNotContext(value);
    case Kind::kPath:
      return std::string();  // Any non-empty path; the library opens it.
  }
  return std::string();
}

// Why `argument`, a --benchmark_* or --v flag, is malformed, or "".
std::string WhyArgumentMalformed(std::string_view argument) {
  const size_t equals = argument.find('=');
  const std::string_view name = argument.substr(2, equals - 2);
  const auto known =
      std::find_if(std::begin(kFlags), std::end(kFlags),
                   [name](const FlagKind& flag) { return flag.name == name; });
  if (known == std::end(kFlags)) {
    return "not a flag of Google Benchmark 1.7.1's usage (see --help)";
  }
  if (equals == std::string_view::npos) {
    return known->kind == Kind::kBool
               ? ""
               : "needs a value, as --" + std::string(name) + "=VALUE";
  }
  const std::string_view value = argument.substr(equals + 1);
  if (value.empty()) return "an empty value";
  const std::string why = WhyMalformed(known->kind, value);
  if (why.empty()) return why;
  return why + ", got \"" + Excerpt(value, 40) + "\"";
}

}  // namespace

std::string MalformedBenchmarkFlag(const std::vector<std::string>& arguments) {
  for (const std::string& argument : arguments) {
    const std::string_view text = argument;
    const bool benchmark_flag = text.rfind("--benchmark_", 0) == 0;
    const bool verbosity = text == "--v" || text.rfind("--v=", 0) == 0;
    if (!benchmark_flag && !verbosity) continue;
    const std::string why = WhyArgumentMalformed(text);
    if (!why.empty()) {
      return Excerpt(text.substr(0, text.find('=')), 60) + ": " + why;
    }
  }
  return std::string();
}

}  // namespace animat::bench
