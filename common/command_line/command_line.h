// Command-line parsing shared by every program built on CLI11 (`animat`,
// animat-master, animat-worker and the developer tools in bench/): one
// convention for exit codes and for the option values CLI11 lets through.
// Thread-safe as CLI11 is: one thread per CLI::App.
#ifndef ANIMAT_COMMON_COMMAND_LINE_COMMAND_LINE_H_
#define ANIMAT_COMMON_COMMAND_LINE_COMMAND_LINE_H_

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace animat {

// The first option value of `app`'s parse (its parsed subcommands
// included) that no program takes: an empty value, a whole number beyond
// 64 bits, a negative one for an unsigned option (CLI11 reads "-1" as
// 2^64 - 1), or a number that is not finite (nan, inf, an overflowing
// exponent). CLI11's own checks let these through. Returns a message
// naming the option, or "" when every value is well formed.
std::string MalformedOptionValue(const CLI::App& app);

// Parses `argc`/`argv` into `app`, then checks its values with
// MalformedOptionValue. Returns nullopt when the program should go on, or
// the code it should exit with now: 0 after --help or --version (printed
// by CLI11 on stdout), 2 after a usage error, said on stderr (CLI11's
// message, or "`program`: <option>: <why>" for a malformed value).
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv,
                                    const std::string& program);

}  // namespace animat

#endif  // ANIMAT_COMMON_COMMAND_LINE_COMMAND_LINE_H_
