#include <charconv>
#include <cstdint>
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

}  // namespace animat::cli
