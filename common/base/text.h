// Numbers as messages show them.
// Thread-safe (no shared state).
#ifndef ANIMAT_COMMON_BASE_TEXT_H_
#define ANIMAT_COMMON_BASE_TEXT_H_

#include <string>

namespace animat {

// The shortest decimal form that reads back to exactly `value`
// (std::to_chars): "0.7", "1e-06", "12345.678", "inf", "nan".
std::string ShortestDouble(double value);

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_TEXT_H_
