// animat signals (--genome FILE [--config FILE] | --db FILE --individual ID
//                 [--run R] | --trace FILE) [--json]
//
// How saturated the animat's morphogen signals are during motion, and how
// many steps a signal takes to cross its body (docs/analysis.md, "Signal
// saturation"; common/evaluation/signal_saturation.h).
#include <cstdio>
#include <memory>
#include <string>

#include "cli/animat_source.h"
#include "cli/commands.h"
#include "common/base/text.h"
#include "common/evaluation/signal_saturation.h"

namespace animat::cli {
namespace {

struct Options {
  AnimatSource source;
  bool json = false;
};

std::string Share(double share) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.4f", share);
  return text;
}

void PrintText(const SignalSaturation& s) {
  std::printf("cells: %d\n", s.cells);
  std::printf("motion_steps: %d\n", s.motion_steps);
  std::printf("diameter: %s\n", ShortestDouble(s.diameter).c_str());
  std::printf("crossing_steps: %d\n", s.crossing_steps);
  std::printf("kernel_sum_mean: %s\n",
              ShortestDouble(s.kernel_sum_mean).c_str());
  std::printf("kernel_sum_max: %s\n", ShortestDouble(s.kernel_sum_max).c_str());
  std::printf(
      "capped_share: %s (%lld of %lld)\n",
      Share(s.values() > 0 ? static_cast<double>(s.capped()) / s.values() : 0.0)
          .c_str(),
      s.capped(), s.values());
  if (s.morphogens.empty()) {
    std::printf("morphogens: none computed during motion\n");
    return;
  }
  std::printf("%-6s %12s %12s %8s\n", "node", "values", "capped", "share");
  for (const MorphogenSaturation& m : s.morphogens) {
    std::printf("%-6d %12lld %12lld %8s\n", m.node, m.values, m.capped,
                Share(m.share()).c_str());
  }
}

void PrintJson(const SignalSaturation& s) {
  std::string out = "{\n";
  out += "  \"cells\": " + std::to_string(s.cells) + ",\n";
  out += "  \"motion_steps\": " + std::to_string(s.motion_steps) + ",\n";
  out += "  \"diameter\": " + ShortestDouble(s.diameter) + ",\n";
  out += "  \"crossing_steps\": " + std::to_string(s.crossing_steps) + ",\n";
  out += "  \"kernel_sum_mean\": " + ShortestDouble(s.kernel_sum_mean) + ",\n";
  out += "  \"kernel_sum_max\": " + ShortestDouble(s.kernel_sum_max) + ",\n";
  out += "  \"values\": " + std::to_string(s.values()) + ",\n";
  out += "  \"capped\": " + std::to_string(s.capped()) + ",\n";
  out += "  \"morphogens\": [";
  for (size_t k = 0; k < s.morphogens.size(); ++k) {
    const MorphogenSaturation& m = s.morphogens[k];
    out += std::string(k > 0 ? "," : "") +
           "\n    {\"node\": " + std::to_string(m.node) +
           ", \"values\": " + std::to_string(m.values) +
           ", \"capped\": " + std::to_string(m.capped) +
           ", \"share\": " + ShortestDouble(m.share()) + "}";
  }
  out += s.morphogens.empty() ? "]\n}\n" : "\n  ]\n}\n";
  std::fputs(out.c_str(), stdout);
}

int Run(const Options& o) {
  Result<AnimatModel> model = LoadAnimatModel(o.source);
  if (!model.ok()) return Fail(model.status().message());
  Result<SignalSaturation> s =
      MeasureSignalSaturation(model->genome, model->config);
  if (!s.ok()) return Fail(s.status().message());
  if (o.json) {
    PrintJson(*s);
  } else {
    PrintText(*s);
  }
  return 0;
}

}  // namespace

Command AddSignalsCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "signals",
      "Measure how often the morphogen signals sit at their cap of 1 during "
      "motion, and the steps a signal takes to cross the body (exit 1 when "
      "the animat fails or the input is bad)");
  AddAnimatSourceOptions(sub, &options->source);
  sub->add_flag("--json", options->json, "Print one JSON object");
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
