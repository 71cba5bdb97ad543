// The master-worker dispatch, measured end to end with real worker
// processes on loopback (docs/protocol.md, "Speed"):
//
//   build/bin/animat-dispatch-bench [--part dispatch|evaluate|both] ...
//
// dispatch: an in-process Dispatcher (accepting null-evaluation workers)
//   and --workers `animat-worker --null-evaluation --threads T` processes;
//   --individuals individuals of a 4-element genome are submitted, then
//   completions per second are timed from the first Poll to the last
//   completion. T only sets the worker's credit (T * kPrefetch): a null
//   worker runs no threads, so T stands for the cores it would feed. Runs
//   once per value of --threads.
// evaluate: real workers evaluate a fixed set of viable genomes
//   (tests/data/genomes), repeated, with the default configuration;
//   evaluations per second with one worker of one thread, one worker of
//   two threads and two workers of one thread, the ratios to the first,
//   and the master's CPU per evaluation (this process: the dispatcher's
//   thread and ZeroMQ's I/O thread).
//
// The workers are this build's animat-worker (ANIMAT_WORKER_PATH), started
// with posix_spawn (bench/worker_processes.h); their log goes to
// --worker-log.
//
// Exit 0 when every part ran; 1 when a file named (--worker, --worker-log,
// --genomes) cannot serve, said before any part runs, or when a part
// fails; 2 on a usage error, a malformed value included.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <zmq.hpp>

#include <CLI/CLI.hpp>

#include "bench/timing.h"
#include "bench/worker_processes.h"
#include "common/command_line/command_line.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/protocol/protocol.h"
#include "master/dispatch/dispatcher.h"

namespace animat {
namespace {

using bench::Clock;
using bench::CpuSeconds;
using bench::SecondsSince;

struct Options {
  std::string part = "both";
  std::string worker = ANIMAT_WORKER_PATH;
  std::string worker_log = "/dev/null";
  // dispatch
  int64_t individuals = 200000;
  int null_workers = 2;
  std::vector<int> threads = {8, 64, 256};
  // evaluate
  // Bodies with chambers (all evaluate ok under the default
  // configuration): two random genomes and an evolved swimmer.
  std::vector<std::string> genomes = {
      ANIMAT_GENOMES_DIR "/seed-1198.json", ANIMAT_GENOMES_DIR "/seed-139.json",
      ANIMAT_BENCH_DATA_DIR "/accuracy/evolved-dn1-g039-47646.json"};
  int evaluations = 300;
  bool verbose = false;
};

// Worker processes of this run's options.
class Workers : public bench::WorkerProcesses {
 public:
  Workers(const Options& options, Dispatcher* dispatcher)
      : WorkerProcesses(options.worker, options.worker_log, dispatcher) {}
};

std::unique_ptr<Dispatcher> MakeDispatcher(zmq::context_t* context,
                                           const Options& options,
                                           bool accept_null_workers) {
  DispatcherOptions dispatcher_options;
  dispatcher_options.endpoint = "tcp://127.0.0.1:*";
  dispatcher_options.accept_null_workers = accept_null_workers;
  if (!options.verbose) dispatcher_options.log = [](std::string_view) {};
  Result<std::unique_ptr<Dispatcher>> dispatcher = Dispatcher::Create(
      context, dispatcher_options, ConfigToProto(ModelConfig{}));
  if (!dispatcher.ok()) {
    std::fprintf(stderr, "%s\n", dispatcher.status().ToString().c_str());
    return nullptr;
  }
  return std::move(dispatcher).value();
}

// The four-element genome of docs/formats.md.
v1::Genome SmallGenome() {
  v1::Genome genome;
  auto add = [&](v1::Element::Type type, double x, double y,
                 v1::Element::Channel channel) {
    v1::Element* e = genome.add_elements();
    e->set_type(type);
    e->set_sign(1);
    e->set_x(x);
    e->set_y(y);
    e->set_channel(channel);
  };
  add(v1::Element::S_IN, 2.0, 2.0, v1::Element::UNIFORM);
  add(v1::Element::P, 2.5, 2.0, v1::Element::CHANNEL_NONE);
  add(v1::Element::G_INTERNAL, 6.0, 1.0, v1::Element::CHANNEL_NONE);
  add(v1::Element::S_OUT, 6.5, 1.0, v1::Element::DIVIDE);
  return genome;
}

struct Run {
  int64_t completed = 0;
  double seconds = 0;     // First Poll to last completion.
  double master_cpu = 0;  // Seconds of this process's CPU in that time.
  int64_t polls = 0;      // Poll calls that returned completions.
  double submit_seconds = 0;
};

// Submits `genomes` (cycled) as individuals 1..count and serves until all
// complete. Returns false on a timeout.
bool Serve(Dispatcher* dispatcher, const std::vector<v1::Genome>& genomes,
           int64_t count, Run* run,
           std::map<uint64_t, Completion>* completions) {
  const Clock::time_point submit = Clock::now();
  for (int64_t i = 0; i < count; ++i) {
    dispatcher->Submit(static_cast<uint64_t>(i + 1),
                       genomes[static_cast<size_t>(i) % genomes.size()]);
  }
  run->submit_seconds = SecondsSince(submit);
  const double cpu = CpuSeconds(RUSAGE_SELF);
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  while (run->completed < count) {
    std::vector<Completion> done = dispatcher->Poll(100);
    if (!done.empty()) {
      last = Clock::now();
      ++run->polls;
    }
    run->completed += static_cast<int64_t>(done.size());
    if (completions != nullptr) {
      for (Completion& c : done) (*completions)[c.individual] = std::move(c);
    }
    if (SecondsSince(last) > 60) {
      std::fprintf(stderr, "no completion for 60 s (%lld of %lld done)\n",
                   static_cast<long long>(run->completed),
                   static_cast<long long>(count));
      return false;
    }
  }
  run->seconds = std::chrono::duration<double>(last - start).count();
  run->master_cpu = CpuSeconds(RUSAGE_SELF) - cpu;
  return true;
}

bool DispatchPart(const Options& options) {
  std::printf(
      "dispatch throughput: %lld individuals, %d null-evaluation workers, "
      "loopback TCP\n",
      static_cast<long long>(options.individuals), options.null_workers);
  {
    // What the master spends on its own: Submit per individual, and one
    // Poll(0) with no worker and everything pending (its housekeeping
    // looks at every pending individual).
    zmq::context_t context(1);
    std::unique_ptr<Dispatcher> dispatcher =
        MakeDispatcher(&context, options, /*accept_null_workers=*/true);
    if (!dispatcher) return false;
    const v1::Genome genome = SmallGenome();
    const Clock::time_point submit = Clock::now();
    for (int64_t i = 0; i < options.individuals; ++i) {
      dispatcher->Submit(static_cast<uint64_t>(i + 1), genome);
    }
    const double submit_seconds = SecondsSince(submit);
    constexpr int kPolls = 20;
    const Clock::time_point poll = Clock::now();
    for (int i = 0; i < kPolls; ++i) dispatcher->Poll(0);
    std::printf(
        "  master alone: Submit %.2f us per individual; an idle Poll(0) "
        "with %lld pending %.3f ms\n",
        1e6 * submit_seconds / static_cast<double>(options.individuals),
        static_cast<long long>(options.individuals),
        1e3 * SecondsSince(poll) / kPolls);
  }
  std::printf("  %-8s %-8s %14s %12s %12s %14s\n", "threads", "credit",
              "completions/s", "seconds", "master cpu", "per poll");
  double best = 0;
  int best_credit = 0;
  for (int threads : options.threads) {
    zmq::context_t context(1);
    std::unique_ptr<Dispatcher> dispatcher =
        MakeDispatcher(&context, options, /*accept_null_workers=*/true);
    if (!dispatcher) return false;
    Workers workers(options, dispatcher.get());
    if (!workers.Spawn(options.null_workers, threads, true)) return false;
    Run run;
    if (!Serve(dispatcher.get(), {SmallGenome()}, options.individuals, &run,
               nullptr)) {
      return false;
    }
    workers.Stop();
    const double rate = static_cast<double>(run.completed) / run.seconds;
    const int credit = options.null_workers * threads * protocol::kPrefetch;
    if (rate > best) {
      best = rate;
      best_credit = credit;
    }
    std::printf("  %-8d %-8d %14.0f %12.3f %11.0f%% %14.1f\n", threads, credit,
                rate, run.seconds, 100 * run.master_cpu / run.seconds,
                static_cast<double>(run.completed) /
                    static_cast<double>(std::max<int64_t>(1, run.polls)));
    if (options.verbose) {
      std::printf("    submit %.3f s; dispatched %lld, requeued %lld\n",
                  run.submit_seconds,
                  static_cast<long long>(dispatcher->stats().dispatched),
                  static_cast<long long>(dispatcher->stats().requeued));
    }
  }
  std::printf(
      "  credit: the evaluations the workers may hold at once; per poll: "
      "completions per Poll call that returned some\n");
  std::printf(
      "DISPATCH: %.0f completions/s at best (credit %d; target >= 100000): "
      "%s\n",
      best, best_credit, best >= 100000 ? "met" : "NOT met");
  return true;
}

// The genomes of --genomes, each read and checked, or why one is not a
// genome (naming the flag and the file).
Result<std::vector<v1::Genome>> ReadGenomes(
    const std::vector<std::string>& paths) {
  std::vector<v1::Genome> genomes;
  for (const std::string& path : paths) {
    v1::Genome genome;
    // A read error names the file; a genome's does not.
    if (Status status = ReadProtoFile(path, &genome); !status.ok()) {
      return status.WithPrefix("--genomes");
    }
    if (Status status = GenomeFromProto(genome).status(); !status.ok()) {
      return status.WithPrefix("--genomes " + path);
    }
    genomes.push_back(genome);
  }
  return genomes;
}

bool EvaluatePart(const Options& options,
                  const std::vector<v1::Genome>& genomes) {
  std::printf(
      "evaluation throughput: %d evaluations of %zu genomes (repeated), "
      "default configuration\n",
      options.evaluations, genomes.size());
  // One worker with one thread, one worker with two threads (its
  // evaluation pool), two workers with one thread each.
  struct Setup {
    int workers, threads;
  };
  constexpr Setup kSetups[] = {{1, 1}, {1, 2}, {2, 1}};
  double rate[3] = {0, 0, 0};
  std::map<uint64_t, Completion> first;
  for (int s = 0; s < 3; ++s) {
    const Setup setup = kSetups[s];
    zmq::context_t context(1);
    std::unique_ptr<Dispatcher> dispatcher =
        MakeDispatcher(&context, options, /*accept_null_workers=*/false);
    if (!dispatcher) return false;
    Workers workers(options, dispatcher.get());
    if (!workers.Spawn(setup.workers, setup.threads, false)) return false;
    Run run;
    std::map<uint64_t, Completion> results;
    if (!Serve(dispatcher.get(), genomes, options.evaluations, &run,
               &results)) {
      return false;
    }
    workers.Stop();
    int ok = 0;
    // Per worker: evaluations, and seconds spent evaluating them.
    std::map<std::string, std::pair<int, double>> busy;
    for (const auto& [id, c] : results) {
      ok += c.result.status() == v1::EvaluationResult::OK;
      busy[c.worker].first += 1;
      busy[c.worker].second += c.wall_seconds;
    }
    // The same genome gives the same bits on any worker and thread.
    int differ = 0;
    if (s == 0) {
      first = results;
    } else {
      for (const auto& [id, c] : results) {
        differ += c.result.SerializeAsString() !=
                  first[id].result.SerializeAsString();
      }
    }
    rate[s] = static_cast<double>(run.completed) / run.seconds;
    std::printf(
        "  %d worker%s x %d thread%s: %7.2f evaluations/s (%.2f s; %d of "
        "%lld OK%s); master CPU %.1f us per evaluation (%.2f%% of a core)\n",
        setup.workers, setup.workers == 1 ? " " : "s", setup.threads,
        setup.threads == 1 ? " " : "s", rate[s], run.seconds, ok,
        static_cast<long long>(run.completed),
        s > 0 ? (differ == 0 ? "; bits as with 1 x 1"
                             : "; RESULTS DIFFER from 1 x 1")
              : "",
        1e6 * run.master_cpu / static_cast<double>(run.completed),
        100 * run.master_cpu / run.seconds);
    for (const auto& [name, load] : busy) {
      std::printf(
          "      %-24s %4d evaluations, evaluating %3.0f%% of the time "
          "(summed over its threads)\n",
          name.c_str(), load.first, 100 * load.second / run.seconds);
    }
  }
  const double threads = rate[1] / rate[0];
  const double workers = rate[2] / rate[0];
  std::printf(
      "SCALING: %.2fx from 1 to 2 threads in one worker (target >= "
      "1.9): %s\n",
      threads, threads >= 1.9 ? "met" : "NOT met");
  std::printf("SCALING: %.2fx from 1 to 2 workers of 1 thread\n", workers);
  return true;
}

}  // namespace
}  // namespace animat

int main(int argc, char** argv) {
  animat::Options options;
  CLI::App app{"animat-dispatch-bench: master-worker dispatch on loopback"};
  app.add_option("--part", options.part, "dispatch, evaluate or both")
      ->check(CLI::IsMember({"dispatch", "evaluate", "both"}))
      ->capture_default_str();
  app.add_option("--worker", options.worker, "The animat-worker binary")
      ->capture_default_str();
  app.add_option("--worker-log", options.worker_log,
                 "Where the workers' log lines go")
      ->capture_default_str();
  app.add_option("--individuals", options.individuals,
                 "Individuals submitted (dispatch)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--workers", options.null_workers,
                 "Null-evaluation workers (dispatch)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--threads", options.threads,
                 "Threads each null worker claims, one run per value "
                 "(dispatch)")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  app.add_option("--genomes", options.genomes, "Genome files (evaluate)")
      ->capture_default_str();
  app.add_option("--evaluations", options.evaluations,
                 "Evaluations per run (evaluate)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--verbose", options.verbose,
               "The dispatcher's log on stderr, and more figures");
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-dispatch-bench")) {
    return *code;
  }
  // Every file named is checked before any part runs.
  if (const animat::Status status =
          animat::bench::CheckWorkerFiles(options.worker, options.worker_log);
      !status.ok()) {
    std::fprintf(stderr, "animat-dispatch-bench: %s\n",
                 status.message().c_str());
    return 1;
  }
  const animat::Result<std::vector<animat::v1::Genome>> genomes =
      animat::ReadGenomes(options.genomes);
  if (!genomes.ok()) {
    std::fprintf(stderr, "animat-dispatch-bench: %s\n",
                 genomes.status().message().c_str());
    return 1;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // Each figure as it comes.

  bool ok = true;
  if (options.part != "evaluate") ok = animat::DispatchPart(options) && ok;
  if (options.part != "dispatch") {
    ok = animat::EvaluatePart(options, *genomes) && ok;
  }
  return ok ? 0 : 1;
}
