#include "cli/analyze_knockouts.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "cli/commands.h"
#include "common/io/proto_file.h"

namespace animat::cli {
namespace {

std::string Fixed(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string YesNo(bool value) { return value ? "yes" : "no"; }

using Row = std::vector<std::string>;

Row TableRow(const std::string& name, const KnockoutRun& run,
             const KnockoutReport& report) {
  const EvaluationResult& r = run.result;
  Row row = {name, EvalStatusName(r.status)};
  row.push_back(r.fitness ? Fixed("%.5g", *r.fitness) : "-");
  // Exactly 0 (the same bits) apart from a change too small to show.
  row.push_back(!run.fitness_change ? "-"
                : *run.fitness_change == 0
                    ? "0"
                    : Fixed("%+.5g", *run.fitness_change));
  row.push_back(r.distance ? Fixed("%.5g", *r.distance) : "-");
  switch (run.knockout.kind) {
    case Knockout::Kind::kNone:
      row.insert(row.end(), {"", ""});
      break;
    case Knockout::Kind::kChemical:
      row.insert(row.end(), {"", YesNo(run.actuator_path)});
      break;
    case Knockout::Kind::kMorphogen:
      row.insert(row.end(),
                 {YesNo(run.chemical_path), YesNo(run.actuator_path)});
      break;
  }
  if (report.guidance) {
    std::string distances;
    for (double d : r.source_distances) {
      if (!distances.empty()) distances += ' ';
      distances += Fixed("%.2f", d);
    }
    row.push_back(distances.empty() ? "-" : distances);
  }
  return row;
}

}  // namespace

std::string KnockoutTable(const KnockoutReport& report) {
  std::vector<Row> rows = {{"silenced", "status", "fitness", "change",
                            "distance", "from CHEMICAL", "to actuators"}};
  if (report.guidance) rows[0].push_back("source distances");
  KnockoutRun intact;
  intact.result = report.intact;
  rows.push_back(TableRow("nothing (intact)", intact, report));
  for (const KnockoutRun& run : report.runs) {
    const std::string name =
        run.knockout.kind == Knockout::Kind::kChemical
            ? "CHEMICAL"
            : "M of unit_" + std::to_string(run.unit_element) + " (node " +
                  std::to_string(run.knockout.node) + ")";
    rows.push_back(TableRow(name, run, report));
  }
  std::vector<size_t> width(rows[0].size(), 0);
  for (const Row& row : rows) {
    for (size_t c = 0; c < row.size(); ++c) {
      width[c] = std::max(width[c], row[c].size());
    }
  }
  std::string text;
  for (const Row& row : rows) {
    std::string line;
    for (size_t c = 0; c < row.size(); ++c) {
      line += row[c];
      if (c + 1 < row.size())
        line += std::string(width[c] - row[c].size() + 2, ' ');
    }
    line.erase(line.find_last_not_of(' ') + 1);
    text += line + "\n";
  }
  return text;
}

int RunKnockoutAnalysis(const AnimatSource& source, const std::string& output,
                        int threads) {
  if (!output.empty() && output != "-") {
    Result<ProtoFormat> format = ProtoFormatForPath(output);
    if (!format.ok()) return Fail(format.status().message());
  }
  Result<AnimatModel> model = LoadAnimatModel(source);
  if (!model.ok()) return Fail(model.status().message());
  const KnockoutReport report =
      RunKnockouts(model->genome, model->config, threads);
  if (!output.empty()) {
    Status status = WriteProtoFile(output, KnockoutReportToProto(report));
    if (!status.ok()) return Fail(status.message());
    if (output == "-") return 0;
  }
  std::fputs(KnockoutTable(report).c_str(), stdout);
  return 0;
}

}  // namespace animat::cli
