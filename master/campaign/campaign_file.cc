#include "master/campaign/campaign_file.h"

#include <cstdint>
#include <filesystem>
#include <set>
#include <utility>

#include "common/io/proto_file.h"

namespace animat {
namespace {

// A campaign beyond this is most likely a grid written by mistake; each
// run holds a store and a thread of the master.
constexpr size_t kMaxRuns = 1000;

bool FileNameSafe(const std::string& part) {
  if (part.empty() || part.size() > 100 || part[0] == '.' || part[0] == '-') {
    return false;
  }
  for (char c : part) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                    (c >= '0' && c <= '9') || c == '.' || c == '-' || c == '_';
    if (!ok) return false;
  }
  return true;
}

Status CheckPart(const std::string& where, const std::string& part) {
  if (FileNameSafe(part)) return Status::Ok();
  return Status::InvalidArgument(
      where + ": \"" + part.substr(0, 100) +
      "\" is not usable in a file name: use 1 to 100 letters, digits, '.', "
      "'-' or '_', not starting with '.' or '-'");
}

// Merges `text` (RunConfig fields in text format) into `config`.
Status MergeText(const std::string& where, const std::string& text,
                 v1::RunConfig* config) {
  if (text.empty()) return Status::Ok();
  v1::RunConfig fields;
  Status status = ParseProto(text, ProtoFormat::kText, &fields);
  if (!status.ok()) return status.WithPrefix(where);
  config->MergeFrom(fields);
  return Status::Ok();
}

struct Value {
  std::string label;
  v1::RunConfig fields;
};

// The axes' values, parsed; errors name the value.
Result<std::vector<std::vector<Value>>> ParseAxes(const v1::CampaignRuns& runs,
                                                  const std::string& where) {
  std::vector<std::vector<Value>> axes;
  for (int a = 0; a < runs.axes_size(); ++a) {
    const std::string axis = where + ".axes[" + std::to_string(a) + "]";
    if (runs.axes(a).values_size() == 0) {
      return Status::InvalidArgument(axis + ": an axis needs values");
    }
    std::vector<Value> values;
    for (int v = 0; v < runs.axes(a).values_size(); ++v) {
      const v1::CampaignValue& value = runs.axes(a).values(v);
      const std::string at = axis + ".values[" + std::to_string(v) + "]";
      if (!value.label().empty()) {
        Status status = CheckPart(at + ".label", value.label());
        if (!status.ok()) return status;
      }
      Value parsed{value.label(), {}};
      Status status = MergeText(at + ".set", value.set(), &parsed.fields);
      if (!status.ok()) return status;
      values.push_back(std::move(parsed));
    }
    axes.push_back(std::move(values));
  }
  return axes;
}

// The configuration of runs[`index`] before its axes: the file and `set`.
Result<v1::RunConfig> BaseConfig(const v1::CampaignRuns& runs,
                                 const std::string& where,
                                 const std::string& base_dir) {
  v1::RunConfig config;
  if (!runs.config().empty()) {
    std::filesystem::path path(runs.config());
    if (path.is_relative() && !base_dir.empty()) path = base_dir / path;
    Status status = ReadProtoFile(path.string(), &config);
    if (!status.ok()) return status.WithPrefix(where + ".config");
  }
  Status status = MergeText(where + ".set", runs.set(), &config);
  if (!status.ok()) return status;
  return config;
}

// Appends the runs of one CampaignRuns entry.
Status Expand(const v1::CampaignRuns& runs, const std::string& where,
              const std::string& base_dir, std::vector<CampaignRun>* out) {
  if (!runs.name().empty()) {
    Status status = CheckPart(where + ".name", runs.name());
    if (!status.ok()) return status;
  }
  Result<v1::RunConfig> base = BaseConfig(runs, where, base_dir);
  if (!base.ok()) return base.status();
  Result<std::vector<std::vector<Value>>> axes = ParseAxes(runs, where);
  if (!axes.ok()) return axes.status();
  std::vector<size_t> choice(axes->size(), 0);  // An odometer.
  for (;;) {
    v1::RunConfig combined = *base;
    std::string name = runs.name();
    const auto add = [&name](const std::string& part) {
      if (part.empty()) return;
      if (!name.empty()) name += '-';
      name += part;
    };
    for (size_t a = 0; a < axes->size(); ++a) {
      const Value& value = (*axes)[a][choice[a]];
      combined.MergeFrom(value.fields);
      add(value.label);
    }
    const bool seeded = runs.seeds_size() > 0;
    for (int s = 0; s < (seeded ? runs.seeds_size() : 1); ++s) {
      CampaignRun run;
      run.name = name;
      run.config = combined;
      if (seeded) {
        const uint64_t seed = runs.seeds(s);
        run.name +=
            (run.name.empty() ? "seed" : "-seed") + std::to_string(seed);
        run.config.mutable_evolution()->set_seed(seed);
      }
      if (run.name.empty()) {
        return Status::InvalidArgument(
            where + ": its runs have no name: give a name, labels or seeds");
      }
      Status status = RunSettingsFromProto(run.config, &run.settings);
      if (!status.ok())
        return status.WithPrefix(where + " (run " + run.name + ")");
      out->push_back(std::move(run));
      if (out->size() > kMaxRuns) {
        return Status::InvalidArgument(
            where + ": the campaign has more than " + std::to_string(kMaxRuns) +
            " runs; split it into several campaigns");
      }
    }
    size_t a = axes->size();
    while (a > 0 && ++choice[a - 1] == (*axes)[a - 1].size()) {
      choice[--a] = 0;
    }
    if (a == 0) return Status::Ok();
  }
}

}  // namespace

Result<std::vector<CampaignRun>> ExpandCampaign(const v1::Campaign& campaign,
                                                const std::string& base_dir) {
  std::vector<CampaignRun> runs;
  for (int i = 0; i < campaign.runs_size(); ++i) {
    Status status = Expand(campaign.runs(i), "runs[" + std::to_string(i) + "]",
                           base_dir, &runs);
    if (!status.ok()) return status;
  }
  if (runs.empty()) {
    return Status::InvalidArgument("the campaign has no runs (runs { ... })");
  }
  std::set<std::string> names;
  for (const CampaignRun& run : runs) {
    if (!names.insert(run.name).second) {
      return Status::InvalidArgument("two runs are named " + run.name +
                                     "; each run needs its own name (store)");
    }
  }
  return runs;
}

Result<std::vector<CampaignRun>> ReadCampaignFile(const std::string& path) {
  v1::Campaign campaign;
  Status status = ReadProtoFile(path, &campaign);
  if (!status.ok()) return status;
  Result<std::vector<CampaignRun>> runs = ExpandCampaign(
      campaign, std::filesystem::path(path).parent_path().string());
  if (!runs.ok()) return runs.status().WithPrefix(path);
  return runs;
}

}  // namespace animat
