// animat config defaults [--run]
//
// The built-in defaults as text protobuf on standard output: the model
// configuration (animat.v1.Config, for --config of simulate, analyze, ...)
// or, with --run, the run configuration (animat.v1.RunConfig, for
// animat evolve and animat-master), each field under a comment saying
// what it is and what values it takes (from the parameter tables).
// Either reads back as it is.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "common/evaluation/model_config.h"
#include "common/io/param_table.h"
#include "common/io/proto_file.h"
#include "master/evolution/evolution_params.h"

namespace animat::cli {
namespace {

struct Options {
  bool run = false;
};

int Defaults(const Options& o) {
  std::string text;
  if (o.run) {
    text =
        "# proto-file: proto/animat/v1/evolution.proto\n"
        "# proto-message: animat.v1.RunConfig\n"
        "# The defaults of this build (animat config defaults --run).\n\n" +
        AnnotateText(SerializeProto(RunSettingsToProto(RunSettings{}),
                                    ProtoFormat::kText),
                     RunParamDocs());
  } else {
    text =
        "# proto-file: proto/animat/v1/config.proto\n"
        "# proto-message: animat.v1.Config\n"
        "# The defaults of this build (animat config defaults).\n\n" +
        AnnotateText(
            SerializeProto(ConfigToProto(ModelConfig{}), ProtoFormat::kText),
            ModelParamDocs());
  }
  Status status = WriteFile("-", text);
  return status.ok() ? 0 : Fail(status.message());
}

}  // namespace

Command AddConfigCommand(CLI::App& app) {
  auto o = std::make_shared<Options>();
  CLI::App* config = app.add_subcommand(
      "config", "Configuration files: print the defaults (config defaults)");
  config->require_subcommand(1);
  CLI::App* defaults = config->add_subcommand(
      "defaults",
      "Print the default model configuration (animat.v1.Config) as text "
      "protobuf; it reads back with --config");
  defaults->add_flag("--run", o->run,
                     "The default run configuration instead "
                     "(animat.v1.RunConfig, for animat evolve --config)");
  return [o] { return Defaults(*o); };
}

}  // namespace animat::cli
