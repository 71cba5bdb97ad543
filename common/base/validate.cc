#include "common/base/validate.h"

#include <cmath>
#include <string>

#include "common/base/text.h"

namespace animat {
namespace {

std::string Format(double value) { return ShortestDouble(value); }

Status Fail(std::string_view field, const std::string& rule,
            const std::string& got) {
  return Status::InvalidArgument(std::string(field) + ": must be " + rule +
                                 ", got " + got);
}

}  // namespace

Status RequireFinite(std::string_view field, double value) {
  if (!std::isfinite(value)) return Fail(field, "finite", Format(value));
  return Status::Ok();
}

Status RequirePositive(std::string_view field, double value) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    return Fail(field, "finite and > 0", Format(value));
  }
  return Status::Ok();
}

Status RequireNonNegative(std::string_view field, double value) {
  if (!std::isfinite(value) || !(value >= 0.0)) {
    return Fail(field, "finite and >= 0", Format(value));
  }
  return Status::Ok();
}

Status RequireInRange(std::string_view field, double value, double lo,
                      double hi, bool include_hi) {
  const bool below_hi = include_hi ? value <= hi : value < hi;
  if (!std::isfinite(value) || !(value >= lo) || !below_hi) {
    return Fail(
        field,
        "in [" + Format(lo) + ", " + Format(hi) + (include_hi ? "]" : ")"),
        Format(value));
  }
  return Status::Ok();
}

Status RequireIntInRange(std::string_view field, long long value, long long lo,
                         long long hi) {
  if (value < lo || value > hi) {
    return Fail(field,
                "in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]",
                std::to_string(value));
  }
  return Status::Ok();
}

Status FirstError(std::initializer_list<Status> checks) {
  for (const Status& s : checks) {
    if (!s.ok()) return s;
  }
  return Status::Ok();
}

}  // namespace animat
