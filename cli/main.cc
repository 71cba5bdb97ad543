// animat: develop, simulate and inspect animats (docs/formats.md).
#include <iostream>
#include <map>
#include <string>

#include "cli/commands.h"
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
  commands["lineage"] = animat::cli::AddLineageCommand(app);
  commands["analyze"] = animat::cli::AddAnalyzeCommand(app);
  commands["figure"] = animat::cli::AddFigureCommand(app);
  commands["keygen"] = animat::cli::AddKeygenCommand(app);
  commands["render"] = animat::cli::AddRenderCommand(app);
  commands["config"] = animat::cli::AddConfigCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  if (const std::string why = animat::cli::MalformedOptionValue(app);
      !why.empty()) {
    std::cerr << "animat: " << why
              << "\nRun with --help for more information.\n";
    return 2;
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
