// The master's throughput, end to end (docs/benchmarks.md, "Master
// throughput"):
//
//   build/bin/animat-master-bench [--population P] [--generations G]
//       [--workers W] [--threads T] [--db FILE] [--endpoint ENDPOINT]
//
// (defaults: 5000 and 10, about 51,000 individuals; 2 workers of 64).
//
// The real master path: animat-master's run loop (EvolutionRun) makes each
// individual, commits it to the lineage store (an SQLite file on disk,
// opened as animat-master opens it, so WAL and the same pragmas), submits
// it to a Dispatcher bound on loopback TCP (or --endpoint), which leases
// it to real `animat-worker --null-evaluation` processes; their answers
// come back over ZeroMQ and are recorded in batched transactions. Null
// workers simulate nothing, so the figure is what the master sustains.
//
// Null results carry no fitness: the run is served through
// bench/null_scoring.h, which scores each as OK with a pseudo-random
// fitness of the seed and id, recorded by the same store write as a real
// result. So the initial population is the
// first P candidates and every later generation is selected, varied, made
// and recorded as in a real run.
//
// The figure: individuals in the store once the run has finished, divided
// by the seconds EvolutionRun::Run took (its start to the commit of the
// last result). Before it is printed, the store is reopened and checked:
// every individual evaluated, with its expected fitness, a worker and a
// time; every offspring with its parents; every generation complete, with
// its ranked members. A failed check exits 1.
//
// Exit 0 when the run finished and checked; 1 when it did not, or when
// --worker, --worker-log or --db cannot serve (said before the run);
// 2 on a usage error (a malformed value, an endpoint beyond loopback).
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <zmq.hpp>

#include <google/protobuf/stubs/logging.h>
#include <CLI/CLI.hpp>

#include "bench/null_scoring.h"
#include "bench/timing.h"
#include "bench/worker_processes.h"
#include "common/command_line/command_line.h"
#include "common/protocol/endpoint.h"
#include "master/dispatch/dispatcher.h"
#include "master/lineage/queries.h"
#include "master/lineage/store.h"
#include "master/run/evolution_run.h"

namespace animat {
namespace {

using bench::Clock;
using bench::CpuSeconds;
using bench::SecondsSince;

struct Options {
  int population = 5000;
  int generations = 10;
  uint64_t seed = 1;
  int workers = 2;
  int threads = 64;
  std::string db;  // Empty: a temporary file, removed afterwards.
  std::string endpoint = "tcp://127.0.0.1:*";
  int heartbeat_ms = protocol::kHeartbeatMs;
  std::string worker = ANIMAT_WORKER_PATH;
  std::string worker_log = "/dev/null";
  bool verbose = false;
};

void RemoveStore(const std::string& path) {
  for (const char* suffix : {"", "-wal", "-shm", ".lock"}) {
    std::remove((path + suffix).c_str());
  }
}

long long FileBytes(const std::string& path) {
  FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) return 0;
  std::fseek(file, 0, SEEK_END);
  const long long bytes = std::ftell(file);
  std::fclose(file);
  return bytes;
}

struct Counts {
  int64_t made = 0;      // Individuals in the store.
  int64_t recorded = 0;  // Of those, evaluated.
};

// Reopens the store for queries and checks that it holds the whole run.
// Returns how many individuals it holds, or what is missing.
Result<Counts> Verify(const std::string& path, int64_t run,
                      const Options& options) {
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::OpenForQueries(path);
  if (!store.ok()) return store.status();
  Result<lineage::RunCounts> n = lineage::CountRun(**store, run);
  if (!n.ok()) return n.status();
  std::vector<std::string> problems;
  const auto expect = [&](const std::string& what, int64_t found,
                          int64_t wanted) {
    if (found != wanted) {
      problems.push_back(what + ": " + std::to_string(found) + ", expected " +
                         std::to_string(wanted));
    }
  };

  expect("finished runs", n->finished ? 1 : 0, 1);

  // Every individual recorded: evaluated OK with a fitness, by a worker, at
  // a time, with its genome. Only initial candidates not chosen may still
  // have been on their way when the run ended (a resumed run would send
  // them again).
  const int64_t made = n->individuals;
  const int64_t count = n->evaluated;
  expect("individuals with status ok", n->ok, count);
  expect("individuals with a fitness", n->with_fitness, count);
  expect("individuals with a worker", n->with_worker, count);
  expect("individuals with an evaluation time", n->with_evaluation_time, count);
  expect("individuals with a genome", n->with_genome, made);
  const int64_t per_generation = options.population - EvolutionParams{}.elite;
  expect("offspring", n->offspring,
         static_cast<int64_t>(options.generations - 1) * per_generation);
  expect("members or offspring not evaluated", n->needed_unevaluated, 0);

  // Each fitness is the one its id gives: the result recorded is the
  // individual's own.
  Result<std::vector<lineage::Score>> scores = lineage::Scores(**store, run);
  if (!scores.ok()) return scores.status();
  int64_t wrong = 0;
  for (const lineage::Score& score : *scores) {
    wrong += score.fitness && *score.fitness != bench::NullEvaluationFitness(
                                                    options.seed, score.id);
  }
  expect("individuals with another fitness than their own", wrong, 0);

  // Every offspring has its parents.
  expect("offspring without parents", n->offspring_without_parents, 0);

  // Every generation complete, its members ranked.
  const int64_t members = static_cast<int64_t>(options.generations) *
                          static_cast<int64_t>(options.population);
  expect("generations", n->generations, options.generations);
  expect("complete generations", n->complete_generations, options.generations);
  expect("members evaluated OK", n->generations_evaluated, members);
  expect("members", n->members, members);
  expect("ranked members", n->ranked_members, members);

  if (!problems.empty()) {
    std::string message = path + ": the store does not hold the run:";
    for (const std::string& p : problems) message += " " + p + ";";
    return Status::Internal(message);
  }
  return Counts{made, count};
}

int Bench(const Options& options) {
  const LogSink quiet = [](std::string_view) {};
  DispatcherOptions dispatcher_options;
  dispatcher_options.endpoint = options.endpoint;
  dispatcher_options.accept_null_workers = true;
  dispatcher_options.acknowledge_on_receipt = false;  // As animat-master.
  dispatcher_options.heartbeat_ms = options.heartbeat_ms;
  dispatcher_options.log =
      options.verbose ? Prefixed("dispatcher", StderrSink) : quiet;
  // What the dispatcher would refuse is refused before the store is made.
  if (const Status status = Dispatcher::CheckOptions(dispatcher_options);
      !status.ok()) {
    std::fprintf(stderr, "animat-master-bench: --endpoint: %s\n",
                 status.message().c_str());
    return 2;
  }

  const bool temporary = options.db.empty();
  std::string path = options.db;
  if (temporary) {
    const char* dir = std::getenv("TMPDIR");
    path = std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") +
           "/animat-master-bench-" + std::to_string(getpid()) + ".db";
    RemoveStore(path);
  }
  const LogSink log = options.verbose ? Prefixed("master", StderrSink) : quiet;

  RunSettings settings;
  settings.evolution.seed = options.seed;
  settings.evolution.population = options.population;
  settings.evolution.generations = options.generations;
  std::printf(
      "master throughput: population %d, %d generations, %d null-evaluation "
      "workers of %d threads (credit %d), %s, store %s\n",
      options.population, options.generations, options.workers, options.threads,
      options.workers * options.threads * protocol::kPrefetch,
      options.endpoint.c_str(), path.c_str());

  Result<std::unique_ptr<lineage::Store>> store = lineage::Store::Open(path);
  if (!store.ok()) {
    std::fprintf(stderr, "animat-master-bench: %s%s\n",
                 temporary ? "" : "--db: ", store.status().message().c_str());
    return 1;
  }
  Result<std::unique_ptr<EvolutionRun>> run =
      EvolutionRun::Start(store->get(), settings, log);
  if (!run.ok()) {
    std::fprintf(stderr, "%s\n", run.status().ToString().c_str());
    return 1;
  }
  const int64_t run_id = (*run)->run_id();

  zmq::context_t context(1);
  Result<std::unique_ptr<Dispatcher>> dispatcher = Dispatcher::Create(
      &context, dispatcher_options, ConfigToProto((*run)->model_config()));
  if (!dispatcher.ok()) {
    std::fprintf(stderr, "%s\n", dispatcher.status().ToString().c_str());
    return 1;
  }
  bench::WorkerProcesses workers(options.worker, options.worker_log,
                                 dispatcher->get());
  if (!workers.Spawn(options.workers, options.threads, true)) return 1;

  // Seconds from the start of Run to the end of each generation.
  std::vector<double> ends;
  const std::atomic<bool> stop{false};
  const double cpu = CpuSeconds(RUSAGE_SELF);
  const Clock::time_point start = Clock::now();
  bench::NullScoring scoring(dispatcher->get(), options.seed);
  const Status status = (*run)->Run(
      &scoring, stop,
      [&](const GenerationReport&) { ends.push_back(SecondsSince(start)); });
  const double seconds = SecondsSince(start);
  const double master_cpu = CpuSeconds(RUSAGE_SELF) - cpu;
  if (!status.ok()) {
    std::fprintf(stderr, "%s\n", status.ToString().c_str());
    return 1;
  }
  const DispatcherStats stats = (*dispatcher)->stats();
  workers.Stop();
  const double workers_cpu = CpuSeconds(RUSAGE_CHILDREN);
  const bool finished = (*run)->finished();
  run->reset();
  store->reset();  // Closes the store (a checkpoint) and frees its lock.
  if (!finished) {
    std::fprintf(stderr, "the run did not finish\n");
    return 1;
  }

  Result<Counts> counts = Verify(path, run_id, options);
  const long long bytes = FileBytes(path);
  if (temporary) RemoveStore(path);
  if (!counts.ok()) {
    std::fprintf(stderr, "%s\n", counts.status().ToString().c_str());
    return 1;
  }
  const int64_t* count = &counts->recorded;
  if (stats.completed != *count) {
    std::fprintf(stderr,
                 "the dispatcher completed %lld individuals, the store holds "
                 "%lld\n",
                 static_cast<long long>(stats.completed),
                 static_cast<long long>(*count));
    return 1;
  }
  const double rate = static_cast<double>(*count) / seconds;
  std::printf(
      "  %lld individuals (%lld dispatches) in %.3f s; master CPU %.0f%% "
      "(%.1f us per individual), workers' CPU %.0f%%; store %.1f MB (%.0f "
      "bytes per individual)\n",
      static_cast<long long>(*count), static_cast<long long>(stats.dispatched),
      seconds, 100 * master_cpu / seconds,
      1e6 * master_cpu / static_cast<double>(*count),
      100 * workers_cpu / seconds, 1e-6 * bytes,
      static_cast<double>(bytes) / static_cast<double>(*count));
  if (counts->made > counts->recorded) {
    std::printf(
        "  (%lld initial candidates not chosen were still on their way at the "
        "end; not counted)\n",
        static_cast<long long>(counts->made - counts->recorded));
  }
  if (ends.size() >= 2) {
    const double later =
        (ends.back() - ends.front()) / static_cast<double>(ends.size() - 1);
    std::printf(
        "  initial population (%d of the first candidates) %.3f s; then "
        "%.3f s per generation (%.0f offspring/s)\n",
        options.population, ends.front(), later,
        static_cast<double>(options.population - EvolutionParams{}.elite) /
            later);
  }
  std::printf(
      "  verified: every individual in the store, evaluated, with its "
      "fitness, worker and time; offspring with parents; generations "
      "complete and ranked\n");
  std::printf(
      "MASTER: %.0f individuals/s made, committed, dispatched and recorded "
      "(target >= 50000): %s\n",
      rate, rate >= 50000 ? "met" : "NOT met");
  return 0;
}

}  // namespace
}  // namespace animat

int main(int argc, char** argv) {
  animat::Options options;
  CLI::App app{
      "animat-master-bench: the master's run loop, dispatcher and lineage "
      "store with null-evaluation workers"};
  app.add_option("--population", options.population,
                 "Individuals per generation")
      ->check(CLI::Range(4, 10000000))
      ->capture_default_str();
  app.add_option("--generations", options.generations, "Generations")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--seed", options.seed, "The run's seed")
      ->capture_default_str();
  app.add_option("--workers", options.workers, "Null-evaluation workers")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--threads", options.threads,
                 "Threads each null worker claims (sets its credit)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  app.add_option("--db", options.db,
                 "The lineage store to write (a new file, kept); default: a "
                 "temporary file in $TMPDIR or /tmp, removed afterwards");
  app.add_option("--endpoint", options.endpoint,
                 "Where the dispatcher binds: tcp://HOST:PORT or ipc://PATH "
                 "(on this machine)")
      ->capture_default_str()
      ->check([](const std::string& endpoint) {
        return animat::protocol::CheckEndpoint(
                   endpoint, animat::protocol::EndpointUse::kBind)
            .message();
      });
  app.add_option("--heartbeat-ms", options.heartbeat_ms,
                 "Heartbeat interval (longer under a profiler)")
      ->check(CLI::Range(10, 600000))
      ->capture_default_str();
  app.add_option("--worker", options.worker, "The animat-worker binary")
      ->capture_default_str();
  app.add_option("--worker-log", options.worker_log,
                 "Where the workers' log lines go")
      ->capture_default_str();
  app.add_flag("--verbose", options.verbose,
               "The master's and dispatcher's log on stderr");
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-master-bench")) {
    return *code;
  }
  if (const animat::Status status =
          animat::bench::CheckWorkerFiles(options.worker, options.worker_log);
      !status.ok()) {
    std::fprintf(stderr, "animat-master-bench: %s\n", status.message().c_str());
    return 1;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // Each figure as it comes.
  google::protobuf::SetLogHandler(nullptr);
  return animat::Bench(options);
}
