// Subcommands of the `animat` tool. Each Add* registers its options on the
// app and returns the function that runs it (exit code 0 on success, 1 when
// the input is bad or a file cannot be written, with a message on stderr).
#ifndef ANIMAT_CLI_COMMANDS_H_
#define ANIMAT_CLI_COMMANDS_H_

#include <cstdint>
#include <functional>
#include <limits>

#include <CLI/CLI.hpp>

namespace animat::cli {

using Command = std::function<int()>;

Command AddRandomGenomeCommand(CLI::App& app);
Command AddGrnCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddSceneCommand(CLI::App& app);
Command AddEvolveCommand(CLI::App& app);
Command AddCampaignCommand(CLI::App& app);
Command AddLineageCommand(CLI::App& app);
Command AddAnalyzeCommand(CLI::App& app);
Command AddClusterCommand(CLI::App& app);
Command AddFigureCommand(CLI::App& app);
Command AddKeygenCommand(CLI::App& app);
Command AddRenderCommand(CLI::App& app);
Command AddConfigCommand(CLI::App& app);
Command AddSignalsCommand(CLI::App& app);

// Prints "animat: <message>" to stderr and returns 1.
int Fail(const std::string& message);

// Accepts only a whole number from 0 to `max` in decimal digits (no sign,
// no fraction), so that "-3" is refused rather than read as 2^64 - 3; the
// message calls it `noun`. For ids of individuals; runs take
// IdValidator(kMaxRunId).
CLI::Validator IdValidator(uint64_t max = std::numeric_limits<uint64_t>::max(),
                           const std::string& noun = "an id");
inline constexpr uint64_t kMaxRunId =
    static_cast<uint64_t>(std::numeric_limits<int64_t>::max());

}  // namespace animat::cli

#endif  // ANIMAT_CLI_COMMANDS_H_
