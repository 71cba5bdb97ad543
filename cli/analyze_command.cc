// animat analyze (--genome FILE [--config FILE] | --db FILE --individual ID
//   [--run R] | --trace FILE) [--from STEP] [--to STEP] [-o FILE]
// animat analyze ... --knockouts [--threads N] [-o FILE]
//
// Body axes, activity along them, dominant period and amplitude of
// actuation, phase lags, driver cells and the swimming strategy
// (docs/analysis.md), as an animat.v1.Analysis. With -o FILE it also
// prints the strategy, its stability, scores and features on standard
// output (without, its label, margin and stability on standard error). With
// --knockouts, the animat intact and with each input motion can use
// silenced in turn, as a table (and an animat.v1.KnockoutAnalysis with -o).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "analysis/analyze.h"
#include "cli/analyze_knockouts.h"
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
  bool output_given = false;
  bool knockouts = false;
  int threads = 1;
};

int Run(const Options& o) {
  if (o.knockouts) {
    return RunKnockoutAnalysis(o.source, o.output_given ? o.output : "",
                               o.threads);
  }
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
  // Which window, and why, and the label: standard output unless the
  // analysis is there.
  const std::string window =
      "window: " + analysis::DescribeWindow(*result) + "\n";
  if (o.output != "-") {
    std::fputs(window.c_str(), stdout);
    std::fputs(analysis::StrategySummary(result->strategy).c_str(), stdout);
  } else {
    std::fputs(window.c_str(), stderr);
    std::fputs(analysis::StrategyHeadline(result->strategy).c_str(), stderr);
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
  CLI::Option* from =
      sub->add_option("--from", o->from,
                      "First motion step analysed (default: half way, or "
                      "where the animat actuates; docs/analysis.md)");
  CLI::Option* to = sub->add_option(
      "--to", o->to, "Last motion step analysed (default: last)");
  CLI::Option* output =
      sub->add_option("-o,--output", o->output,
                      "Output file (.json, .txtpb); - for JSON on standard "
                      "output (otherwise the strategy, or with --knockouts "
                      "the table, is printed there)")
          ->capture_default_str();
  o->threads = static_cast<int>(
      std::clamp(std::thread::hardware_concurrency(), 1u, 256u));
  CLI::Option* threads =
      sub->add_option("--threads", o->threads,
                      "Evaluations at once with --knockouts (default: the "
                      "cores; the results do not depend on it)")
          ->check(CLI::Range(1, 256));
  sub->add_flag("--knockouts", o->knockouts,
                "Evaluate the animat intact, then with CHEMICAL (with "
                "guidance) and each morphogen motion uses silenced during "
                "motion; a table on standard output (docs/analysis.md, "
                "Knock-outs)")
      ->excludes(from)
      ->excludes(to)
      ->excludes(sub->get_option("--every"));
  threads->needs(sub->get_option("--knockouts"));
  return [o, output] {
    o->output_given = output->count() > 0;
    return Run(*o);
  };
}

}  // namespace animat::cli
