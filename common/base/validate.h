// Checks of configuration values whose errors name the field
// ("physics.mass: must be > 0, got -1"). Pure functions.
#ifndef ANIMAT_COMMON_BASE_VALIDATE_H_
#define ANIMAT_COMMON_BASE_VALIDATE_H_

#include <initializer_list>
#include <string_view>

#include "common/base/status.h"

namespace animat {

// Each returns OK or kInvalidArgument "<field>: must be ..., got <value>".
// Every double check also rejects NaN and infinities.
Status RequireFinite(std::string_view field, double value);
Status RequirePositive(std::string_view field, double value);     // > 0
Status RequireNonNegative(std::string_view field, double value);  // >= 0
// lo <= value <= hi, or lo <= value < hi when !include_hi.
Status RequireInRange(std::string_view field, double value, double lo,
                      double hi, bool include_hi = true);
Status RequireIntInRange(std::string_view field, long long value, long long lo,
                         long long hi);

// The first error among `checks`, or OK.
Status FirstError(std::initializer_list<Status> checks);

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_VALIDATE_H_
