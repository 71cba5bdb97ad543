// A configuration struct's numeric parameters declared once: one row per
// parameter names its proto field, the struct member (whose initializer
// is its default), what values it takes and what it means; ReadParams,
// CheckParams and WriteParams copy and check every row through protobuf
// reflection. Adding a numeric parameter is then one proto field (an
// `optional double` or `optional int32`), one member and one row.
//
// Rows are constant tables (see common/physics/physics_params.cc); every
// row must name a field of the message of the matching type, which
// CheckParamTable verifies (the configuration tests call it for each
// table). Pure functions; thread-safe.
#ifndef ANIMAT_COMMON_IO_PARAM_TABLE_H_
#define ANIMAT_COMMON_IO_PARAM_TABLE_H_

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "common/base/status.h"
#include "common/base/validate.h"

namespace animat {

// The values a parameter takes, checked as validate.h words its errors.
struct ParamRange {
  enum class Kind {
    kPositive,     // Finite and > 0.
    kNonNegative,  // Finite and >= 0.
    kClosed,       // [lo, hi] (an int: [lo, hi] too).
    kHalfOpen,     // [lo, hi).
  };
  Kind kind = Kind::kNonNegative;
  double lo = 0.0;
  double hi = 0.0;

  static constexpr ParamRange Positive() { return {Kind::kPositive}; }
  static constexpr ParamRange NonNegative() { return {Kind::kNonNegative}; }
  static constexpr ParamRange Closed(double lo, double hi) {
    return {Kind::kClosed, lo, hi};
  }
  static constexpr ParamRange HalfOpen(double lo, double hi) {
    return {Kind::kHalfOpen, lo, hi};
  }
};

template <typename Params>
struct ParamRow {
  const char* field;  // The proto field's name.
  std::variant<double Params::*, int Params::*> member;
  ParamRange range;
  const char* doc;  // What it is, with its unit: one line.
};

template <typename Params>
using ParamTable = std::span<const ParamRow<Params>>;

namespace param_table_internal {

inline const google::protobuf::FieldDescriptor* Field(
    const google::protobuf::Message& m, const char* name) {
  return m.GetDescriptor()->FindFieldByName(name);
}

}  // namespace param_table_internal

// Every row names an optional field of `prototype`'s message whose type
// matches its member (double or int32); the error names the first that
// does not.
template <typename Params>
Status CheckParamTable(const google::protobuf::Message& prototype,
                       ParamTable<Params> rows) {
  using google::protobuf::FieldDescriptor;
  for (const ParamRow<Params>& row : rows) {
    const FieldDescriptor* f =
        param_table_internal::Field(prototype, row.field);
    const FieldDescriptor::CppType want =
        std::holds_alternative<double Params::*>(row.member)
            ? FieldDescriptor::CPPTYPE_DOUBLE
            : FieldDescriptor::CPPTYPE_INT32;
    if (f == nullptr || f->cpp_type() != want || !f->has_presence()) {
      return Status::Internal(std::string(prototype.GetTypeName()) +
                              ": no optional field " + row.field +
                              " of the row's type");
    }
  }
  return Status::Ok();
}

// Copies each row's field present in `m` into `*params` (unchecked).
template <typename Params>
void ReadParams(const google::protobuf::Message& m, ParamTable<Params> rows,
                Params* params) {
  const google::protobuf::Reflection& r = *m.GetReflection();
  for (const ParamRow<Params>& row : rows) {
    const auto* f = param_table_internal::Field(m, row.field);
    if (!r.HasField(m, f)) continue;
    if (auto* d = std::get_if<double Params::*>(&row.member)) {
      params->** d = r.GetDouble(m, f);
    } else {
      params->*std::get<int Params::*>(row.member) = r.GetInt32(m, f);
    }
  }
}

// Sets each row's field of `*m` from `params`.
template <typename Params>
void WriteParams(const Params& params, ParamTable<Params> rows,
                 google::protobuf::Message* m) {
  const google::protobuf::Reflection& r = *m->GetReflection();
  for (const ParamRow<Params>& row : rows) {
    const auto* f = param_table_internal::Field(*m, row.field);
    if (auto* d = std::get_if<double Params::*>(&row.member)) {
      r.SetDouble(m, f, params.**d);
    } else {
      r.SetInt32(m, f, params.*std::get<int Params::*>(row.member));
    }
  }
}

// The first row whose value is out of its range, named "<prefix>.<field>"
// ("physics.mass: must be finite and > 0, got -1"), or OK.
template <typename Params>
Status CheckParams(std::string_view prefix, const Params& params,
                   ParamTable<Params> rows) {
  using Kind = ParamRange::Kind;
  for (const ParamRow<Params>& row : rows) {
    const std::string name = std::string(prefix) + "." + row.field;
    const ParamRange& range = row.range;
    Status status;
    if (const auto* i = std::get_if<int Params::*>(&row.member)) {
      status =
          RequireIntInRange(name, params.**i, static_cast<long long>(range.lo),
                            static_cast<long long>(range.hi));
    } else {
      const double v = params.*std::get<double Params::*>(row.member);
      switch (range.kind) {
        case Kind::kPositive:
          status = RequirePositive(name, v);
          break;
        case Kind::kNonNegative:
          status = RequireNonNegative(name, v);
          break;
        case Kind::kClosed:
        case Kind::kHalfOpen:
          status = RequireInRange(name, v, range.lo, range.hi,
                                  range.kind == Kind::kClosed);
          break;
      }
    }
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

}  // namespace animat

#endif  // ANIMAT_COMMON_IO_PARAM_TABLE_H_
