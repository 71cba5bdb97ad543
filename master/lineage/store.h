// The lineage store: every individual a run makes, its parents, how it was
// made, its genome and its evaluation; runs and generations (SQLite, WAL;
// schema in schema.cc and docs/lineage.md).
//
// Writes are transactions: individuals are committed before their genomes
// leave the master, results in batches as they arrive (a crash leaves the
// results received since the last commit unrecorded; workers keep them
// until acknowledged and send them to the resumed master, docs/lineage.md).
// Opening takes an exclusive lock on "<path>.lock", so two masters never
// share a store.
//
// Not thread-safe: one thread uses a Store.
#ifndef ANIMAT_MASTER_LINEAGE_STORE_H_
#define ANIMAT_MASTER_LINEAGE_STORE_H_

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "animat/v1/evolution.pb.h"
#include "animat/v1/genome.pb.h"
#include "animat/v1/trace.pb.h"
#include "common/base/clock.h"
#include "common/base/status.h"
#include "common/protocol/genome_wire.h"
#include "master/lineage/sqlite.h"

namespace animat::lineage {

struct RunRow {
  int64_t run_id = 0;
  uint64_t seed = 0;
  v1::RunConfig config;
  std::string config_hash;  // 16 hex digits.
  std::string build_id;
  std::string started_at;
  std::string ended_at;  // Empty while running.
  std::string state;     // "running" or "finished".
};

// One configuration a run has had (Store::ConfigHistory): what the run ran
// with, and which build evaluated it, from `from_generation` on.
struct RunConfigRow {
  int change = 0;           // 0: as started; then 1, 2, ... in order.
  int from_generation = 0;  // The first generation made under it.
  v1::RunConfig config;
  std::string config_hash;  // 16 hex digits.
  std::string build_id;
  std::string recorded_at;
  std::string reason;  // "started", or what changed and why.
};

// An individual as made, before its evaluation.
struct NewIndividual {
  uint64_t id = 0;
  int generation = 0;
  std::vector<uint64_t> parents;       // In order; none for random ones.
  std::vector<std::string> operators;  // E.g. {"crossover", "sign"}.
  // The genome, as a message or as bytes: when `serialized` is set (by
  // protocol::SerializeGenome, of the message or of the Genome it came
  // from), the store writes those bytes, hash and length, and `genome` may
  // be left empty.
  v1::Genome genome;
  std::optional<protocol::SerializedGenome> serialized;
};

struct Evaluation {
  uint64_t id = 0;
  // Recorded whole: status, fitness, ..., and the body summary when the
  // result has one (the body columns are NULL otherwise). The caller has
  // checked it (protocol::ValidateResult).
  v1::EvaluationResult result;
  double wall_seconds = 0;
  std::string worker;  // host:pid
  std::string isa;     // "avx512", ...; empty (NULL) when not known.
};

struct IndividualRow {
  uint64_t id = 0;
  int generation = 0;
  std::vector<uint64_t> parents;
  std::string operators;
  v1::Genome genome;
  bool evaluated = false;
  std::string status;  // "ok", ...; empty until evaluated.
  std::string reason;
  std::optional<double> fitness;  // Only when status is "ok".
};

// What the run loop needs of an individual's evaluation.
struct Score {
  uint64_t id = 0;
  bool evaluated = false;
  std::optional<double> fitness;  // Only for status "ok".
};

// A member of a generation with what making the next one needs.
struct MemberGenome {
  uint64_t id = 0;
  std::optional<double> fitness;  // Only for status "ok".
  v1::Genome genome;
};

struct GenerationRow {
  int generation = 0;
  int size = 0;
  bool complete = false;
  std::vector<uint64_t> members;  // Ranked (best first) once complete.
};

struct GenerationStats {
  int evaluated = 0;  // Members with status "ok".
  int failed = 0;
  std::optional<uint64_t> best_id;
  std::optional<double> best, mean, median;
};

class GenerationWrite;

class Store {
 public:
  // Opens or creates the store at `path` ("" or ":memory:" for a private
  // in-memory store, without a lock file), upgrading an older schema.
  // Fails, saying so, when another process holds the store's lock. The
  // times it records (created_at, evaluated_at, ...) are `clock`'s Utc(),
  // which must outlive the store.
  static Result<std::unique_ptr<Store>> Open(const std::string& path,
                                             const Clock& clock = RealClock());
  // Opens an existing store for queries only: no lock (a master may be
  // writing; WAL lets both proceed), no migration. Fails, saying so, when
  // the file does not exist or its schema is not this build's.
  static Result<std::unique_ptr<Store>> OpenForQueries(const std::string& path);
  // Brings the existing store at `path` to this build's schema
  // (kSchemaVersion), under its lock and with Open's migrations, and
  // returns the schema version it had before (kSchemaVersion when there
  // was nothing to do). Unlike Open, never creates a store: kNotFound
  // ("<path>: no such lineage store") for a missing file,
  // kInvalidArgument for an SQLite file that is no lineage store (schema
  // version 0), Open's errors otherwise (another master holds the lock, a
  // store written by a newer build, ...).
  static Result<int> Upgrade(const std::string& path);
  ~Store();

  // The path the store was opened with ("" or ":memory:" for an in-memory
  // store), for messages.
  const std::string& path() const { return db_->path(); }

  // Runs. CreateRun also starts the run's configuration history.
  Result<int64_t> CreateRun(uint64_t seed, const v1::RunConfig& config,
                            const std::string& build_id);
  Result<std::vector<RunRow>> Runs();  // Oldest first.
  Status FinishRun(int64_t run);
  // The run's configuration and the build that evaluates it from generation
  // `from_generation` on (a run extended to more generations, or resumed
  // with --force): the run's row shows them, its configuration history
  // keeps them after the earlier ones with `reason`, and the run is marked
  // running again; in one transaction.
  Status UpdateRunConfig(int64_t run, int from_generation,
                         const v1::RunConfig& config,
                         const std::string& build_id,
                         const std::string& reason);
  // The configurations the run has had, oldest first: the one it started
  // with, then each change (none for an unknown run).
  Result<std::vector<RunConfigRow>> ConfigHistory(int64_t run);

  // Individuals. AddIndividuals writes all of them (and their parents) in
  // one transaction. RecordEvaluations writes a batch in one transaction;
  // an individual already evaluated keeps its first evaluation.
  Status AddIndividuals(int64_t run, const std::vector<NewIndividual>& batch);
  Status RecordEvaluations(int64_t run, const std::vector<Evaluation>& batch);
  Result<IndividualRow> Individual(int64_t run, uint64_t id);
  // Individuals of `generation` in increasing id, evaluated or not.
  Result<std::vector<IndividualRow>> IndividualsOf(int64_t run, int generation);
  // The scores of the individuals made for `generation`, in increasing id
  // (no genomes are read).
  Result<std::vector<Score>> ScoresOf(int64_t run, int generation);
  // The scores of the members of `generation`, in increasing id.
  Result<std::vector<Score>> MemberScores(int64_t run, int generation);
  // The members of `generation` with their fitness and genomes, in
  // increasing id, in one query. Fails, naming the individual, on a genome
  // that does not parse.
  Result<std::vector<MemberGenome>> MemberGenomes(int64_t run, int generation);
  // Every individual of the run not yet evaluated, in increasing id.
  Result<std::vector<uint64_t>> Unevaluated(int64_t run);
  // One more than the highest id of the run (0 for none).
  Result<uint64_t> NextId(int64_t run);

  // Generations. AddGeneration records a generation's members; with
  // `individuals`, those are added in the same transaction (a generation
  // and the offspring it needs appear together or not at all).
  Status AddGeneration(int64_t run, int generation,
                       const std::vector<uint64_t>& members,
                       const std::vector<NewIndividual>& individuals = {});
  // The same in parts (GenerationWrite): the offspring in chunks as they
  // are made, then the generation, in one transaction begun here.
  Result<std::unique_ptr<GenerationWrite>> BeginGeneration(
      int64_t run, int generation, std::vector<uint64_t> members);
  Status CompleteGeneration(int64_t run, int generation,
                            const std::vector<uint64_t>& ranked,
                            const GenerationStats& stats);
  // The generation with the highest number, if any.
  Result<std::optional<GenerationRow>> LatestGeneration(int64_t run);
  // The same without its members (left empty), in one row read.
  Result<std::optional<GenerationRow>> LatestGenerationHead(int64_t run);
  Result<GenerationRow> Generation(int64_t run, int generation);

 private:
  // The SQL stays in master/lineage/: its query functions reach the
  // database through StoreAccess (store_access.h), tests through
  // StoreTestPeer (tests/lineage/store_test_peer.h).
  friend class StoreAccess;
  friend class StoreTestPeer;
  friend class GenerationWrite;
  sql::Database& database() { return *db_; }

  Store(std::unique_ptr<sql::Database> db, int lock_fd, const Clock& clock)
      : db_(std::move(db)), lock_fd_(lock_fd), clock_(&clock) {}
  // The clock's time as the store records it (utc_time.h).
  std::string Now() const;
  Status InsertIndividual(int64_t run, const NewIndividual& n,
                          const std::string& now);
  Status InsertIndividuals(int64_t run,
                           const std::vector<NewIndividual>& batch);
  // A guidance evaluation's source distances, one row per trial.
  Status InsertTrials(int64_t run, uint64_t id, const v1::EvaluationResult& r);
  // Appends to the run's configuration history.
  Status InsertConfigChange(int64_t run, int from_generation,
                            const v1::RunConfig& config,
                            const std::string& text,
                            const std::string& build_id, const std::string& now,
                            const std::string& reason);

  std::unique_ptr<sql::Database> db_;
  int lock_fd_;  // flock()ed "<path>.lock", -1 for in-memory stores.
  const Clock* clock_;
};

// A generation being written (Store::BeginGeneration): its offspring in
// chunks (Add), then the generation and its members (Commit), all in one
// transaction, so a generation and the offspring it needs appear together
// or not at all. Between calls the caller may do other work (serve its
// workers), but must not use the store otherwise; the store calls nothing
// back. Destroyed without a successful Commit, it rolls back. After a
// failure, every later call returns that failure.
class GenerationWrite {
 public:
  ~GenerationWrite();
  GenerationWrite(const GenerationWrite&) = delete;
  GenerationWrite& operator=(const GenerationWrite&) = delete;

  Status Add(const std::vector<NewIndividual>& offspring);
  // Records `source`'s evaluation as that of offspring `id` (added
  // before, not yet evaluated), whose genome is the same bytes: every
  // column but wall_seconds, worker and isa (NULL: nothing was simulated
  // for it) and evaluated_at, with its trials, and reused_from naming the
  // individual whose simulation it is (source's own reused_from when it
  // has one, else source). True when recorded; false, recording nothing,
  // when `source` has no evaluation or one that says nothing about its
  // genome (status crashed or not_evaluated), or `id` is already
  // evaluated or unknown. The caller vouches that the genomes are equal
  // and that evaluation depends on nothing else (the run's configuration
  // and build being the same).
  Result<bool> Reuse(uint64_t id, uint64_t source);
  Status Commit();

 private:
  friend class Store;
  GenerationWrite(Store* store, int64_t run, int generation,
                  std::vector<uint64_t> members, std::string now)
      : store_(store),
        run_(run),
        generation_(generation),
        members_(std::move(members)),
        now_(std::move(now)) {}
  // Rolls back after a failure; returns it.
  Status Fail(Status status);

  Store* store_;
  int64_t run_;
  int generation_;
  std::vector<uint64_t> members_;
  std::string now_;  // Every row's time stamp.
  bool open_ = true;
  Status failed_;
};

// 16 lowercase hex digits.
std::string Hex64(uint64_t value);

}  // namespace animat::lineage

#endif  // ANIMAT_MASTER_LINEAGE_STORE_H_
