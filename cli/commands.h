// Subcommands of the `animat` tool. Each Add* registers its options on the
// app and returns the function that runs it (exit code 0 on success, 1 when
// the input is bad or a file cannot be written, with a message on stderr).
#ifndef ANIMAT_CLI_COMMANDS_H_
#define ANIMAT_CLI_COMMANDS_H_

#include <functional>

#include <CLI/CLI.hpp>

namespace animat::cli {

using Command = std::function<int()>;

Command AddRandomGenomeCommand(CLI::App& app);
Command AddGrnCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddSceneCommand(CLI::App& app);
Command AddEvolveCommand(CLI::App& app);
Command AddLineageCommand(CLI::App& app);
Command AddAnalyzeCommand(CLI::App& app);
Command AddFigureCommand(CLI::App& app);
Command AddKeygenCommand(CLI::App& app);
Command AddRenderCommand(CLI::App& app);

// Prints "animat: <message>" to stderr and returns 1.
int Fail(const std::string& message);

}  // namespace animat::cli

#endif  // ANIMAT_CLI_COMMANDS_H_
