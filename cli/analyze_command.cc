// animat analyze (--genome FILE [--config FILE] | --db FILE --individual ID
//   [--run R] | --trace FILE) [--from STEP] [--to STEP] [-o FILE]
//
// Body axes, activity along them, dominant period and amplitude of
// actuation, phase lags, driver cells and the swimming strategy
// (docs/analysis.md), as an animat.v1.Analysis. With -o FILE it also
// prints the strategy, its scores and features on standard output.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "analysis/analyze.h"
#include "cli/animat_source.h"
#include "cli/commands.h"
#include "common/io/proto_file.h"

namespace animat::cli {
namespace {

struct Options {
  AnimatSource source;
  std::optional<int64_t> from;
  std::optional<int64_t> to;
  std::string output = "-";
};

int Run(const Options& o) {
  if (o.output != "-") {
    Result<ProtoFormat> format = ProtoFormatForPath(o.output);
    if (!format.ok()) return Fail(format.status().message());
  }
  Result<v1::Trace> trace = LoadAnimatTrace(o.source);
  if (!trace.ok()) return Fail(trace.status().message());
  Result<analysis::Recording> recording = analysis::RecordingFromTrace(*trace);
  if (!recording.ok()) return Fail(recording.status().message());
  Result<analysis::Analysis> result =
      analysis::Analyze(*recording, {.from_step = o.from, .to_step = o.to});
  if (!result.ok()) return Fail(result.status().message());
  std::optional<double> fitness;
  if (trace->result().has_fitness()) fitness = trace->result().fitness();
  Status status =
      WriteProtoFile(o.output, analysis::AnalysisToProto(*result, fitness));
  if (!status.ok()) return Fail(status.message());
  // Which window, and why: standard output unless the analysis is there.
  const std::string window =
      "window: " + analysis::DescribeWindow(*result) + "\n";
  std::fputs(window.c_str(), o.output != "-" ? stdout : stderr);
  if (o.output != "-") {
    std::fputs(analysis::StrategySummary(result->strategy).c_str(), stdout);
  }
  return 0;
}

}  // namespace

Command AddAnalyzeCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "analyze",
      "Body axes, activity, period, amplitude, phase lags, driver cells "
      "and swimming strategy of an animat (docs/analysis.md)");
  AddAnimatSourceOptions(sub, &o->source);
  sub->add_option("--from", o->from,
                  "First motion step analysed (default: half way, or where "
                  "the animat actuates; docs/analysis.md)");
  sub->add_option("--to", o->to, "Last motion step analysed (default: last)");
  sub->add_option("-o,--output", o->output,
                  "Output file (.json, .txtpb); - for JSON on standard output "
                  "(otherwise the strategy is printed there)")
      ->capture_default_str();
  return [o] { return Run(*o); };
}

}  // namespace animat::cli
