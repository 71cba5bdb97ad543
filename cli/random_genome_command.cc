// animat random-genome --seed S [--individual I] [--units 10] -o FILE
#include <cstdint>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "common/base/rng.h"
#include "common/genome/genome_proto.h"
#include "common/genome/random_genome.h"
#include "common/io/proto_file.h"

namespace animat::cli {
namespace {

struct Options {
  uint64_t seed = 0;
  uint64_t individual = 0;
  int units = 10;
  std::string output;
};

int Run(const Options& o) {
  RandomStream stream(o.seed, o.individual, StreamPurpose::kRandomGenome);
  const Genome genome = RandomGenome(stream, o.units);
  Status status = WriteProtoFile(o.output, GenomeToProto(genome));
  if (!status.ok()) return Fail(status.message());
  return 0;
}

}  // namespace

Command AddRandomGenomeCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "random-genome",
      "Write a random genome (docs/model.md §9.3): UNITS regulatory units of "
      "one P and one G element, never split by an S element, plus one S "
      "element per input and output channel");
  sub->add_option("--seed", options->seed, "Run seed")
      ->required()
      ->check(IdValidator(std::numeric_limits<uint64_t>::max(), "a seed"));
  sub->add_option("--individual", options->individual,
                  "Individual number: one seed gives a stream of genomes")
      ->check(IdValidator())
      ->capture_default_str();
  sub->add_option("--units", options->units, "Regulatory units")
      ->check(CLI::Range(0, 4000))
      ->capture_default_str();
  sub->add_option("-o,--output", options->output,
                  "Output file: .json, .txtpb or .binpb; - for JSON on "
                  "stdout")
      ->required();
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
