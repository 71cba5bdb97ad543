// Writes the seed corpora of the fuzz targets with the real encoder:
// valid messages of every kind, and a few near misses the dispatcher must
// reject.
//
//   make_corpus SOURCE_DIR OUT_DIR
//
// reads genomes from SOURCE_DIR/tests/data/genomes and writes
// OUT_DIR/<target>/<name>, one encoded input per file (the committed seeds
// are fuzz/corpus/; scripts/fuzz.sh --seeds regenerates them).
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "common/evaluation/model_config.h"
#include "common/io/proto_file.h"
#include "common/protocol/genome_wire.h"
#include "common/protocol/protocol.h"
#include "fuzz/fuzz_common.h"

namespace animat::fuzz {
namespace {

namespace fs = std::filesystem;

class Writer {
 public:
  explicit Writer(fs::path out) : out_(std::move(out)) {}

  void Put(const std::string& target, const std::string& name,
           const std::string& bytes) {
    fs::create_directories(out_ / target);
    const Status status = WriteFile((out_ / target / name).string(), bytes);
    if (!status.ok()) {
      std::fprintf(stderr, "make_corpus: %s\n", status.ToString().c_str());
      failed_ = true;
    }
  }
  bool failed() const { return failed_; }

 private:
  fs::path out_;
  bool failed_ = false;
};

v1::Envelope Hello(uint32_t threads, bool null_evaluation) {
  v1::Envelope e;
  v1::Hello* h = e.mutable_hello();
  h->set_protocol_version(protocol::kVersion);
  h->set_build_id(protocol::BuildId());
  h->set_threads(threads);
  h->set_host("seed");
  h->set_pid(4242);
  h->set_null_evaluation(null_evaluation);
  return e;
}

v1::Envelope Welcome(const v1::Config& config) {
  v1::Envelope e;
  v1::Welcome* w = e.mutable_welcome();
  w->set_protocol_version(protocol::kVersion);
  w->set_build_id(protocol::BuildId());
  *w->mutable_config() = config;
  w->set_config_hash(protocol::ConfigHash(config));
  w->set_heartbeat_ms(protocol::kHeartbeatMs);
  return e;
}

v1::Envelope Credit(uint32_t credit) {
  v1::Envelope e;
  e.mutable_credit()->set_credit(credit);
  return e;
}

v1::Envelope Work(const std::vector<v1::Genome>& genomes, uint64_t hash) {
  v1::Envelope e;
  v1::Work* work = e.mutable_work();
  work->set_config_hash(hash);
  uint64_t id = 1;
  for (const v1::Genome& genome : genomes) {
    v1::WorkItem* item = work->add_items();
    item->set_individual(id++);
    *item->mutable_genome() = genome;
    item->set_genome_hash(protocol::GenomeHash(genome));
  }
  return e;
}

v1::WorkResult MakeResult(uint64_t id, uint64_t genome_hash,
                          v1::EvaluationResult::Status status) {
  v1::WorkResult r;
  r.set_individual(id);
  r.set_genome_hash(genome_hash);
  r.set_wall_seconds(0.25);
  v1::EvaluationResult* result = r.mutable_result();
  result->set_status(status);
  if (status == v1::EvaluationResult::OK) {
    result->set_fitness(0.10802053681947885);
    result->set_cells(32);
    result->set_steps(6600);
    result->set_state_hash(0xc9385f269eba3b50ull);
  } else {
    result->set_reason("seed reason");
  }
  return r;
}

v1::Envelope Results(const std::vector<v1::WorkResult>& results) {
  v1::Envelope e;
  for (const v1::WorkResult& r : results) {
    *e.mutable_results()->add_results() = r;
  }
  return e;
}

v1::Envelope Heartbeat() {
  v1::Envelope e;
  e.mutable_heartbeat();
  return e;
}

v1::Envelope Goodbye(const std::vector<uint64_t>& returned) {
  v1::Envelope e;
  for (uint64_t id : returned) e.mutable_goodbye()->add_returned(id);
  e.mutable_goodbye()->set_reason("worker stopping");
  return e;
}

v1::Envelope Refuse() {
  v1::Envelope e;
  e.mutable_refuse()->set_reason("build differs");
  return e;
}

int Main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: make_corpus SOURCE_DIR OUT_DIR\n");
    return 2;
  }
  const fs::path genomes_dir = fs::path(argv[1]) / "tests/data/genomes";
  Writer out{fs::path(argv[2])};

  std::vector<std::pair<std::string, v1::Genome>> genomes;
  for (const char* name : {"example", "seed-1198", "seed-1203", "seed-139",
                           "seed-1-nonviable", "seed-2-too-few-cells"}) {
    v1::Genome genome;
    const Status status = ReadProtoFile(
        (genomes_dir / (std::string(name) + ".json")).string(), &genome);
    if (!status.ok()) {
      std::fprintf(stderr, "make_corpus: %s\n", status.ToString().c_str());
      return 1;
    }
    genomes.emplace_back(name, genome);
  }
  const v1::Config config = ConfigToProto(ModelConfig{});
  const uint64_t config_hash = protocol::ConfigHash(config);
  v1::Config partial;
  partial.mutable_physics()->set_dt(0.01);
  partial.mutable_evaluation()->set_motion_steps(100);

  // decode_fuzzer: one of each message.
  const std::string decode = "decode_fuzzer";
  out.Put(decode, "hello", protocol::Encode(Hello(4, false)));
  out.Put(decode, "welcome", protocol::Encode(Welcome(config)));
  out.Put(decode, "refuse", protocol::Encode(Refuse()));
  out.Put(decode, "credit", protocol::Encode(Credit(8)));
  out.Put(decode, "work",
          protocol::Encode(
              Work({genomes[0].second, genomes[1].second}, config_hash)));
  out.Put(decode, "results",
          protocol::Encode(
              Results({MakeResult(1, 7, v1::EvaluationResult::OK),
                       MakeResult(2, 8, v1::EvaluationResult::NON_VIABLE)})));
  out.Put(decode, "heartbeat", protocol::Encode(Heartbeat()));
  out.Put(decode, "goodbye", protocol::Encode(Goodbye({3, 4})));

  // work_fuzzer: every test genome, alone and together, and welcomes.
  const std::string work = "work_fuzzer";
  std::vector<v1::Genome> all;
  for (const auto& [name, genome] : genomes) {
    out.Put(work, "work-" + name,
            protocol::Encode(Work({genome}, config_hash)));
    all.push_back(genome);
  }
  out.Put(work, "work-all", protocol::Encode(Work(all, config_hash)));
  out.Put(work, "welcome-default", protocol::Encode(Welcome(config)));
  {
    // A Work that carries its configuration (a campaign's other model).
    v1::Config other = config;
    other.mutable_physics()->set_drag_normal(10);
    v1::Envelope carried =
        Work({genomes[0].second}, protocol::ConfigHash(other));
    *carried.mutable_work()->mutable_config() = other;
    out.Put(work, "work-carried-config", protocol::Encode(carried));
    // The same under a hash it does not have.
    carried.mutable_work()->set_config_hash(protocol::ConfigHash(other) + 1);
    out.Put(work, "work-carried-config-wrong-hash", protocol::Encode(carried));
  }
  out.Put(work, "welcome-partial", protocol::Encode(Welcome(partial)));

  // results_fuzzer: every status, and some a master must refuse.
  const std::string results = "results_fuzzer";
  std::vector<v1::WorkResult> every;
  for (int s = v1::EvaluationResult::OK; s <= v1::EvaluationResult::CRASHED;
       ++s) {
    const auto status = static_cast<v1::EvaluationResult::Status>(s);
    every.push_back(MakeResult(s, 1000 + s, status));
    out.Put(results, "results-" + v1::EvaluationResult::Status_Name(status),
            protocol::Encode(Results({every.back()})));
  }
  out.Put(results, "results-every-status", protocol::Encode(Results(every)));
  v1::WorkResult no_fitness = MakeResult(1, 1, v1::EvaluationResult::OK);
  no_fitness.mutable_result()->clear_fitness();
  v1::WorkResult negative = MakeResult(2, 2, v1::EvaluationResult::OK);
  negative.mutable_result()->set_fitness(-1);
  v1::WorkResult fitness_not_ok =
      MakeResult(3, 3, v1::EvaluationResult::NON_VIABLE);
  fitness_not_ok.mutable_result()->set_fitness(1);
  out.Put(results, "results-invalid",
          protocol::Encode(Results({no_fitness, negative, fitness_not_ok})));

  // dispatcher_fuzzer: what a worker and strangers send, in the harness's
  // input format, for its pending individuals 1..kIndividuals.
  const std::string dispatcher = "dispatcher_fuzzer";
  const uint64_t harness_hash = protocol::GenomeHash(HarnessGenome());
  auto message = [](const v1::Envelope& envelope, bool stranger = false,
                    bool wait = false) {
    FuzzMessage m;
    m.stranger = stranger;
    m.fix_build_id = true;
    m.wait = wait;
    m.frames = {protocol::Encode(envelope)};
    return m;
  };
  auto put = [&](const std::string& name,
                 const std::vector<FuzzMessage>& messages) {
    out.Put(dispatcher, name, FormatDispatcherInput(messages));
  };
  std::vector<v1::WorkResult> harness_ok, harness_not_evaluated;
  std::vector<uint64_t> ids;
  for (uint64_t id = 1; id <= kIndividuals; ++id) {
    harness_ok.push_back(
        MakeResult(id, harness_hash, v1::EvaluationResult::OK));
    harness_not_evaluated.push_back(
        MakeResult(id, harness_hash, v1::EvaluationResult::NOT_EVALUATED));
    ids.push_back(id);
  }
  put("credit", {message(Credit(4))});
  put("credit-beyond-cap", {message(Credit(1000000))});
  put("credit-results",
      {message(Credit(8), false, true), message(Results(harness_ok))});
  put("results-not-evaluated", {message(Results(harness_not_evaluated))});
  put("results-unknown-individual",
      {message(
          Results({MakeResult(99, harness_hash, v1::EvaluationResult::OK)}))});
  put("results-other-genome",
      {message(Results({MakeResult(1, 12345, v1::EvaluationResult::OK)}))});
  put("results-invalid", {message(Results({no_fitness}))});
  put("credit-goodbye",
      {message(Credit(8), false, true), message(Goodbye(ids))});
  put("heartbeat-wait", {message(Heartbeat(), false, true)});
  put("hello-credit", {message(Hello(64, false)), message(Credit(100))});
  put("hello-null-evaluation", {message(Hello(1, true))});
  v1::Envelope old_hello = Hello(1, false);
  old_hello.mutable_hello()->set_protocol_version(0);
  put("hello-old-version", {message(old_hello)});
  put("stranger-hello-credit",
      {message(Hello(2, false), true), message(Credit(4), true, true)});
  put("stranger-credit", {message(Credit(4), true)});
  put("unexpected-work", {message(Work({HarnessGenome()}, config_hash))});
  {
    FuzzMessage m;
    m.frames = {protocol::Encode(Credit(2)), protocol::Encode(Heartbeat())};
    put("two-frames", {m});
    m.frames = {"", "garbage", std::string(3, '\xff')};
    put("three-frames-garbage", {m});
    m.frames = {std::string("\x08\x02\x82\x01\x00", 5)};  // Version 2.
    put("other-version", {m});
  }

  // scheduler_fuzzer: scripts of events (scheduler_fuzzer.cc): a byte for
  // the event, one for the peer, then its arguments.
  const std::string scheduler = "scheduler_fuzzer";
  const auto script = [](std::initializer_list<int> bytes) {
    std::string s;
    for (const int b : bytes) s.push_back(static_cast<char>(b));
    return s;
  };
  // Hello, credit 3, three valid results, time.
  out.Put(scheduler, "serve", script({1, 0, 0, 7, 2, 0, 2, 3, 0, 1, 3,
                                      3, 0, 2, 3, 3, 0, 3, 3, 4, 0, 10}));
  // Two workers; one goes silent and its leases expire.
  out.Put(scheduler, "expire", script({1, 0, 1, 7, 2,  0, 3, 1,  1, 0, 8, 2,
                                       1, 3, 4, 0, 60, 4, 0, 60, 3, 1, 1, 3}));
  // An outbox that fails, a goodbye, a result for another genome.
  out.Put(scheduler, "faults", script({1, 2, 0, 9, 5, 2, 0, 2, 2, 1, 4, 0, 5,
                                       5, 2, 0, 4, 0, 5, 6, 2, 1, 3, 2, 1, 0}));
  // A frame: a credit message as the transport would decode it.
  {
    const std::string credit = protocol::Encode(Credit(2));
    std::string frame = script({1, 1, 0, 3, 0, 1});
    frame.push_back(static_cast<char>(credit.size()));
    frame += credit;
    out.Put(scheduler, "frame", frame + script({4, 0, 1}));
  }
  return out.failed() ? 1 : 0;
}

}  // namespace
}  // namespace animat::fuzz

int main(int argc, char** argv) { return animat::fuzz::Main(argc, argv); }
