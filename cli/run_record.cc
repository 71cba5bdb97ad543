#include "cli/run_record.h"

#include <google/protobuf/struct.pb.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>

#include "common/io/proto_file.h"

namespace animat::cli {
namespace {

using google::protobuf::Struct;
using google::protobuf::Value;

// The member `key` of `object`, or null when it is absent.
const Value* Member(const Struct& object, const std::string& key) {
  const auto it = object.fields().find(key);
  return it == object.fields().end() ? nullptr : &it->second;
}

// Reads the fields of one record, each error naming the field.
class Fields {
 public:
  Fields(const Struct& object, std::string where)
      : object_(object), where_(std::move(where)) {}

  Result<const Value*> Get(const std::string& key, Value::KindCase kind) const {
    const Value* v = Member(object_, key);
    if (v == nullptr) return Error(key, "missing");
    if (v->kind_case() != kind) return Error(key, "of the wrong type");
    return v;
  }

  Result<std::string> String(const std::string& key) const {
    Result<const Value*> v = Get(key, Value::kStringValue);
    if (!v.ok()) return v.status();
    return (*v)->string_value();
  }

  // A JSON number that is an integer in [lo, hi].
  Result<int64_t> Integer(const std::string& key, double lo, double hi) const {
    Result<const Value*> v = Get(key, Value::kNumberValue);
    if (!v.ok()) return v.status();
    const double x = (*v)->number_value();
    if (!(x >= lo && x <= hi) || std::trunc(x) != x) {
      return Error(key, "not an integer in range");
    }
    return static_cast<int64_t>(x);
  }

  // A finite number, or null (empty).
  Result<std::optional<double>> Statistic(const std::string& key) const {
    const Value* v = Member(object_, key);
    if (v == nullptr) return Error(key, "missing");
    if (v->kind_case() == Value::kNullValue) return std::optional<double>();
    if (v->kind_case() != Value::kNumberValue ||
        !std::isfinite(v->number_value())) {
      return Error(key, "not a finite number or null");
    }
    return std::optional<double>(v->number_value());
  }

  Status Error(const std::string& key, std::string_view what) const {
    return Status::InvalidArgument(where_ + key + ": " + std::string(what));
  }

 private:
  const Struct& object_;
  std::string where_;
};

Result<lineage::CompletedGeneration> ReadGeneration(const Value& value,
                                                    const std::string& where) {
  if (value.kind_case() != Value::kStructValue) {
    return Status::InvalidArgument(where + ": not an object");
  }
  const Fields f(value.struct_value(), where + ".");
  lineage::CompletedGeneration g;
  Result<int64_t> generation = f.Integer("generation", 0, 1e9);
  if (!generation.ok()) return generation.status();
  g.generation = static_cast<int>(*generation);
  for (auto [key, out] : {std::pair{"best_fitness", &g.stats.best},
                          std::pair{"mean_fitness", &g.stats.mean},
                          std::pair{"median_fitness", &g.stats.median}}) {
    Result<std::optional<double>> x = f.Statistic(key);
    if (!x.ok()) return x.status();
    *out = *x;
  }
  return g;
}

Result<RunRecord> ParseRecord(const Struct& root, const std::string& file) {
  const Fields f(root, file + ": ");
  RunRecord record;
  Result<std::string> run = f.String("run");
  if (!run.ok()) return run.status();
  record.run = *run;
  Result<int64_t> seed = f.Integer("seed", 0, 9007199254740992.0);
  if (!seed.ok()) return seed.status();
  record.seed = *seed;
  Result<std::string> text = f.String("config_text");
  if (!text.ok()) return text.status();
  Status parsed = ParseProto(*text, ProtoFormat::kText, &record.config);
  if (!parsed.ok()) return f.Error("config_text", parsed.message());
  Result<const Value*> rows = f.Get("statistics", Value::kListValue);
  if (!rows.ok()) return rows.status();
  const auto& values = (*rows)->list_value().values();
  for (int i = 0; i < values.size(); ++i) {
    Result<lineage::CompletedGeneration> g = ReadGeneration(
        values[i], file + ": statistics[" + std::to_string(i) + "]");
    if (!g.ok()) return g.status();
    if (!record.generations.empty() &&
        g->generation <= record.generations.back().generation) {
      return f.Error("statistics", "generations not increasing");
    }
    record.generations.push_back(*g);
  }
  return record;
}

}  // namespace

Result<RunRecord> ReadRunRecord(const std::string& path) {
  std::error_code error;
  const std::string file =
      std::filesystem::is_directory(path, error)
          ? (std::filesystem::path(path) / "record.json").string()
          : path;
  Result<std::string> text = ReadFile(file);
  if (!text.ok()) return text.status();
  Struct root;
  Status parsed = ParseProto(*text, ProtoFormat::kJson, &root);
  if (!parsed.ok()) {
    return Status::InvalidArgument(file + ": " + parsed.message());
  }
  return ParseRecord(root, file);
}

}  // namespace animat::cli
