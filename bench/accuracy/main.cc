// animat-accuracy: the speed-against-error report (docs/accuracy.md).
//
//   build/bin/animat-accuracy [--out docs/accuracy] [--quick]
//       [--repeats 3] [--animats N] [--data DIR] [--candidates R1f,S1f]
//
// Evaluates a fixed set of animats (bench/data/accuracy/) under a reference
// configuration (RK4, 16 sub-steps, double) and under every candidate
// integrator, sub-step count, drag update, precision and backend, and writes
// accuracy.csv, summary.csv, summary.md and accuracy.svg into --out.
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <vector>

#include "bench/accuracy/experiment.h"
#include "bench/accuracy/report.h"
#include "common/io/proto_file.h"

namespace {

struct Options {
  std::string out = "docs/accuracy";
  std::string data = ANIMAT_ACCURACY_DATA_DIR;
  bool quick = false;
  int repeats = 3;
  int animats = 0;
  std::vector<std::string> candidates;
};

int Run(const Options& o) {
  animat::accuracy::ExperimentOptions options;
  options.data_dir = o.data;
  options.quick = o.quick;
  options.repeats = o.quick ? 1 : o.repeats;
  options.max_animats = o.animats;  // 0: all, or --quick's subset.
  options.progress = &std::cerr;
  options.candidates = o.candidates;
  animat::Result<animat::accuracy::Report> report =
      animat::accuracy::RunExperiment(options);
  if (!report.ok()) {
    std::cerr << "animat-accuracy: " << report.status().message() << "\n";
    return 1;
  }

  std::error_code error;
  std::filesystem::create_directories(o.out, error);
  if (error) {
    std::cerr << "animat-accuracy: " << o.out << ": " << error.message()
              << "\n";
    return 1;
  }
  const std::string markdown = animat::accuracy::SummaryMarkdown(*report);
  const std::pair<std::string, std::string> files[] = {
      {"accuracy.csv", animat::accuracy::AccuracyCsv(*report)},
      {"summary.csv", animat::accuracy::SummaryCsv(*report)},
      {"summary.md", markdown},
      {"accuracy.svg", animat::accuracy::ReportSvg(*report)},
  };
  for (const auto& [name, contents] : files) {
    animat::Status status = animat::WriteFile(o.out + "/" + name, contents);
    if (!status.ok()) {
      std::cerr << "animat-accuracy: " << status.message() << "\n";
      return 1;
    }
  }
  std::cout << markdown << "\nwritten: " << o.out
            << "/{accuracy.csv,summary.csv,summary.md,accuracy.svg}\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "animat-accuracy: speed against error of the integrators, sub-steps, "
      "drag updates, precisions and backends (docs/accuracy.md)"};
  Options o;
  app.add_option("--out", o.out, "Output directory")->capture_default_str();
  app.add_option("--data", o.data, "Directory of the animat set's genomes")
      ->capture_default_str();
  app.add_flag("--quick", o.quick,
               "A smaller run for CI: 5 animats (the first 4 random and the "
               "first evolved), 1 repetition, no chaos run of the reference");
  app.add_option("--repeats", o.repeats, "Timed repetitions of the whole set")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--animats", o.animats,
                 "Use only the first N animats by name (0: all, or "
                 "--quick's 4 random and 1 evolved)")
      ->check(CLI::Range(0, 100000));
  app.add_option("--candidates", o.candidates,
                 "Only these candidates, by label (e.g. R1f,S1f; default: "
                 "all)")
      ->delimiter(',');
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return Run(o);
}
