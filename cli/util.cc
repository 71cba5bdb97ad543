#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "cli/commands.h"
#include "common/base/text.h"

namespace animat::cli {

int Fail(const std::string& message) {
  std::cerr << "animat: " << message << "\n";
  return 1;
}

CLI::Validator IdValidator(uint64_t max, const std::string& noun) {
  return CLI::Validator(
      [max, noun](std::string& text) -> std::string {
        uint64_t value = 0;
        const char* end = text.data() + text.size();
        const std::from_chars_result result =
            std::from_chars(text.data(), end, value);
        const std::string got = ", got \"" + Excerpt(text, 40) + "\"";
        if (text.empty() || result.ptr != end ||
            (result.ec != std::errc() &&
             result.ec != std::errc::result_out_of_range)) {
          return "expected " + noun + " (a whole number, 0 or more)" + got;
        }
        if (result.ec != std::errc() || value > max) {
          return "expected " + noun + " of at most " + std::to_string(max) +
                 got;
        }
        return std::string();
      },
      "");
}

namespace {

// Why `value` of an option of type `type` (CLI11's name: INT, UINT, FLOAT,
// TEXT, possibly followed by a validator's description) is malformed, or
// "".
std::string WhyMalformed(const std::string& type, const std::string& value) {
  if (value.empty()) return "an empty value";
  errno = 0;
  char* end = nullptr;
  if (type.rfind("INT", 0) == 0) {
    (void)std::strtoll(value.c_str(), &end, 10);
    if (errno == ERANGE) return "a whole number beyond 64 bits";
  } else if (type.rfind("UINT", 0) == 0) {
    (void)std::strtoull(value.c_str(), &end, 10);
    if (errno == ERANGE) return "a whole number beyond 64 bits";
  } else if (type.rfind("FLOAT", 0) == 0) {
    const double number = std::strtod(value.c_str(), &end);
    if (!std::isfinite(number)) return "a number that is not finite";
  }
  return std::string();
}

}  // namespace

std::string MalformedOptionValue(const CLI::App& app) {
  for (const CLI::Option* option : app.get_options()) {
    if (option->get_type_size() == 0) continue;  // A flag.
    for (const std::string& value : option->results()) {
      const std::string why = WhyMalformed(option->get_type_name(), value);
      if (!why.empty()) {
        return option->get_name() + ": " + why + " (\"" + Excerpt(value, 40) +
               "\")";
      }
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) {
    const std::string why = MalformedOptionValue(*sub);
    if (!why.empty()) return why;
  }
  return std::string();
}

}  // namespace animat::cli
