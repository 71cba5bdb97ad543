// A configuration struct's parameters declared once: one row per
// parameter names its proto field, the struct member (whose initializer
// is its default), what values it takes and what it means; ReadParams,
// CheckParams and WriteParams copy and check every row through protobuf
// reflection, and DescribeParams lists them for `animat config defaults`.
// Adding a parameter is then one proto field (an `optional` double, int32,
// bool or uint64), one member and one row. Enum parameters have rows of
// their own (EnumRow), each with its pairs of struct and proto values.
//
// Rows are constant tables (see common/physics/physics_params.cc); every
// row must name a field of the message of the matching type, which
// CheckParamTable verifies (the configuration tests call it for each
// table). Pure functions; thread-safe.
#ifndef ANIMAT_COMMON_IO_PARAM_TABLE_H_
#define ANIMAT_COMMON_IO_PARAM_TABLE_H_

#include <google/protobuf/descriptor.h>
#include <google/protobuf/message.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "common/base/status.h"
#include "common/base/validate.h"

namespace animat {

// The values a parameter takes, checked as validate.h words its errors.
struct ParamRange {
  enum class Kind {
    kAny,             // Every value (a bool, a seed).
    kPositive,        // Finite and > 0.
    kNonNegative,     // Finite and >= 0.
    kClosed,          // [lo, hi] (an int: [lo, hi] too).
    kHalfOpen,        // [lo, hi).
    kPositiveAtMost,  // (0, hi].
  };
  Kind kind = Kind::kNonNegative;
  double lo = 0.0;
  double hi = 0.0;

  static constexpr ParamRange Any() { return {Kind::kAny}; }
  static constexpr ParamRange Positive() { return {Kind::kPositive}; }
  static constexpr ParamRange NonNegative() { return {Kind::kNonNegative}; }
  static constexpr ParamRange Closed(double lo, double hi) {
    return {Kind::kClosed, lo, hi};
  }
  static constexpr ParamRange HalfOpen(double lo, double hi) {
    return {Kind::kHalfOpen, lo, hi};
  }
  static constexpr ParamRange PositiveAtMost(double hi) {
    return {Kind::kPositiveAtMost, 0.0, hi};
  }
};

template <typename Params>
struct ParamRow {
  const char* field;  // The proto field's name.
  std::variant<double Params::*, int Params::*, bool Params::*,
               uint64_t Params::*>
      member;
  ParamRange range;
  const char* doc;  // What it is, with its unit: one line.
};

template <typename Params>
using ParamTable = std::span<const ParamRow<Params>>;

// One value of an enum parameter: the struct's enumerator (as int) and the
// proto enum's number.
struct EnumPair {
  int value;
  int number;
};

template <typename Params>
struct EnumRow {
  const char* field;  // The proto enum field's name.
  int (*get)(const Params&);
  void (*set)(Params*, int value);
  std::span<const EnumPair> pairs;  // Every enumerator of the struct's.
  const char* doc;
};

template <typename Params>
using EnumTable = std::span<const EnumRow<Params>>;

namespace param_table_internal {

template <typename T>
struct MemberOf;
template <typename P, typename E>
struct MemberOf<E P::*> {
  using Params = P;
  using Value = E;
};

inline const google::protobuf::FieldDescriptor* Field(
    const google::protobuf::Message& m, const char* name) {
  return m.GetDescriptor()->FindFieldByName(name);
}

template <typename Params>
google::protobuf::FieldDescriptor::CppType CppTypeOf(
    const ParamRow<Params>& row) {
  using F = google::protobuf::FieldDescriptor;
  constexpr F::CppType kTypes[] = {F::CPPTYPE_DOUBLE, F::CPPTYPE_INT32,
                                   F::CPPTYPE_BOOL, F::CPPTYPE_UINT64};
  return kTypes[row.member.index()];
}

Status CheckRange(const std::string& name, double value,
                  const ParamRange& range);
Status CheckIntRange(const std::string& name, long long value,
                     const ParamRange& range);
std::string DescribeRange(const ParamRange& range, bool integer);
std::string DescribeEnum(const google::protobuf::FieldDescriptor& field,
                         std::span<const EnumPair> pairs);
Status MissingField(const google::protobuf::Message& prototype,
                    const char* field, const char* what);

}  // namespace param_table_internal

// A row of `table` for the enum member `Member` (&Params::field):
// constexpr EnumRow<P> r = MakeEnumRow<&P::integrator>("integrator", ...).
template <auto Member>
constexpr auto MakeEnumRow(const char* field, std::span<const EnumPair> pairs,
                           const char* doc) {
  using M = param_table_internal::MemberOf<decltype(Member)>;
  using Params = typename M::Params;
  return EnumRow<Params>{
      field, [](const Params& p) { return static_cast<int>(p.*Member); },
      [](Params* p, int value) {
        p->*Member = static_cast<typename M::Value>(value);
      },
      pairs, doc};
}

// Every row names an optional field of `prototype`'s message whose type
// matches its member; every enum row's numbers are values of its enum. The
// error names the first that does not.
template <typename Params>
Status CheckParamTable(const google::protobuf::Message& prototype,
                       ParamTable<Params> rows, EnumTable<Params> enums = {}) {
  using google::protobuf::FieldDescriptor;
  for (const ParamRow<Params>& row : rows) {
    const FieldDescriptor* f =
        param_table_internal::Field(prototype, row.field);
    if (f == nullptr || f->cpp_type() != param_table_internal::CppTypeOf(row) ||
        !f->has_presence()) {
      return param_table_internal::MissingField(prototype, row.field,
                                                "of the row's type");
    }
  }
  for (const EnumRow<Params>& row : enums) {
    const FieldDescriptor* f =
        param_table_internal::Field(prototype, row.field);
    bool known = f != nullptr && f->cpp_type() == FieldDescriptor::CPPTYPE_ENUM;
    for (const EnumPair& pair : row.pairs) {
      known = known && pair.number != 0 &&
              f->enum_type()->FindValueByNumber(pair.number) != nullptr;
    }
    if (!known) {
      return param_table_internal::MissingField(
          prototype, row.field, "of enum type with the row's values");
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
    std::visit(
        [&](auto member) {
          using T =
              typename param_table_internal::MemberOf<decltype(member)>::Value;
          if constexpr (std::is_same_v<T, double>) {
            params->*member = r.GetDouble(m, f);
          } else if constexpr (std::is_same_v<T, int>) {
            params->*member = r.GetInt32(m, f);
          } else if constexpr (std::is_same_v<T, bool>) {
            params->*member = r.GetBool(m, f);
          } else {
            params->*member = r.GetUInt64(m, f);
          }
        },
        row.member);
  }
}

// Copies each enum row's field present in `m` into `*params`; the
// unspecified value (0) leaves the default. Error: "<prefix>.<field>:
// unknown value <n>", with `*params` then partly written.
template <typename Params>
Status ReadEnums(std::string_view prefix, const google::protobuf::Message& m,
                 EnumTable<Params> rows, Params* params) {
  const google::protobuf::Reflection& r = *m.GetReflection();
  for (const EnumRow<Params>& row : rows) {
    const auto* f = param_table_internal::Field(m, row.field);
    if (!r.HasField(m, f)) continue;
    const int number = r.GetEnumValue(m, f);
    if (number == 0) continue;
    bool found = false;
    for (const EnumPair& pair : row.pairs) {
      if (pair.number != number) continue;
      row.set(params, pair.value);
      found = true;
    }
    if (!found) {
      return Status::InvalidArgument(std::string(prefix) + "." + row.field +
                                     ": unknown value " +
                                     std::to_string(number));
    }
  }
  return Status::Ok();
}

// Sets each row's field of `*m` from `params`.
template <typename Params>
void WriteParams(const Params& params, ParamTable<Params> rows,
                 google::protobuf::Message* m, EnumTable<Params> enums = {}) {
  const google::protobuf::Reflection& r = *m->GetReflection();
  for (const ParamRow<Params>& row : rows) {
    const auto* f = param_table_internal::Field(*m, row.field);
    std::visit(
        [&](auto member) {
          using T =
              typename param_table_internal::MemberOf<decltype(member)>::Value;
          if constexpr (std::is_same_v<T, double>) {
            r.SetDouble(m, f, params.*member);
          } else if constexpr (std::is_same_v<T, int>) {
            r.SetInt32(m, f, params.*member);
          } else if constexpr (std::is_same_v<T, bool>) {
            r.SetBool(m, f, params.*member);
          } else {
            r.SetUInt64(m, f, params.*member);
          }
        },
        row.member);
  }
  for (const EnumRow<Params>& row : enums) {
    for (const EnumPair& pair : row.pairs) {
      if (pair.value == row.get(params)) {
        r.SetEnumValue(m, param_table_internal::Field(*m, row.field),
                       pair.number);
      }
    }
  }
}

// The first row whose value is out of its range, named "<prefix>.<field>"
// ("physics.mass: must be finite and > 0, got -1"), or OK.
template <typename Params>
Status CheckParams(std::string_view prefix, const Params& params,
                   ParamTable<Params> rows) {
  for (const ParamRow<Params>& row : rows) {
    const std::string name = std::string(prefix) + "." + row.field;
    Status status;
    if (const auto* i = std::get_if<int Params::*>(&row.member)) {
      status = param_table_internal::CheckIntRange(name, params.**i, row.range);
    } else if (const auto* d = std::get_if<double Params::*>(&row.member)) {
      status = param_table_internal::CheckRange(name, params.**d, row.range);
    }
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

// One parameter as `animat config defaults` explains it.
struct ParamDoc {
  std::string name;    // "<prefix>.<field>", e.g. "physics.mass".
  std::string doc;     // The row's line.
  std::string values;  // "> 0", "[0, 1]", "one of RK4, ..." or "".
};

// Every row of both tables, in table order (numbers, then enums).
template <typename Params>
std::vector<ParamDoc> DescribeParams(std::string_view prefix,
                                     const google::protobuf::Message& prototype,
                                     ParamTable<Params> rows,
                                     EnumTable<Params> enums = {}) {
  std::vector<ParamDoc> docs;
  const std::string p = std::string(prefix) + ".";
  for (const ParamRow<Params>& row : rows) {
    docs.push_back({p + row.field, row.doc,
                    param_table_internal::DescribeRange(
                        row.range, row.member.index() == 1)});
  }
  for (const EnumRow<Params>& row : enums) {
    docs.push_back(
        {p + row.field, row.doc,
         param_table_internal::DescribeEnum(
             *param_table_internal::Field(prototype, row.field), row.pairs)});
  }
  return docs;
}

// The lines of `text` (text protobuf, as SerializeProto writes it) with a
// comment "# <doc>; <values>" above each field `docs` names; the result
// reads back as the same message. Names nest as blocks do ("physics.mass"
// for `mass` inside `physics { }`).
std::string AnnotateText(std::string_view text, std::span<const ParamDoc> docs);

}  // namespace animat

#endif  // ANIMAT_COMMON_IO_PARAM_TABLE_H_
