// One master serving many runs against one master per run (docs/scale.md,
// "Many runs, one master"):
//
//   build/bin/animat-campaign-bench [--runs R] [--population P]
//       [--generations G] [--slots S] [--delay-ms D] [--delay-cv CV]
//       [--arrangement both|campaign|separate] [--repeats N]
//       [--worker PATH] [--worker-log PATH] [--verbose]
//
// (defaults: 8 runs of 300 over 5 generations, 320 slots, delays of 20 ms
// with a coefficient of variation of 0.5, both arrangements once).
//
// The same R runs (seeds 1 to R, scored by bench/null_scoring.h as in
// animat-master-bench, each into its own store on disk) are served in two
// arrangements, one after the other in one window (alternating when
// repeated):
// - campaign: one Dispatcher; the runs share it through the lanes of
//   master/campaign/shared_evaluators.h, each run on its own thread and
//   this thread pumping, as `animat campaign` serves them;
// - separate: R Dispatchers, one per run, each on its own thread and port
//   with its own share of the workers, as R `animat-master`s would be.
// Either way the S slots are R null-evaluation worker processes of S / R
// threads, whose items each take their genome's delay (animat-worker
// --null-delay-ms, --null-delay-cv): the same genomes take the same time
// in both arrangements, so both have the same work to do.
//
// Per arrangement: the wall time from the runs' start to the last run's
// end; the evaluation time (the workers' wall times of every result,
// summed); the idle fraction of the slots, 1 - evaluation time / (S x wall
// time); results recorded per second; the master's CPU per result (this
// process's: every master's, in the separate arrangement; the workers are
// other processes), split into the runs' threads (making, committing,
// recording; in the separate arrangement also each run's dispatcher) and
// this thread's (the campaign's pump and its one dispatcher: the part that
// does not spread over cores); the workers' CPU per result (the worker
// processes', reaped); and how long each individual waited beyond its
// own evaluation, from its run's submission to its completion reaching the run
// (median and 99th percentile: queueing behind other work, dispatch and
// transport).
//
// Before a figure is printed, each store is reopened and checked: the run
// finished with all its generations complete; with both arrangements,
// every run's scores (id and fitness of every individual) are the same in
// both. A failed check exits 1.
//
// Exit 0 when every arrangement finished and checked; 1 when one did not,
// or when --worker or --worker-log cannot serve; 2 on a usage error.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <unordered_map>
#include <utility>
#include <vector>
#include <zmq.hpp>

#include <google/protobuf/stubs/logging.h>
#include <CLI/CLI.hpp>

#include "bench/null_scoring.h"
#include "bench/timing.h"
#include "bench/worker_processes.h"
#include "common/command_line/command_line.h"
#include "master/campaign/shared_evaluators.h"
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
  int runs = 8;
  int population = 300;
  int generations = 5;
  int slots = 320;
  double delay_ms = 20;
  double delay_cv = 0.5;
  std::string arrangement = "both";
  int repeats = 1;
  std::string worker = ANIMAT_WORKER_PATH;
  std::string worker_log = "/dev/null";
  bool verbose = false;
};

// Around one run's evaluation service: the evaluation time of its results
// and how long each individual waited beyond its evaluation. Not
// thread-safe: the run's thread uses it.
class Measured final : public EvaluationService {
 public:
  explicit Measured(EvaluationService* inner) : inner_(inner) {}

  void Submit(uint64_t individual, const v1::Genome& genome) override {
    submitted_.emplace(individual, Clock::now());
    inner_->Submit(individual, genome);
  }
  void Submit(uint64_t individual,
              const protocol::SerializedGenome& genome) override {
    submitted_.emplace(individual, Clock::now());
    inner_->Submit(individual, genome);
  }
  std::vector<Completion> Poll(int timeout_ms) override {
    std::vector<Completion> done = inner_->Poll(timeout_ms);
    const Clock::time_point now = Clock::now();
    for (const Completion& c : done) {
      evaluation_seconds_ += c.wall_seconds;
      const auto it = submitted_.find(c.individual);
      if (it == submitted_.end()) continue;
      const std::chrono::duration<double> since = now - it->second;
      waits_.push_back(since.count() - c.wall_seconds);
      submitted_.erase(it);
    }
    return done;
  }
  void Acknowledge(const std::vector<uint64_t>& individuals) override {
    inner_->Acknowledge(individuals);
  }
  size_t pending() const override { return inner_->pending(); }
  const animat::Clock& clock() const override { return inner_->clock(); }

  double evaluation_seconds() const { return evaluation_seconds_; }
  const std::vector<double>& waits() const { return waits_; }

 private:
  EvaluationService* inner_;
  // Submission times of the individuals not yet completed (looked up by
  // id, never iterated).
  std::unordered_map<uint64_t, Clock::time_point> submitted_;
  double evaluation_seconds_ = 0;
  std::vector<double> waits_;
};

// One run of either arrangement, from its store to its scores.
struct BenchRun {
  uint64_t seed = 0;
  std::string path;
  std::unique_ptr<lineage::Store> store;
  std::unique_ptr<EvolutionRun> run;
  int64_t run_id = 0;
  std::unique_ptr<Measured> measured;
  std::unique_ptr<bench::NullScoring> scoring;
  Status status;
  std::atomic<bool> done{false};
  double ended = 0;  // Seconds from the start.
  double cpu = 0;    // CPU seconds of the run's thread.
};

// What an arrangement measured.
struct Outcome {
  std::string name;
  double wall = 0;
  double first_end = 0;
  double evaluation_seconds = 0;
  double master_cpu = 0;   // This process's CPU seconds.
  double serve_cpu = 0;    // This thread's: the campaign's dispatcher.
  double runs_cpu = 0;     // The runs' threads'.
  double workers_cpu = 0;  // The worker processes'.
  int64_t recorded = 0;
  std::vector<double> waits;
  std::vector<std::vector<lineage::Score>> scores;  // Per run.
  double idle = 0;                                  // Fraction of slot time.
};

DispatcherOptions DispatcherOptionsFor(const Options& o) {
  DispatcherOptions d;
  d.endpoint = "tcp://127.0.0.1:*";
  d.accept_null_workers = true;
  d.acknowledge_on_receipt = false;  // As animat-master.
  d.log = o.verbose ? Prefixed("dispatcher", StderrSink)
                    : LogSink([](std::string_view) {});
  return d;
}

// Makes each run's store in `dir` (run1.db, run2.db, ...) and starts its
// run.
Status OpenRuns(const Options& o, const std::string& dir,
                std::vector<std::unique_ptr<BenchRun>>* runs) {
  const LogSink log = o.verbose ? Prefixed("master", StderrSink)
                                : LogSink([](std::string_view) {});
  for (int i = 0; i < o.runs; ++i) {
    auto r = std::make_unique<BenchRun>();
    r->seed = static_cast<uint64_t>(i + 1);
    r->path = dir + "/run" + std::to_string(r->seed) + ".db";
    Result<std::unique_ptr<lineage::Store>> store =
        lineage::Store::Open(r->path);
    if (!store.ok()) return store.status();
    r->store = std::move(store).value();
    RunSettings settings;
    settings.evolution.seed = r->seed;
    settings.evolution.population = o.population;
    settings.evolution.generations = o.generations;
    Result<std::unique_ptr<EvolutionRun>> run =
        EvolutionRun::Start(r->store.get(), settings, log);
    if (!run.ok()) return run.status();
    r->run = std::move(run).value();
    r->run_id = r->run->run_id();
    runs->push_back(std::move(r));
  }
  return Status::Ok();
}

// Each run on a thread of its own through its service (set up by the
// caller); `serve` is called on this thread until every run has returned.
template <typename Serve>
void RunAll(std::vector<std::unique_ptr<BenchRun>>& runs, Serve serve) {
  std::atomic<bool> stop{false};
  const Clock::time_point start = Clock::now();
  std::vector<std::thread> threads;
  for (auto& run : runs) {
    BenchRun* r = run.get();
    threads.emplace_back([r, &stop, start] {
      const double cpu = CpuSeconds(RUSAGE_THREAD);
      r->status = r->run->Run(r->scoring.get(), stop);
      r->cpu = CpuSeconds(RUSAGE_THREAD) - cpu;
      r->ended = SecondsSince(start);
      r->done = true;
    });
  }
  for (bool all_done = false; !all_done;) {
    serve(stop);
    all_done = true;
    for (const auto& r : runs) {
      all_done = all_done && r->done;
      if (r->done && !r->status.ok()) stop = true;
    }
  }
  for (std::thread& t : threads) t.join();
}

// Closes each run's store, reopens it and checks that it holds the whole
// run; fills the outcome's counts, scores and per-run figures.
Status Collect(const Options& o, std::vector<std::unique_ptr<BenchRun>>& runs,
               Outcome* out) {
  out->first_end = runs.front()->ended;
  for (auto& r : runs) {
    if (!r->status.ok()) return r->status.WithPrefix("run " + r->path);
    out->wall = std::max(out->wall, r->ended);
    out->first_end = std::min(out->first_end, r->ended);
    out->evaluation_seconds += r->measured->evaluation_seconds();
    out->runs_cpu += r->cpu;
    const std::vector<double>& waits = r->measured->waits();
    out->waits.insert(out->waits.end(), waits.begin(), waits.end());
    r->run.reset();
    r->store.reset();
    Result<std::unique_ptr<lineage::Store>> store =
        lineage::Store::OpenForQueries(r->path);
    if (!store.ok()) return store.status();
    Result<lineage::RunCounts> n = lineage::CountRun(**store, r->run_id);
    if (!n.ok()) return n.status();
    if (!n->finished || n->complete_generations != o.generations ||
        n->needed_unevaluated != 0) {
      return Status::Internal(r->path + ": the run did not finish whole (" +
                              std::to_string(n->complete_generations) + " of " +
                              std::to_string(o.generations) + " generations)");
    }
    out->recorded += n->evaluated;
    Result<std::vector<lineage::Score>> scores =
        lineage::Scores(**store, r->run_id);
    if (!scores.ok()) return scores.status();
    out->scores.push_back(std::move(scores).value());
  }
  out->idle = 1 - out->evaluation_seconds / (o.slots * out->wall);
  return Status::Ok();
}

// The campaign arrangement: one dispatcher, the runs through its lanes.
Status ServeCampaign(const Options& o, const std::string& dir, Outcome* out) {
  std::vector<std::unique_ptr<BenchRun>> runs;
  if (Status s = OpenRuns(o, dir, &runs); !s.ok()) return s;
  const v1::Config config = ConfigToProto(runs.front()->run->model_config());
  zmq::context_t context(1);
  Result<std::unique_ptr<Dispatcher>> dispatcher =
      Dispatcher::Create(&context, DispatcherOptionsFor(o), config);
  if (!dispatcher.ok()) return dispatcher.status();
  Result<size_t> index = (*dispatcher)->AddConfig(config);
  if (!index.ok()) return index.status();
  bench::WorkerProcesses workers(o.worker, o.worker_log, dispatcher->get());
  if (!workers.Spawn(o.runs, o.slots / o.runs, true, o.delay_ms, o.delay_cv)) {
    return Status::Internal("the workers did not start");
  }
  {
    SharedEvaluators shared(dispatcher->get());
    for (auto& r : runs) {
      r->measured = std::make_unique<Measured>(shared.AddLane(*index));
      r->scoring =
          std::make_unique<bench::NullScoring>(r->measured.get(), r->seed);
    }
    const double cpu = CpuSeconds(RUSAGE_SELF);
    const double serve_cpu = CpuSeconds(RUSAGE_THREAD);
    RunAll(runs, [&](std::atomic<bool>& stop) {
      shared.Pump(10);
      for (size_t i = 0; i < runs.size(); ++i) {
        if (!shared.error(i).ok()) {
          runs[i]->status = shared.error(i);
          stop = true;
        }
      }
    });
    out->master_cpu = CpuSeconds(RUSAGE_SELF) - cpu;
    out->serve_cpu = CpuSeconds(RUSAGE_THREAD) - serve_cpu;
  }
  workers.Stop();
  return Collect(o, runs, out);
}

// The separate arrangement: a dispatcher and a share of the workers per
// run.
Status ServeSeparately(const Options& o, const std::string& dir, Outcome* out) {
  std::vector<std::unique_ptr<BenchRun>> runs;
  if (Status s = OpenRuns(o, dir, &runs); !s.ok()) return s;
  zmq::context_t context(1);
  std::vector<std::unique_ptr<Dispatcher>> dispatchers;
  std::vector<std::unique_ptr<bench::WorkerProcesses>> workers;
  for (auto& r : runs) {
    Result<std::unique_ptr<Dispatcher>> dispatcher =
        Dispatcher::Create(&context, DispatcherOptionsFor(o),
                           ConfigToProto(r->run->model_config()));
    if (!dispatcher.ok()) return dispatcher.status();
    dispatchers.push_back(std::move(dispatcher).value());
    workers.push_back(std::make_unique<bench::WorkerProcesses>(
        o.worker, o.worker_log, dispatchers.back().get()));
    if (!workers.back()->Spawn(1, o.slots / o.runs, true, o.delay_ms,
                               o.delay_cv)) {
      return Status::Internal("the workers did not start");
    }
    r->measured = std::make_unique<Measured>(dispatchers.back().get());
    r->scoring =
        std::make_unique<bench::NullScoring>(r->measured.get(), r->seed);
  }
  const double cpu = CpuSeconds(RUSAGE_SELF);
  // Each run serves its own dispatcher; this thread only waits.
  RunAll(runs, [](std::atomic<bool>&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  });
  out->master_cpu = CpuSeconds(RUSAGE_SELF) - cpu;
  for (auto& w : workers) w->Stop();
  return Collect(o, runs, out);
}

// Whether two arrangements' runs scored every individual alike.
bool SameScores(const Outcome& a, const Outcome& b) {
  if (a.scores.size() != b.scores.size()) return false;
  for (size_t run = 0; run < a.scores.size(); ++run) {
    const std::vector<lineage::Score>& x = a.scores[run];
    const std::vector<lineage::Score>& y = b.scores[run];
    if (x.size() != y.size()) return false;
    for (size_t i = 0; i < x.size(); ++i) {
      if (x[i].id != y[i].id || x[i].evaluated != y[i].evaluated ||
          x[i].fitness != y[i].fitness) {
        return false;
      }
    }
  }
  return true;
}

double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t at =
      static_cast<size_t>(p * static_cast<double>(values.size() - 1));
  return values[at];
}

void Print(const Options& o, const Outcome& out) {
  std::printf(
      "  %-8s wall %.3f s (first run ended at %.3f s); evaluation %.1f of "
      "%.1f slot-s: idle %.1f%%; %lld recorded, %.0f/s; master CPU %.1f us "
      "per result (%.1f on the runs' threads, %.1f on the pump's), workers' "
      "%.1f us; waited beyond evaluation: median %.1f ms, p99 %.1f ms\n",
      out.name.c_str(), out.wall, out.first_end, out.evaluation_seconds,
      o.slots * out.wall, 100 * out.idle, static_cast<long long>(out.recorded),
      static_cast<double>(out.recorded) / out.wall,
      1e6 * out.master_cpu / static_cast<double>(out.recorded),
      1e6 * out.runs_cpu / static_cast<double>(out.recorded),
      1e6 * out.serve_cpu / static_cast<double>(out.recorded),
      1e6 * out.workers_cpu / static_cast<double>(out.recorded),
      1e3 * Percentile(out.waits, 0.5), 1e3 * Percentile(out.waits, 0.99));
}

// Serves arrangement `name` in a fresh folder under `root`.
Result<Outcome> Serve(const Options& o, const std::string& root,
                      const std::string& name) {
  const std::string dir = root + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  Outcome out;
  out.name = name;
  const double workers_cpu = CpuSeconds(RUSAGE_CHILDREN);
  const Status status = name == "campaign" ? ServeCampaign(o, dir, &out)
                                           : ServeSeparately(o, dir, &out);
  // The workers have been stopped and reaped.
  out.workers_cpu = CpuSeconds(RUSAGE_CHILDREN) - workers_cpu;
  std::filesystem::remove_all(dir);
  if (!status.ok()) return status.WithPrefix(name);
  Print(o, out);
  return out;
}

int Bench(const Options& o) {
  std::printf(
      "campaign bench: %d runs of population %d over %d generations; %d "
      "slots (%d null-evaluation workers of %d threads); delays %.3g ms "
      "mean, cv %.3g\n",
      o.runs, o.population, o.generations, o.slots, o.runs, o.slots / o.runs,
      o.delay_ms, o.delay_cv);
  const char* tmp = std::getenv("TMPDIR");
  const std::string root =
      std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") +
      "/animat-campaign-bench-" + std::to_string(getpid());
  std::vector<std::string> order;
  if (o.arrangement != "separate") order.push_back("campaign");
  if (o.arrangement != "campaign") order.push_back("separate");
  std::vector<std::vector<Outcome>> outcomes(order.size());
  for (int repeat = 0; repeat < o.repeats; ++repeat) {
    for (size_t k = 0; k < order.size(); ++k) {
      // Alternate which goes first, so neither always follows the other.
      const size_t which = repeat % 2 == 0 ? k : order.size() - 1 - k;
      Result<Outcome> out = Serve(o, root, order[which]);
      if (!out.ok()) {
        std::filesystem::remove_all(root);
        std::fprintf(stderr, "%s\n", out.status().ToString().c_str());
        return 1;
      }
      outcomes[which].push_back(std::move(out).value());
    }
  }
  std::filesystem::remove_all(root);
  if (order.size() == 2) {
    for (size_t i = 0; i < outcomes[0].size(); ++i) {
      for (size_t j = 0; j < outcomes[1].size(); ++j) {
        if (!SameScores(outcomes[0][i], outcomes[1][j])) {
          std::fprintf(stderr, "a run's scores differ between arrangements\n");
          return 1;
        }
      }
    }
  }
  std::printf(
      "  checked: every run finished with its %d generations complete%s\n",
      o.generations,
      order.size() == 2 ? "; every run's scores the same in both arrangements"
                        : "");
  std::printf("IDLE:");
  for (size_t k = 0; k < order.size(); ++k) {
    std::vector<double> idle;
    for (const Outcome& out : outcomes[k]) idle.push_back(out.idle);
    std::printf(" %s %.1f%%", order[k].c_str(), 100 * Percentile(idle, 0.5));
  }
  std::printf(" (median of %d)\n", o.repeats);
  return 0;
}

}  // namespace
}  // namespace animat

int main(int argc, char** argv) {
  animat::Options o;
  CLI::App app{
      "animat-campaign-bench: one master serving many runs against one "
      "master per run, with null-evaluation workers that take time"};
  app.add_option("--runs", o.runs, "Runs (seeds 1 to R)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  app.add_option("--population", o.population, "Individuals per generation")
      ->check(CLI::Range(4, 1000000))
      ->capture_default_str();
  app.add_option("--generations", o.generations, "Generations per run")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--slots", o.slots,
                 "Worker threads in all, a multiple of --runs")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  app.add_option("--delay-ms", o.delay_ms, "Mean evaluation time (ms; 0: none)")
      ->check(CLI::Range(0.0, 60000.0))
      ->capture_default_str();
  app.add_option("--delay-cv", o.delay_cv,
                 "The evaluation times' coefficient of variation")
      ->check(CLI::Range(0.0, 10.0))
      ->capture_default_str();
  app.add_option("--arrangement", o.arrangement,
                 "both, campaign (one master) or separate (one per run)")
      ->check(CLI::IsMember({"both", "campaign", "separate"}))
      ->capture_default_str();
  app.add_option("--repeats", o.repeats, "Times each arrangement is served")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--worker", o.worker, "The animat-worker binary")
      ->capture_default_str();
  app.add_option("--worker-log", o.worker_log,
                 "Where the workers' log lines go")
      ->capture_default_str();
  app.add_flag("--verbose", o.verbose,
               "The masters' and dispatchers' log on stderr");
  if (const std::optional<int> code =
          animat::ParseCommandLine(app, argc, argv, "animat-campaign-bench")) {
    return *code;
  }
  if (o.slots % o.runs != 0 || o.slots / o.runs > 4096) {
    std::fprintf(stderr,
                 "animat-campaign-bench: --slots: %d is not a multiple of "
                 "--runs (%d) of at most 4096 per run\n",
                 o.slots, o.runs);
    return 2;
  }
  if (const animat::Status status =
          animat::bench::CheckWorkerFiles(o.worker, o.worker_log);
      !status.ok()) {
    std::fprintf(stderr, "animat-campaign-bench: %s\n",
                 status.message().c_str());
    return 1;
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // Each figure as it comes.
  google::protobuf::SetLogHandler(nullptr);
  return animat::Bench(o);
}
