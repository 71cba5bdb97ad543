// Writers of the accuracy report's files: accuracy.csv (one row per
// candidate and animat), summary.csv (one row per candidate), summary.md
// (the tables) and the plot's points for accuracy.svg.
//
// Pure functions of a Report; infinite errors (failures) print as "inf" in
// CSV and "fail" in markdown.
#ifndef ANIMAT_BENCH_ACCURACY_REPORT_H_
#define ANIMAT_BENCH_ACCURACY_REPORT_H_

#include <string>

#include "bench/accuracy/results.h"

namespace animat::accuracy {

std::string AccuracyCsv(const Report& report);
std::string SummaryCsv(const Report& report);
std::string SummaryMarkdown(const Report& report);
// accuracy.svg: median ms per evaluation against median relative fitness
// error, one point per measured candidate, the front marked.
std::string ReportSvg(const Report& report);

// A CSV field, quoted when it holds a comma, quote or line break.
std::string CsvField(const std::string& text);

}  // namespace animat::accuracy

#endif  // ANIMAT_BENCH_ACCURACY_REPORT_H_
