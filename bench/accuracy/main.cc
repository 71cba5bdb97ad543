// animat-accuracy: the speed-against-error report (docs/accuracy.md).
//
//   build/bin/animat-accuracy [--out docs/accuracy] [--quick]
//       [--repeats 3] [--animats N] [--data DIR] [--candidates R1f,S1f]
//       [--contact-near 0.1] [--contact-stiffness 1500]
//
// Evaluates a fixed set of animats (bench/data/accuracy/) under a reference
// configuration (RK4, 16 sub-steps, double) and under every candidate
// integrator, sub-step count, drag update, precision and backend, and writes
// accuracy.csv, summary.csv, summary.md and accuracy.svg into --out.
//
// Exit 0 once the report is written; 1 when --out cannot be a directory to
// write in (said before any work), the animat set or a candidate is wrong,
// or a file cannot be written; 2 on a usage error.
#include <unistd.h>

#include <CLI/CLI.hpp>

#include <cerrno>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "bench/accuracy/experiment.h"
#include "bench/accuracy/report.h"
#include "common/command_line/command_line.h"
#include "common/io/proto_file.h"

namespace {

struct Options {
  std::string out = "docs/accuracy";
  std::string data = ANIMAT_ACCURACY_DATA_DIR;
  bool quick = false;
  int repeats = 3;
  int animats = 0;
  std::vector<std::string> candidates;
  double contact_near = -1.0;
  double contact_stiffness = -1.0;
};

// Makes --out (and its parents) unless it exists, and checks that it is a
// directory that can be written, before any work; names the flag and the
// path otherwise.
animat::Status PrepareOutput(const std::string& out) {
  std::error_code error;
  std::filesystem::create_directories(out, error);
  if (!error && !std::filesystem::is_directory(out, error) && !error) {
    error = std::make_error_code(std::errc::not_a_directory);
  }
  if (!error && access(out.c_str(), W_OK | X_OK) != 0) {
    error = std::error_code(errno, std::generic_category());
  }
  if (error) {
    return animat::Status::InvalidArgument("--out " + out + ": " +
                                           error.message());
  }
  return animat::Status::Ok();
}

int Run(const Options& o) {
  if (const animat::Status status = PrepareOutput(o.out); !status.ok()) {
    std::cerr << "animat-accuracy: " << status.message() << "\n";
    return 1;
  }
  animat::accuracy::ExperimentOptions options;
  options.data_dir = o.data;
  options.quick = o.quick;
  options.repeats = o.quick ? 1 : o.repeats;
  options.max_animats = o.animats;  // 0: all, or --quick's subset.
  options.progress = &std::cerr;
  options.candidates = o.candidates;
  options.contact_near = o.contact_near;
  options.contact_stiffness = o.contact_stiffness;
  animat::Result<animat::accuracy::Report> report =
      animat::accuracy::RunExperiment(options);
  if (!report.ok()) {
    std::cerr << "animat-accuracy: " << report.status().message() << "\n";
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
  app.add_option("--contact-near", o.contact_near,
                 "physics.contact_near of the candidates with contact "
                 "sub-steps (default: the model's, 0.1)")
      ->check(CLI::Range(0.0, 1e6));
  app.add_option("--contact-stiffness", o.contact_stiffness,
                 "physics.contact_stiffness (k_c) of every configuration, "
                 "the reference included (default: the model's)")
      ->check(CLI::Range(0.0, 1e9));
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-accuracy")) {
    return *code;
  }
  return Run(o);
}
