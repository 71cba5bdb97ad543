#include "master/campaign/campaign_session.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>
#include <zmq.hpp>

#include "common/evaluation/model_config.h"
#include "master/campaign/campaign_file.h"
#include "master/campaign/shared_evaluators.h"
#include "master/dispatch/dispatcher.h"
#include "master/lineage/store.h"
#include "master/run/child_isolation.h"
#include "master/run/local_workers.h"
#include "master/run/run_plan.h"

namespace animat {
namespace {

// A run of the campaign with work left, from planning to its end.
struct ActiveRun {
  std::string name;
  std::string db_path;
  std::unique_ptr<lineage::Store> store;
  RunPlan plan;
  std::unique_ptr<EvolutionRun> run;
  size_t config = 0;  // The dispatcher's index of its model configuration.
  EvaluationService* lane = nullptr;
  Status status;      // Run's; written by the run's thread before `done`.
  Status lane_error;  // Its lane's (shared_evaluators.h); the pump's thread.
  std::atomic<bool> done{false};
  std::atomic<int> generation{0};  // Generations completed.
};

// What planning the campaign's runs found.
struct CampaignPlan {
  std::vector<std::unique_ptr<ActiveRun>> active;
  int finished = 0;  // Runs with nothing to do.
  int total = 0;
};

// Start or resume `run`'s store as the campaign file says; a finished run
// that the file does not extend is left alone (no store kept open).
Status PlanRun(const CampaignRun& run, const std::string& dir,
               CampaignPlan* plan) {
  auto active = std::make_unique<ActiveRun>();
  active->name = run.name;
  active->db_path = (std::filesystem::path(dir) / (run.name + ".db")).string();
  const std::string where = "run " + run.name + " (" + active->db_path + ")";
  Result<std::unique_ptr<lineage::Store>> store =
      lineage::Store::Open(active->db_path);
  if (!store.ok()) return store.status().WithPrefix(where);
  Result<std::vector<lineage::RunRow>> rows = (*store)->Runs();
  if (!rows.ok()) return rows.status().WithPrefix(where);
  const int generations = run.settings.evolution.generations;
  Result<RunPlan> planned = rows->empty()
                                ? PlanStart(store->get(), run.settings)
                                : PlanResume(store->get(), run.settings,
                                             /*force=*/false, generations);
  if (!planned.ok()) return planned.status().WithPrefix(where);
  // A run that went on while improving (extend_to) may hold more than
  // `generations`; EvolutionRun decides its length again from its bests.
  const int most = EvolutionMaxLength(planned->settings.evolution);
  if (planned->generations_made > most) {
    return Status::InvalidArgument(
        where + ": the store has " + std::to_string(planned->generations_made) +
        " generations, more than the campaign file's " + std::to_string(most));
  }
  if (planned->run_id != 0 && planned->state == "finished" &&
      !planned->update_config) {
    ++plan->finished;
    return Status::Ok();
  }
  active->store = std::move(store).value();
  active->plan = std::move(planned).value();
  active->generation = active->plan.generations_made;
  plan->active.push_back(std::move(active));
  return Status::Ok();
}

Result<CampaignPlan> Plan(const CampaignOptions& o) {
  Result<std::vector<CampaignRun>> runs = ReadCampaignFile(o.campaign_path);
  if (!runs.ok()) return runs.status();
  std::error_code error;
  std::filesystem::create_directories(o.dir, error);
  if (error) {
    return Status::IoError(
        o.dir + ": cannot make the campaign's folder: " + error.message());
  }
  CampaignPlan plan;
  plan.total = static_cast<int>(runs->size());
  for (const CampaignRun& run : *runs) {
    Status status = PlanRun(run, o.dir, &plan);
    if (!status.ok()) return status;
  }
  return plan;
}

std::string Duration(double seconds) {
  const long s = static_cast<long>(seconds);
  char text[32];
  std::snprintf(text, sizeof(text), "%02ld:%02ld:%02ld", s / 3600, s / 60 % 60,
                s % 60);
  return text;
}

// The campaign line: runs finished, evaluations per second since the
// start, generations to go and the time they take at the rate so far.
class CampaignLine {
 public:
  CampaignLine(const CampaignPlan& plan, const Dispatcher& dispatcher,
               double period)
      : plan_(plan),
        dispatcher_(dispatcher),
        period_(period),
        started_(dispatcher.clock().Seconds()),
        last_(started_) {
    for (const auto& run : plan.active) start_generations_ += run->generation;
  }
  void MaybeSay(const LogSink& log) {
    int finished = plan_.finished;
    for (const auto& run : plan_.active) {
      finished += run->done && run->run->finished();
    }
    const double now = dispatcher_.clock().Seconds();
    if (finished == last_finished_ && now - last_ < period_) return;
    last_ = now;
    last_finished_ = finished;
    int made = 0;
    int left = 0;
    for (const auto& run : plan_.active) {
      const EvolutionParams& p = run->plan.settings.evolution;
      const bool over = run->done && run->run->finished();
      // Past `generations` and not over, a run has decided to go on.
      const int length = !over && run->generation >= p.generations
                             ? EvolutionMaxLength(p)
                             : p.generations;
      made += run->generation;
      left += over ? 0 : std::max(0, length - run->generation);
    }
    const double elapsed = now - started_;
    const int since = made - start_generations_;
    std::string line = std::to_string(finished) + " of " +
                       std::to_string(plan_.total) + " runs finished | ";
    char rate[64];
    std::snprintf(rate, sizeof(rate), "%.1f evaluations/s",
                  elapsed > 0 ? dispatcher_.stats().completed / elapsed : 0.0);
    line += rate;
    line += " | " + std::to_string(left) + " generations to go";
    if (since > 0 && left > 0) {
      line += " | ETA " + Duration(elapsed / since * left);
    }
    log(line);
  }

 private:
  const CampaignPlan& plan_;
  const Dispatcher& dispatcher_;
  double period_;
  double started_;
  double last_;
  int last_finished_ = -1;
  int start_generations_ = 0;
};

// Each run on its thread through its lane; this thread pumps until all
// have returned. A signal or a failing run stops them all.
void ServeRuns(const CampaignOptions& o, CampaignPlan* plan,
               Dispatcher* dispatcher, const std::atomic<bool>& signalled) {
  SharedEvaluators shared(dispatcher);
  for (auto& run : plan->active) run->lane = shared.AddLane(run->config);
  std::atomic<bool> stop{false};
  std::vector<std::thread> threads;
  for (auto& run : plan->active) {
    ActiveRun* r = run.get();
    threads.emplace_back([&o, r, &stop] {
      r->status =
          r->run->Run(r->lane, stop, [&o, r](const GenerationReport& g) {
            r->generation = g.generation + 1;  // Made, counting from 0.
            if (o.progress) o.progress(r->name, g);
          });
      r->done = true;
    });
  }
  CampaignLine line(*plan, *dispatcher, o.campaign_line_seconds);
  for (bool all_done = false; !all_done;) {
    shared.Pump(10);
    all_done = true;
    for (size_t i = 0; i < plan->active.size(); ++i) {
      ActiveRun& r = *plan->active[i];
      all_done = all_done && r.done;
      if (r.lane_error.ok()) r.lane_error = shared.error(i);
      if ((r.done && !r.status.ok()) || !r.lane_error.ok()) stop = true;
    }
    if (signalled.load()) stop = true;
    line.MaybeSay(o.session.log);
  }
  for (std::thread& t : threads) t.join();
}

// Binds, writes the runs, starts the workers and serves every run; then
// says what next.
Status Serve(const CampaignOptions& o, CampaignPlan* plan,
             DispatcherOptions listen, const std::atomic<bool>& signalled) {
  zmq::context_t context(1);
  Result<std::unique_ptr<ChildIsolation>> isolation = ChildIsolation::Create(
      {{WorkerBesideThisProgram()}, listen.lease_ms, listen.clock});
  if (!isolation.ok()) return isolation.status();
  listen.isolation = isolation->get();
  Result<std::unique_ptr<Dispatcher>> dispatcher = Dispatcher::Create(
      &context, listen,
      ConfigToProto(plan->active.front()->plan.settings.model));
  if (!dispatcher.ok()) return dispatcher.status();
  for (auto& run : plan->active) {
    Result<size_t> config =
        (*dispatcher)->AddConfig(ConfigToProto(run->plan.settings.model));
    if (!config.ok()) return config.status().WithPrefix("run " + run->name);
    run->config = *config;
  }
  for (auto& run : plan->active) {
    Result<std::unique_ptr<EvolutionRun>> begun = EvolutionRun::Begin(
        run->store.get(), run->plan, Prefixed(run->name, o.session.log));
    if (!begun.ok()) return begun.status().WithPrefix("run " + run->name);
    run->run = std::move(begun).value();
  }
  LocalWorkers workers;
  Status status = StartLocalWorkers(o.session, **dispatcher, &workers);
  if (!status.ok()) return status;
  ServeRuns(o, plan, dispatcher->get(), signalled);
  bool all_finished = true;
  for (const auto& run : plan->active) {
    const Status& failed = run->lane_error.ok() ? run->status : run->lane_error;
    if (!failed.ok()) return failed.WithPrefix("run " + run->name);
    all_finished = all_finished && run->run->finished();
  }
  if (!all_finished) {
    o.session.outcome("stopped; resume with: " + o.session.resume_command);
    return Status::Ok();
  }
  (*dispatcher)->Farewell("the campaign is finished");
  o.session.outcome("finished: " + std::to_string(plan->total) + " runs in " +
                    o.dir +
                    "; their state: animat campaign "
                    "status --dir " +
                    CommandLine({o.dir}));
  return Status::Ok();
}

}  // namespace

Status RunCampaign(const CampaignOptions& o) {
  if (o.campaign_path.empty()) {
    return Status::InvalidArgument("--campaign needs a campaign file");
  }
  if (o.dir.empty()) {
    return Status::InvalidArgument(
        "--dir needs the folder of the campaign's stores");
  }
  Result<DispatcherOptions> listen = ListenOptions(o.session);
  if (!listen.ok()) return listen.status();
  const std::atomic<bool>& signalled = InstallStopHandlers();
  Result<CampaignPlan> plan = Plan(o);
  if (!plan.ok()) return plan.status();
  if (plan->active.empty()) {
    o.session.outcome("the campaign is finished: its " +
                      std::to_string(plan->total) + " runs in " + o.dir +
                      " have all their generations; nothing to do");
    return Status::Ok();
  }
  o.session.log(std::to_string(plan->active.size()) + " of " +
                std::to_string(plan->total) + " runs to serve (" +
                std::to_string(plan->finished) + " finished)");
  return Serve(o, &*plan, std::move(listen).value(), signalled);
}

}  // namespace animat
