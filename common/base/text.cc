#include "common/base/text.h"

#include <charconv>
#include <cstdio>

namespace animat {

std::string ShortestDouble(double value) {
  char buffer[32];
  const std::to_chars_result result =
      std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (result.ec != std::errc()) return "?";
  return std::string(buffer, result.ptr);
}

namespace {

std::string Escape(std::string_view bytes, size_t max_bytes, bool quotes) {
  std::string out;
  const size_t shown = bytes.size() <= max_bytes ? bytes.size() : max_bytes;
  for (size_t i = 0; i < shown; ++i) {
    const unsigned char c = static_cast<unsigned char>(bytes[i]);
    switch (c) {
      case '\\':
        out += quotes ? "\\\\" : "\\";
        break;
      case '"':
        out += quotes ? "\\\"" : "\"";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (c >= 0x20 && c < 0x7f) {
          out += static_cast<char>(c);
        } else {
          char hex[8];
          std::snprintf(hex, sizeof(hex), "\\x%02x", c);
          out += hex;
        }
    }
  }
  return out;
}

}  // namespace

std::string Excerpt(std::string_view bytes, size_t max_bytes) {
  std::string out = Escape(bytes, max_bytes, /*quotes=*/true);
  if (bytes.size() > max_bytes) {
    out += "... (" + std::to_string(bytes.size()) + " bytes)";
  }
  return out;
}

std::string ForeignText(std::string_view message, size_t max_bytes) {
  std::string out = Escape(message, max_bytes, /*quotes=*/false);
  if (message.size() > max_bytes) out += "...";
  return out;
}

std::string AsciiLowerCase(std::string_view name) {
  std::string lower(name);
  for (char& c : lower) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return lower;
}

}  // namespace animat
