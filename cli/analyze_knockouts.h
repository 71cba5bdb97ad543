// animat analyze --knockouts: the animat intact and with each input that
// motion can use silenced (docs/analysis.md, "Knock-outs").
#ifndef ANIMAT_CLI_ANALYZE_KNOCKOUTS_H_
#define ANIMAT_CLI_ANALYZE_KNOCKOUTS_H_

#include <string>

#include "cli/animat_source.h"
#include "common/evaluation/knockout.h"

namespace animat::cli {

// The report as a text table, one row per evaluation (intact first), for
// people: numbers rounded, the file has them exact.
std::string KnockoutTable(const KnockoutReport& report);

// Evaluates the chosen animat intact and with every knock-out on up to
// `threads` threads, prints the table on standard output and, unless
// `output` is empty, writes the animat.v1.KnockoutAnalysis there ("-":
// JSON on standard output instead of the table). Returns the exit code.
int RunKnockoutAnalysis(const AnimatSource& source, const std::string& output,
                        int threads);

}  // namespace animat::cli

#endif  // ANIMAT_CLI_ANALYZE_KNOCKOUTS_H_
