#include "common/command_line/command_line.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

#include "common/base/text.h"

namespace animat {
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
    // strtoull, and so CLI11, reads "-1" as 2^64 - 1.
    const size_t first = value.find_first_not_of(" \t");
    if (first != std::string::npos && value[first] == '-') {
      return "a negative number for an unsigned value";
    }
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

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv,
                                    const std::string& program) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (const std::string why = MalformedOptionValue(app); !why.empty()) {
    std::cerr << program << ": " << why
              << "\nRun with --help for more information.\n";
    return 2;
  }
  return std::nullopt;
}

}  // namespace animat
