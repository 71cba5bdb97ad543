#include "master/dispatch/lease_scheduler.h"
#include <algorithm>
#include <chrono>
#include <utility>

#include "common/base/text.h"

namespace animat {
namespace {

// Most credit a worker may hold: a hostile or broken peer asking for more
// only gets this much (and its leases expire if it never answers).
int CreditCap(int threads) {
  return static_cast<int>(
      std::min<int64_t>(int64_t{std::max(1, threads)} * protocol::kPrefetch *
                            protocol::kCreditCapFactor,
                        1 << 20));
}

// The peer's host, escaped and cut short: it reaches every log line about
// this worker.
std::string WorkerName(const v1::Hello& hello) {
  return ForeignText(hello.host(), 64) + ":" + std::to_string(hello.pid());
}

// A checked result (protocol::CheckWorkResult) as a completion, its
// attempts still to count; the path's name in lower case ("avx512"), empty
// when unspecified.
Completion FromWorker(v1::WorkResult r, std::string evaluator,
                      bool null_evaluation) {
  Completion completion;
  completion.individual = r.individual();
  completion.result = std::move(*r.mutable_result());
  completion.worker = std::move(evaluator);
  completion.wall_seconds = r.wall_seconds();
  if (r.isa() != v1::WorkResult::ISA_UNSPECIFIED) {
    completion.isa = AsciiLowerCase(v1::WorkResult::Isa_Name(r.isa()));
  }
  completion.null_evaluation = null_evaluation;
  return completion;
}

}  // namespace

LeaseScheduler::LeaseScheduler(SchedulerOptions options, v1::Config model,
                               Outbox* outbox)
    : options_(std::move(options)), outbox_(outbox) {
  const uint64_t hash = protocol::ConfigHash(model);
  std::string bytes = model.SerializeAsString();
  configs_.push_back({std::move(model), hash, std::move(bytes)});
  idle_since_ = options_.clock->Now();
  last_notice_ = idle_since_;
  if (!options_.notices) options_.notices = options_.log;
}

Result<size_t> LeaseScheduler::AddConfig(const v1::Config& config) {
  const uint64_t hash = protocol::ConfigHash(config);
  for (size_t i = 0; i < configs_.size(); ++i) {
    if (configs_[i].hash == hash) return i;
  }
  if (configs_.size() >= protocol::kMaxConfigs) {
    return Status::InvalidArgument("a master serves at most " +
                                   std::to_string(protocol::kMaxConfigs) +
                                   " model configurations at once");
  }
  configs_.push_back({config, hash, config.SerializeAsString()});
  return configs_.size() - 1;
}

void LeaseScheduler::Submit(uint64_t individual,
                            const protocol::SerializedGenome& genome,
                            size_t config) {
  if (pending_.count(individual) != 0) return;
  Individual& entry = pending_[individual];
  entry.item = EncodeWorkItem(individual, genome);
  entry.genome_hash = genome.hash;
  entry.config = config < configs_.size() ? config : 0;
  queue_.push_back(individual);
}

void LeaseScheduler::Handle(const std::string& identity,
                            const v1::Envelope& envelope,
                            std::vector<Completion>* done) {
  if (envelope.has_hello()) {
    Greet(identity, envelope.hello(), envelope.protocol_version());
    return;
  }
  const auto it = workers_.find(identity);
  if (it == workers_.end()) {
    // A worker from before a restart, or a stranger: it will time out and
    // say hello again. Logged once per peer.
    if (strangers_.size() < 10000 && strangers_.insert(identity).second) {
      Ignore(std::string("a ") + protocol::BodyName(envelope) +
             " message from a peer that has not said hello");
    } else {
      ++stats_.ignored;
    }
    return;
  }
  WorkerState& worker = it->second;
  worker.last_heard = options_.clock->Now();
  switch (envelope.body_case()) {
    case v1::Envelope::kCredit: {
      const int cap = CreditCap(worker.threads);
      const int64_t asked =
          static_cast<int64_t>(worker.credit) + envelope.credit().credit();
      if (asked > cap) {
        Ignore("credit beyond " + std::to_string(cap) + " from " + worker.name);
      }
      worker.credit = static_cast<int>(std::min<int64_t>(asked, cap));
      break;
    }
    case v1::Envelope::kResults:
      Collect(identity, worker, envelope.results(), done);
      break;
    case v1::Envelope::kHeartbeat:
      break;
    case v1::Envelope::kGoodbye: {
      int returned = 0;
      for (uint64_t id : envelope.goodbye().returned()) {
        if (worker.leased.count(id) != 0) {
          Unlease(id);
          Requeue(id, /*counts_as_attempt=*/false);
          ++returned;
        }
      }
      options_.log(worker.name + " said goodbye (" +
                   ForeignText(envelope.goodbye().reason(), 100) +
                   "), handing back " + std::to_string(returned));
      DropWorker(identity, /*died=*/false);
      break;
    }
    default:
      Ignore(std::string("an unexpected ") + protocol::BodyName(envelope) +
             " from " + worker.name);
      break;
  }
}

void LeaseScheduler::RefuseMalformed(const std::string& identity,
                                     const v1::Hello& hello,
                                     const std::string& why) {
  RefuseWorker(identity, WorkerName(hello), why);
}

std::string LeaseScheduler::PeerName(const std::string& identity) const {
  const auto it = workers_.find(identity);
  return it == workers_.end() ? std::string("an unknown peer")
                              : it->second.name;
}

std::string LeaseScheduler::Refusal(const v1::Hello& hello,
                                    uint32_t envelope_version) const {
  if (envelope_version != protocol::kVersion ||
      hello.protocol_version() != protocol::kVersion) {
    const uint32_t theirs = envelope_version != protocol::kVersion
                                ? envelope_version
                                : hello.protocol_version();
    return "protocol version " + std::to_string(theirs) +
           " differs from the master's " + std::to_string(protocol::kVersion);
  }
  if (hello.build_id() != protocol::BuildId()) {
    return "build \"" + ForeignText(hello.build_id(), 100) +
           "\" differs from the master's \"" + protocol::BuildId() +
           "\" (different builds can give different bits)";
  }
  if (hello.null_evaluation() && !options_.accept_null_workers) {
    return "null-evaluation workers are not accepted by this master";
  }
  return "";
}

void LeaseScheduler::RefuseWorker(const std::string& identity,
                                  const std::string& name,
                                  const std::string& refusal) {
  if (workers_.count(identity) != 0) {
    DropWorker(identity, /*died=*/false);
  }
  options_.log("refused worker " + name + ": " + refusal);
  ++stats_.refused;
  v1::Envelope envelope;
  envelope.mutable_refuse()->set_reason(refusal);
  Send(identity, envelope);
}

void LeaseScheduler::Greet(const std::string& identity, const v1::Hello& hello,
                           uint32_t envelope_version) {
  const std::string name = WorkerName(hello);
  const std::string refusal = Refusal(hello, envelope_version);
  if (!refusal.empty()) {
    RefuseWorker(identity, name, refusal);
    return;
  }
  if (workers_.count(identity) != 0) {
    // A second hello on one connection: start the session afresh.
    DropWorker(identity, /*died=*/false);
  }
  if (hello.instance() != 0) {
    // The same worker process on a new connection: it took the master for
    // lost (a master busy for longer than the workers' liveness), so its
    // old session is over, through no fault of the work it held.
    std::vector<std::string> replaced;
    for (const auto& [other, state] : workers_) {
      if (state.instance == hello.instance() && state.name == name) {
        replaced.push_back(other);
      }
    }
    for (const std::string& other : replaced) {
      options_.log("worker " + name + " reconnected; " +
                   std::to_string(workers_.at(other).leased.size()) +
                   " leases of its old session back in the queue");
      DropWorker(other, /*died=*/false);
    }
  }
  WorkerState& worker = workers_[identity];
  ever_joined_ = true;
  worker.name = name;
  worker.instance = hello.instance();
  worker.threads = static_cast<int>(hello.threads());  // Checked by Decode.
  worker.null_evaluation = hello.null_evaluation();
  worker.last_heard = options_.clock->Now();
  strangers_.erase(identity);
  v1::Envelope envelope;
  v1::Welcome* welcome = envelope.mutable_welcome();
  welcome->set_protocol_version(protocol::kVersion);
  welcome->set_build_id(protocol::BuildId());
  *welcome->mutable_config() = configs_[0].message;
  welcome->set_config_hash(configs_[0].hash);
  worker.configs = {0};
  welcome->set_heartbeat_ms(options_.heartbeat_ms);
  Send(identity, envelope);
  options_.log("worker " + name + " joined (" + std::to_string(worker.threads) +
               " threads)");
}

void LeaseScheduler::Collect(const std::string& identity, WorkerState& worker,
                             const v1::Results& results,
                             std::vector<Completion>* done) {
  // What the worker may forget now: results of no use here, and with
  // acknowledge_on_receipt, the completions.
  v1::Envelope acknowledge;
  v1::Acknowledge* forget = acknowledge.mutable_acknowledge();
  for (const v1::WorkResult& r : results.results()) {
    const auto it = pending_.find(r.individual());
    if (it == pending_.end()) {
      const auto delivered = delivered_.find(r.individual());
      if (delivered != delivered_.end()) {
        // Completed here and not yet recorded, sent again by a worker
        // that reconnected: that connection is told once it is recorded.
        delivered->second = identity;
        continue;
      }
      Ignore("a result for individual " + std::to_string(r.individual()) +
             " from " + worker.name + " (unknown or already complete)");
      forget->add_individuals(r.individual());
      continue;
    }
    Individual& entry = it->second;
    if (r.genome_hash() != entry.genome_hash) {
      Ignore("a result for individual " + std::to_string(r.individual()) +
             " from " + worker.name + " for another genome");
      forget->add_individuals(r.individual());
      continue;
    }
    const Status valid = protocol::CheckWorkResult(r);
    if (!valid.ok()) {
      Ignore("an invalid result for individual " +
             std::to_string(r.individual()) + " from " + worker.name + ": " +
             valid.message());
      forget->add_individuals(r.individual());
      continue;
    }
    if (entry.leased) {
      Unlease(r.individual());
    } else if (entry.isolated) {
      options_.isolation->Cancel(r.individual());  // No longer needed.
    } else {
      Unqueue(r.individual());
    }
    Complete(FromWorker(r, worker.name, worker.null_evaluation), done);
    if (options_.acknowledge_on_receipt) {
      forget->add_individuals(r.individual());
    } else {
      delivered_[r.individual()] = identity;
    }
  }
  if (forget->individuals_size() > 0) Send(identity, std::move(acknowledge));
}

void LeaseScheduler::Acknowledge(const std::vector<uint64_t>& individuals) {
  // Per worker, in identity order, messages of up to kMaxAcknowledged.
  std::map<std::string, std::vector<uint64_t>> ids;
  for (uint64_t id : individuals) {
    const auto it = delivered_.find(id);
    if (it == delivered_.end()) continue;
    if (workers_.count(it->second) != 0) ids[it->second].push_back(id);
    delivered_.erase(it);
  }
  for (const auto& [identity, list] : ids) {
    for (size_t begin = 0; begin < list.size();
         begin += protocol::kMaxAcknowledged) {
      const size_t end = std::min(
          list.size(), begin + static_cast<size_t>(protocol::kMaxAcknowledged));
      v1::Envelope envelope;
      for (size_t i = begin; i < end; ++i) {
        envelope.mutable_acknowledge()->add_individuals(list[i]);
      }
      Send(identity, std::move(envelope));
    }
  }
}

void LeaseScheduler::Lease(const std::string& identity, WorkerState& worker,
                           uint64_t individual, TimePoint deadline,
                           WorkEncoder* work, std::vector<uint64_t>* items) {
  Individual& entry = pending_.at(individual);
  work->Add(entry.item);
  items->push_back(individual);
  entry.leased = true;
  entry.worker = identity;
  entry.deadline = deadline;
  entry.lease = ++leases_made_;
  // Deadlines are handed out in time order, so expiry only looks at the
  // front of this queue.
  lease_order_.push_back({deadline, individual, entry.lease});
  worker.leased.insert(individual);
  --worker.credit;
  ++stats_.dispatched;
}

void LeaseScheduler::Dispatch() {
  for (auto& [identity, worker] : workers_) {
    if (worker.credit <= 0 || worker.suspect.has_value()) continue;
    const TimePoint deadline =
        options_.clock->Now() + std::chrono::milliseconds(options_.lease_ms);
    if (!suspects_.empty()) {
      // A suspect (its last worker died or its lease expired) goes alone to
      // a worker holding nothing else, so it cannot take others down.
      if (worker.leased.empty()) {
        const uint64_t suspect = suspects_.begin()->second;
        const size_t config = pending_.at(suspect).config;
        WorkEncoder work(configs_[config].hash);
        std::vector<uint64_t> items;
        suspects_.erase(suspects_.begin());
        worker.suspect = suspect;
        Lease(identity, worker, suspect, deadline, &work, &items);
        SendWork(identity, worker, config, &work, items);
        if (drainer_ == identity) drainer_.clear();
        continue;
      }
      // One worker stops taking other work until it is empty.
      if (drainer_.empty() || workers_.count(drainer_) == 0) {
        drainer_ = identity;
      }
      if (drainer_ == identity) continue;
    }
    while (worker.credit > 0 && !queue_.empty()) {
      // Room for a batch of items like the next one.
      const size_t batch = static_cast<size_t>(
          std::min(worker.credit, static_cast<int>(protocol::kMaxBatch)));
      const Individual& next = pending_.at(queue_.front());
      // One Work holds items of one configuration: the next one's.
      const size_t config = next.config;
      WorkEncoder work(
          configs_[config].hash,
          std::min(protocol::kMaxWorkBytes, batch * (next.item.size() + 8)));
      std::vector<uint64_t> items;
      while (worker.credit > 0 && !queue_.empty() &&
             work.items() < protocol::kMaxBatch) {
        const uint64_t individual = queue_.front();
        const Individual& entry = pending_.at(individual);
        // Keep each message well inside the sockets' size limit.
        if (entry.config != config ||
            (work.items() > 0 &&
             work.item_bytes() + entry.item.size() > protocol::kMaxWorkBytes)) {
          break;
        }
        queue_.pop_front();
        Lease(identity, worker, individual, deadline, &work, &items);
      }
      if (!SendWork(identity, worker, config, &work, items)) break;
    }
  }
  if (suspects_.empty()) drainer_.clear();
}

bool LeaseScheduler::SendWork(const std::string& identity, WorkerState& worker,
                              size_t config, WorkEncoder* work,
                              const std::vector<uint64_t>& items) {
  const bool carried = worker.configs.count(config) == 0;
  if (carried) work->SetConfig(configs_[config].bytes);
  if (SendEncoded(identity, "work", work->Finish())) {
    if (carried) worker.configs.insert(config);
    return true;
  }
  // Not delivered (the worker's queue is full or it is gone): the items
  // go back at once, without counting an attempt.
  for (auto id = items.rbegin(); id != items.rend(); ++id) {
    Unlease(*id);
    ++worker.credit;
    Requeue(*id, /*counts_as_attempt=*/false);
  }
  return false;
}

void LeaseScheduler::Housekeep(std::vector<Completion>* done) {
  CollectIsolated(done);
  const TimePoint now = options_.clock->Now();
  NoticeIdle(now);
  const auto silent_limit =
      std::chrono::milliseconds(protocol::kLiveness * options_.heartbeat_ms);
  std::vector<std::string> dead;
  for (auto& [identity, worker] : workers_) {
    if (now - worker.last_heard > silent_limit) {
      dead.push_back(identity);
      continue;
    }
    if (now - worker.last_sent >=
        std::chrono::milliseconds(options_.heartbeat_ms)) {
      v1::Envelope heartbeat;
      heartbeat.mutable_heartbeat();
      Send(identity, heartbeat);
    }
  }
  for (const std::string& identity : dead) {
    const WorkerState& worker = workers_.at(identity);
    options_.log("worker " + worker.name + " silent for " +
                 std::to_string(silent_limit.count()) + " ms; " +
                 std::to_string(worker.leased.size()) +
                 " leases back in the queue");
    DropWorker(identity, /*died=*/true);
  }
  // Expired leases (their worker may still answer: the first result wins).
  // Records of leases that already ended are dropped on the way.
  std::vector<uint64_t> expired;
  while (!lease_order_.empty()) {
    const LeaseRecord& record = lease_order_.front();
    const auto it = pending_.find(record.individual);
    const bool live = it != pending_.end() && it->second.leased &&
                      it->second.lease == record.lease;
    if (live && !(now > record.deadline)) break;  // The rest are later.
    if (live) expired.push_back(record.individual);
    lease_order_.pop_front();
  }
  for (uint64_t id : expired) {
    const auto holder = workers_.find(pending_.at(id).worker);
    if (holder != workers_.end()) {
      options_.log("lease of individual " + std::to_string(id) + " on " +
                   holder->second.name + " expired");
    }
    Unlease(id);
    Requeue(id, /*counts_as_attempt=*/true);
  }
}

void LeaseScheduler::NoticeIdle(TimePoint now) {
  if (!workers_.empty() || options_.idle_notice_ms <= 0) return;
  const auto every = std::chrono::milliseconds(options_.idle_notice_ms);
  if (now - std::max(idle_since_, last_notice_) < every) return;
  last_notice_ = now;
  const auto idle =
      std::chrono::duration_cast<std::chrono::seconds>(now - idle_since_);
  options_.notices(std::string(ever_joined_ ? "no worker connected for "
                                            : "no worker has joined in ") +
                   std::to_string(idle.count()) + " s; listening on " +
                   endpoint_ + " (" + std::to_string(pending_.size()) +
                   " individuals waiting)");
}

void LeaseScheduler::Farewell(const std::string& reason) {
  std::vector<std::string> identities;
  for (const auto& [identity, worker] : workers_)
    identities.push_back(identity);
  for (const std::string& identity : identities) {
    v1::Envelope goodbye;
    goodbye.mutable_goodbye()->set_reason(reason);
    Send(identity, std::move(goodbye));
  }
}

void LeaseScheduler::Requeue(uint64_t individual, bool counts_as_attempt) {
  Individual& entry = pending_.at(individual);
  entry.leased = false;
  entry.worker.clear();
  ++stats_.requeued;
  if (counts_as_attempt && ++entry.attempts >= protocol::kMaxAttempts) {
    Isolate(individual);
  } else if (entry.attempts > 0) {
    suspects_.insert({-entry.attempts, individual});
  } else {
    queue_.push_front(individual);  // Handed back: next in line.
  }
}

void LeaseScheduler::Isolate(uint64_t individual) {
  Individual& entry = pending_.at(individual);
  const std::string ended = "individual " + std::to_string(individual) + ": " +
                            std::to_string(entry.attempts) +
                            " leases ended without a result";
  if (options_.isolation == nullptr) {
    options_.log(ended + "; retried on workers (no isolation here)");
  } else {
    const Config& config = configs_[entry.config];
    const Status started = options_.isolation->Start(
        individual, entry.item, config.message, config.hash);
    if (started.ok()) {
      entry.isolated = true;
      ++stats_.isolated;
      options_.log(ended +
                   " (each time its worker vanished or the lease "
                   "expired); evaluating it alone in a child process");
      return;
    }
    options_.log(ended + "; it cannot be evaluated alone (" +
                 started.message() + "), so it is retried on workers");
  }
  suspects_.insert({-entry.attempts, individual});
}

void LeaseScheduler::CollectIsolated(std::vector<Completion>* done) {
  if (options_.isolation == nullptr) return;
  for (IsolatedOutcome& outcome : options_.isolation->Finished()) {
    const uint64_t id = outcome.individual;
    const auto it = pending_.find(id);
    if (it == pending_.end() || !it->second.isolated) continue;
    Individual& entry = it->second;
    entry.isolated = false;
    const std::string which = "individual " + std::to_string(id);
    if (outcome.kind == IsolatedOutcome::Kind::kResult) {
      Status valid = protocol::CheckWorkResult(outcome.result);
      if (valid.ok() && (outcome.result.individual() != id ||
                         outcome.result.genome_hash() != entry.genome_hash)) {
        valid = Status::InvalidArgument("a result for another individual");
      }
      if (valid.ok()) {
        options_.log(which + " evaluated alone: " +
                     v1::EvaluationResult::Status_Name(
                         outcome.result.result().status()));
        Complete(
            FromWorker(std::move(outcome.result), std::move(outcome.evaluator),
                       /*null_evaluation=*/false),
            done);
        continue;
      }
      outcome.how = "an invalid result: " + valid.message();
    } else if (outcome.kind == IsolatedOutcome::Kind::kCrashed) {
      v1::EvaluationResult crashed;
      crashed.set_status(v1::EvaluationResult::CRASHED);
      crashed.set_reason("the evaluation crashed (" + outcome.how +
                         ") alone in a child process, after " +
                         std::to_string(entry.attempts) +
                         " leases on workers ended without a result");
      options_.log(which + " crashed alone too (" + outcome.how +
                   "): recorded as crashed");
      ++stats_.crashed;
      Completion completion;
      completion.individual = id;
      completion.result = std::move(crashed);
      completion.worker = std::move(outcome.evaluator);
      Complete(std::move(completion), done);
      continue;
    }
    options_.log("the evaluation of " + which + " alone decided nothing (" +
                 outcome.how + "); it is retried on workers");
    suspects_.insert({-entry.attempts, id});
  }
}

void LeaseScheduler::Complete(Completion completion,
                              std::vector<Completion>* done) {
  const auto it = pending_.find(completion.individual);
  completion.attempts = it->second.attempts;
  done->push_back(std::move(completion));
  pending_.erase(it);
  ++stats_.completed;
}

void LeaseScheduler::Unlease(uint64_t individual) {
  Individual& entry = pending_.at(individual);
  const auto holder = workers_.find(entry.worker);
  if (holder != workers_.end()) {
    holder->second.leased.erase(individual);
    if (holder->second.suspect == individual) holder->second.suspect.reset();
  }
  entry.leased = false;
  entry.worker.clear();
}

void LeaseScheduler::Unqueue(uint64_t individual) {
  if (suspects_.erase({-pending_.at(individual).attempts, individual}) != 0) {
    return;
  }
  const auto it = std::find(queue_.begin(), queue_.end(), individual);
  if (it != queue_.end()) queue_.erase(it);
}

void LeaseScheduler::DropWorker(const std::string& identity, bool died) {
  const auto it = workers_.find(identity);
  if (it == workers_.end()) return;
  const std::set<uint64_t> leased = std::move(it->second.leased);
  workers_.erase(it);
  if (workers_.empty()) idle_since_ = options_.clock->Now();
  // Highest first, so the queue front ends up in increasing order.
  for (auto id = leased.rbegin(); id != leased.rend(); ++id) {
    if (pending_.count(*id) != 0) Requeue(*id, died);
  }
}

bool LeaseScheduler::Send(const std::string& identity, v1::Envelope envelope) {
  const char* what = protocol::BodyName(envelope);
  return SendEncoded(identity, what, protocol::Encode(std::move(envelope)));
}

bool LeaseScheduler::SendEncoded(const std::string& identity, const char* what,
                                 const std::string& bytes) {
  const auto it = workers_.find(identity);
  std::string problem;
  const bool delivered = outbox_->Deliver(identity, bytes, &problem);
  if (it != workers_.end()) it->second.last_sent = options_.clock->Now();
  if (delivered) {
    if (it != workers_.end()) it->second.send_failed = false;
    return true;
  }
  // Counted as sent: the next attempt waits a heartbeat interval, and a
  // worker that is gone is dropped when its silence runs out. Logged once
  // per worker until a send succeeds again.
  if (it == workers_.end() || !it->second.send_failed) {
    options_.log(
        std::string("could not send ") + what + " to " +
        (it == workers_.end() ? std::string("a peer") : it->second.name) +
        ": " + problem);
  }
  if (it != workers_.end()) it->second.send_failed = true;
  return false;
}

void LeaseScheduler::Ignore(const std::string& what) {
  ++stats_.ignored;
  options_.log("ignored " + what);
}

}  // namespace animat
