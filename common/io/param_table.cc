#include "common/io/param_table.h"

#include <map>
#include <string>

#include "common/base/text.h"

namespace animat {
namespace param_table_internal {

Status CheckRange(const std::string& name, double value,
                  const ParamRange& range) {
  using Kind = ParamRange::Kind;
  switch (range.kind) {
    case Kind::kAny:
      return Status::Ok();
    case Kind::kPositive:
      return RequirePositive(name, value);
    case Kind::kNonNegative:
      return RequireNonNegative(name, value);
    case Kind::kClosed:
    case Kind::kHalfOpen:
      return RequireInRange(name, value, range.lo, range.hi,
                            range.kind == Kind::kClosed);
    case Kind::kPositiveAtMost:
      return FirstError({RequirePositive(name, value),
                         RequireInRange(name, value, 0.0, range.hi)});
  }
  return Status::Ok();
}

Status CheckIntRange(const std::string& name, long long value,
                     const ParamRange& range) {
  if (range.kind == ParamRange::Kind::kAny) return Status::Ok();
  return RequireIntInRange(name, value, static_cast<long long>(range.lo),
                           static_cast<long long>(range.hi));
}

std::string DescribeRange(const ParamRange& range, bool integer) {
  using Kind = ParamRange::Kind;
  auto number = [integer](double v) {
    return integer ? std::to_string(static_cast<long long>(v))
                   : ShortestDouble(v);
  };
  // Appended, not concatenated: GCC 12's -Wrestrict misfires on
  // "[" + string + ...
  std::string text;
  switch (range.kind) {
    case Kind::kAny:
      return text;
    case Kind::kPositive:
      return "> 0";
    case Kind::kNonNegative:
      return ">= 0";
    case Kind::kClosed:
    case Kind::kHalfOpen:
      text.append("[").append(number(range.lo));
      break;
    case Kind::kPositiveAtMost:
      text.append("(0");
      break;
  }
  text.append(", ").append(number(range.hi));
  text.append(range.kind == Kind::kHalfOpen ? ")" : "]");
  return text;
}

std::string DescribeEnum(const google::protobuf::FieldDescriptor& field,
                         std::span<const EnumPair> pairs) {
  std::string names;
  for (const EnumPair& pair : pairs) {
    names +=
        (names.empty() ? "one of " : ", ") +
        std::string(field.enum_type()->FindValueByNumber(pair.number)->name());
  }
  return names;
}

Status MissingField(const google::protobuf::Message& prototype,
                    const char* field, const char* what) {
  return Status::Internal(std::string(prototype.GetTypeName()) +
                          ": no optional field " + field + " " + what);
}

}  // namespace param_table_internal

std::string AnnotateText(std::string_view text,
                         std::span<const ParamDoc> docs) {
  std::map<std::string, const ParamDoc*, std::less<>> by_name;
  for (const ParamDoc& doc : docs) by_name.emplace(doc.name, &doc);
  std::vector<std::string> blocks;  // The open blocks' names.
  std::string out;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + 1;
    const size_t indent = line.find_first_not_of(' ');
    const std::string_view body =
        indent == std::string_view::npos ? "" : line.substr(indent);
    if (body == "}") {
      if (!blocks.empty()) blocks.pop_back();
    } else if (body.ends_with(" {")) {
      blocks.emplace_back(body.substr(0, body.size() - 2));
    } else if (const size_t colon = body.find(':');
               colon != std::string_view::npos) {
      std::string name;
      for (const std::string& block : blocks) name += block + ".";
      name += body.substr(0, colon);
      if (auto it = by_name.find(name); it != by_name.end()) {
        const ParamDoc& doc = *it->second;
        out.append(line.substr(0, indent)).append("# ").append(doc.doc);
        if (!doc.values.empty()) out.append("; ").append(doc.values);
        out.push_back('\n');
      }
    }
    out.append(line).push_back('\n');
  }
  return out;
}

}  // namespace animat
