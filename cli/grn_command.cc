// animat grn --genome FILE --inputs a,b,c,d --steps N [--config FILE]
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/load.h"
#include "common/base/text.h"
#include "common/grn/grn_batch.h"
#include "common/grn/network.h"

namespace animat::cli {
namespace {

struct Options {
  std::string genome;
  std::string config;
  std::vector<double> inputs;
  int steps = 0;
};

std::string NodeName(const Node& node) {
  const std::string index = std::to_string(node.first_element);
  switch (node.kind) {
    case NodeKind::kUnit:
      return "unit_" + index;
    case NodeKind::kInput:
      return "in_" + index + "_" + InputChannelName(node.channel);
    case NodeKind::kOutput:
      return "out_" + index + "_" + OutputChannelName(node.channel);
  }
  return "?";
}

int Run(const Options& o) {
  Result<Genome> genome = LoadGenome(o.genome);
  if (!genome.ok()) return Fail(genome.status().message());
  Result<ModelConfig> config = LoadConfig(o.config);
  if (!config.ok()) return Fail(config.status().message());
  std::array<double, kInputChannels> inputs{};  // CHEMICAL 0 when not given.
  for (int c = 0; c < static_cast<int>(o.inputs.size()); ++c) {
    if (!std::isfinite(o.inputs[c])) {
      return Fail(std::string("--inputs: the ") + InputChannelName(c) +
                  " value is not finite");
    }
    inputs[c] = o.inputs[c];
  }

  const Network network = Network::Build(*genome, config->grn);
  GrnBatch grn(network, config->grn, 1);
  grn.AddCell();
  grn.SetInputs(0, inputs);

  std::string out = "step";
  for (const Node& node : network.nodes()) out += "," + NodeName(node);
  out += "\n";
  for (int step = 1; step <= o.steps; ++step) {
    grn.SetOwnSignals();
    grn.Step();
    out += std::to_string(step);
    for (int v = 0; v < network.node_count(); ++v) {
      out += "," + ShortestDouble(grn.level(0, v));
    }
    out += "\n";
    if (out.size() > (1 << 16)) {
      std::fputs(out.c_str(), stdout);
      out.clear();
    }
  }
  std::fputs(out.c_str(), stdout);
  return std::fflush(stdout) == 0 ? 0 : Fail("stdout: write failed");
}

}  // namespace

Command AddGrnCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "grn",
      "Run the network of one isolated cell with fixed inputs and print its "
      "trajectory as CSV: row t is the state after step t, one column per "
      "node in node order");
  sub->add_option("--genome", options->genome, "Genome file (.json, .txtpb)")
      ->required();
  sub->add_option("--inputs", options->inputs,
                  "Input values MATERNAL_0,MATERNAL_1,MATERNAL_2,UNIFORM and "
                  "optionally CHEMICAL (0 when left out)")
      ->delimiter(',')
      ->expected(kPaperInputChannels, kInputChannels)
      ->required();
  sub->add_option("--steps", options->steps, "Steps to run")
      ->check(CLI::Range(0, 100000000))
      ->required();
  sub->add_option("--config", options->config,
                  "Configuration file (defaults: docs/model.md)");
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
