// Numbers and foreign bytes as messages show them.
// Thread-safe (no shared state).
#ifndef ANIMAT_COMMON_BASE_TEXT_H_
#define ANIMAT_COMMON_BASE_TEXT_H_

#include <cstddef>
#include <string>
#include <string_view>

namespace animat {

// The shortest decimal form that reads back to exactly `value`
// (std::to_chars): "0.7", "1e-06", "12345.678", "inf", "nan".
std::string ShortestDouble(double value);

// The first `max_bytes` bytes of `bytes` as one printable line: a
// backslash, a double quote and the bytes outside printable ASCII are
// escaped (\\, \", \n, \t, \r, \xNN), and a cut is marked with "..." and
// the total length ("... (52428800 bytes)"). Not quoted.
std::string Excerpt(std::string_view bytes, size_t max_bytes = 64);

// A message from a parser that may quote its input: its first `max_bytes`
// bytes ("..." marks a cut), with the bytes outside printable ASCII
// escaped as by Excerpt (quotes and backslashes kept as they are).
std::string ForeignText(std::string_view message, size_t max_bytes = 200);

// `name` with its ASCII capitals in lower case, as the store and logs name
// an enum value: "NUMERICAL_FAILURE" -> "numerical_failure".
std::string AsciiLowerCase(std::string_view name);

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_TEXT_H_
