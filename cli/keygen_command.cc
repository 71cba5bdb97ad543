// animat keygen -o STEM | --cluster DIR: CurveZMQ key pairs for the master
// and its workers (docs/security.md).
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "common/security/curve_keys.h"

namespace animat::cli {
namespace {

struct Options {
  std::string stem;
  std::string cluster;
};

Status MakePair(const std::string& stem, const std::string& comment) {
  Result<security::CurveKeyPair> pair = security::GenerateKeyPair();
  if (!pair.ok()) return pair.status();
  Status status = security::WriteKeyPair(stem, *pair, comment);
  if (status.ok()) std::cout << stem << ".key, " << stem << ".pub\n";
  return status;
}

// DIR/master.{key,pub}, DIR/worker.{key,pub} (one pair shared by every
// worker of the cluster) and DIR/workers.allow listing the worker key.
Status MakeCluster(const std::string& dir) {
  if (mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST) {
    return Status::IoError(dir + ": " + std::strerror(errno));
  }
  const std::string allow = dir + "/workers.allow";
  std::ifstream existing(allow);
  if (existing) {
    return Status::InvalidArgument(allow +
                                   " exists; keys are never overwritten");
  }
  Status status = MakePair(dir + "/master", "animat master (CurveZMQ server)");
  if (!status.ok()) return status;
  Result<security::CurveKeyPair> worker = security::GenerateKeyPair();
  if (!worker.ok()) return worker.status();
  status = security::WriteKeyPair(dir + "/worker", *worker,
                                  "animat workers of this cluster");
  if (!status.ok()) return status;
  std::cout << dir << "/worker.key, " << dir << "/worker.pub\n";
  std::ofstream out(allow);
  out << "# Worker public keys the master serves: one per line, then an\n"
         "# optional name. Add lines for workers with keys of their own.\n"
      << worker->public_key << " cluster workers\n";
  out.close();
  if (!out) return Status::IoError(allow + ": write failed");
  std::cout << allow << "\n";
  return Status::Ok();
}

int Run(const Options& o) {
  Status status = o.cluster.empty()
                      ? MakePair(o.stem, "animat CurveZMQ key pair")
                      : MakeCluster(o.cluster);
  return status.ok() ? 0 : Fail(status.message());
}

}  // namespace

Command AddKeygenCommand(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "keygen",
      "Make CurveZMQ key pairs: STEM.key (secret, mode 600) and STEM.pub; "
      "or, with --cluster, a directory with the master's pair, one pair "
      "for every worker and the allow-list (docs/security.md)");
  auto* stem = sub->add_option("-o,--output", options->stem,
                               "Write STEM.key and STEM.pub");
  auto* cluster = sub->add_option(
      "--cluster", options->cluster,
      "Write DIR/master.{key,pub}, DIR/worker.{key,pub}, DIR/workers.allow");
  stem->excludes(cluster);
  sub->require_option(1);
  return [options] { return Run(*options); };
}

}  // namespace animat::cli
