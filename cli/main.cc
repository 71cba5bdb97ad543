// animat: develop, simulate and inspect animats (docs/formats.md).
#include <iostream>
#include <map>
#include <optional>
#include <string>

#include "cli/commands.h"
#include "common/command_line/command_line.h"
#include "common/kernels/isa.h"
#include "common/protocol/protocol.h"

int main(int argc, char** argv) {
  CLI::App app{
      "animat: evolve soft-bodied, brainless animats (see README.md and "
      "docs/formats.md)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", animat::protocol::VersionText(),
                       "Print the build id, protocol and model versions");
  std::map<std::string, animat::cli::Command> commands;
  commands["random-genome"] = animat::cli::AddRandomGenomeCommand(app);
  commands["grn"] = animat::cli::AddGrnCommand(app);
  commands["simulate"] = animat::cli::AddSimulateCommand(app);
  commands["scene"] = animat::cli::AddSceneCommand(app);
  commands["evolve"] = animat::cli::AddEvolveCommand(app);
  commands["campaign"] = animat::cli::AddCampaignCommand(app);
  commands["lineage"] = animat::cli::AddLineageCommand(app);
  commands["analyze"] = animat::cli::AddAnalyzeCommand(app);
  commands["cluster"] = animat::cli::AddClusterCommand(app);
  commands["figure"] = animat::cli::AddFigureCommand(app);
  commands["keygen"] = animat::cli::AddKeygenCommand(app);
  commands["render"] = animat::cli::AddRenderCommand(app);
  commands["config"] = animat::cli::AddConfigCommand(app);
  commands["signals"] = animat::cli::AddSignalsCommand(app);
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat")) {
    return *code;
  }
  // A mistyped ANIMAT_ISA is refused, not silently replaced.
  if (const animat::Result<animat::Isa> isa = animat::IsaFromEnvironment();
      !isa.ok()) {
    std::cerr << "animat: " << isa.status().message() << "\n";
    return 2;
  }
  for (const CLI::App* sub : app.get_subcommands()) {
    return commands.at(sub->get_name())();
  }
  return 2;
}
