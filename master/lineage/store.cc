#include "master/lineage/store.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <google/protobuf/text_format.h>

#include "common/base/text.h"
#include "common/base/utc_time.h"
#include "common/protocol/genome_wire.h"
#include "master/lineage/schema.h"

namespace animat::lineage {
namespace {

std::string Join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& part : parts) {
    if (!out.empty()) out += ",";
    out += part;
  }
  return out;
}

// Runs `body` inside BEGIN IMMEDIATE ... COMMIT, rolling back on failure.
template <typename Body>
Status InTransaction(sql::Database& db, Body body) {
  Status status = db.Execute("BEGIN IMMEDIATE");
  if (!status.ok()) return status;
  status = body();
  if (status.ok()) status = db.Execute("COMMIT");
  if (!status.ok()) (void)db.Execute("ROLLBACK");
  return status;
}

}  // namespace

std::string Store::Now() const { return FormatUtc(clock_->Utc()); }

std::string Hex64(uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx",
                static_cast<unsigned long long>(value));
  return text;
}

Result<std::unique_ptr<Store>> Store::Open(const std::string& path,
                                           const Clock& clock) {
  int lock_fd = -1;
  const bool in_memory = path.empty() || path == ":memory:";
  if (!in_memory) {
    // What is wrong with the store's own path, before its lock file's.
    Status usable = sql::CheckDatabasePath(path, /*read_only=*/false);
    if (!usable.ok()) return usable;
    const std::string lock_path = path + ".lock";
    lock_fd = open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd < 0) {
      return Status::IoError(path + ": cannot open its lock file " + lock_path +
                             ": " + std::strerror(errno));
    }
    if (flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
      close(lock_fd);
      return Status::IoError(path + ": in use by another master (" + lock_path +
                             " is locked); only one master may run on a store");
    }
  }
  Result<std::unique_ptr<sql::Database>> db = sql::Database::Open(path);
  if (!db.ok()) {
    if (lock_fd >= 0) close(lock_fd);
    return db.status();
  }
  // WAL: readers (queries, exports) never block the master. synchronous
  // NORMAL: a commit survives a crash of the master (kill -9) but not
  // necessarily a power loss or an OS crash, which may roll the store
  // back to an earlier commit (never corrupt it); a resume then makes and
  // evaluates the lost individuals again, to the same bits. FULL would
  // fsync at every commit, a few ms each (docs/benchmarks.md, "Master
  // throughput"). A 64 MiB page cache holds a generation's rows; a
  // checkpoint every 16384 pages (64 MiB of WAL) copies pages written
  // several times once.
  Status status = (*db)->Execute(
      "PRAGMA journal_mode = WAL; PRAGMA synchronous = NORMAL;"
      "PRAGMA foreign_keys = ON; PRAGMA cache_size = -65536;"
      "PRAGMA wal_autocheckpoint = 16384;");
  if (status.ok()) status = Migrate(**db);
  if (!status.ok()) {
    if (lock_fd >= 0) close(lock_fd);
    return status;
  }
  return std::unique_ptr<Store>(
      new Store(std::move(db).value(), lock_fd, clock));
}

Result<std::unique_ptr<Store>> Store::OpenForQueries(const std::string& path) {
  Status usable = sql::CheckDatabasePath(path, /*read_only=*/true);
  if (usable.code() == StatusCode::kNotFound) {
    return Status::NotFound(path + ": no such lineage store");
  }
  if (!usable.ok()) return usable;
  Result<std::unique_ptr<sql::Database>> db =
      sql::Database::Open(path, /*read_only=*/true);
  if (!db.ok()) return db.status();
  Result<int> version = SchemaVersion(**db);
  if (!version.ok()) return version.status();
  const int found = *version;
  if (found != kSchemaVersion) {
    return Status::InvalidArgument(
        path + ": lineage schema version " + std::to_string(found) +
        ", this build reads version " + std::to_string(kSchemaVersion) +
        (found < kSchemaVersion
             ? " (`animat lineage upgrade --db " + path +
                   "` upgrades it, as does a master of this build)"
             : std::string(" (written by a newer animat)")));
  }
  return std::unique_ptr<Store>(
      new Store(std::move(db).value(), -1, RealClock()));
}

Result<int> Store::Upgrade(const std::string& path) {
  // Open would create a missing store: a mistyped path is an error.
  if (access(path.c_str(), F_OK) != 0) {
    return Status::NotFound(path + ": no such lineage store");
  }
  int before = -1;
  {
    Result<std::unique_ptr<sql::Database>> db =
        sql::Database::Open(path, /*read_only=*/true);
    if (!db.ok()) return db.status();
    Result<int> version = SchemaVersion(**db);
    if (!version.ok()) return version.status();
    before = *version;
  }
  if (before == 0) {
    return Status::InvalidArgument(path +
                                   ": not a lineage store (schema version 0)");
  }
  // Takes the store's lock (refused while a master runs on it) and runs
  // the missing migrations, each in one transaction.
  Result<std::unique_ptr<Store>> store = Open(path);
  if (!store.ok()) return store.status();
  return before;
}

Store::~Store() {
  db_.reset();
  if (lock_fd_ >= 0) close(lock_fd_);  // Releases the lock.
}

Result<int64_t> Store::CreateRun(uint64_t seed, const v1::RunConfig& config,
                                 const std::string& build_id) {
  std::string text;
  google::protobuf::TextFormat::PrintToString(config, &text);
  const std::string now = Now();
  int64_t run = 0;
  Status status = InTransaction(*db_, [&]() -> Status {
    Result<sql::Statement> insert = db_->Cached(
        "INSERT INTO runs (seed, config, config_text, config_hash, build_id,"
        " started_at, state) VALUES (?, ?, ?, ?, ?, ?, 'running')");
    if (!insert.ok()) return insert.status();
    insert->Bind(1, static_cast<int64_t>(seed))
        .BindBlob(2, config.SerializeAsString())
        .Bind(3, text)
        .Bind(4, Hex64(protocol::MessageHash(config)))
        .Bind(5, build_id)
        .Bind(6, now);
    Status inserted = insert->Run();
    if (!inserted.ok()) return inserted;
    run = db_->last_insert_rowid();
    return InsertConfigChange(run, 0, config, text, build_id, now, "started");
  });
  if (!status.ok()) return status;
  return run;
}

Status Store::InsertConfigChange(int64_t run, int from_generation,
                                 const v1::RunConfig& config,
                                 const std::string& text,
                                 const std::string& build_id,
                                 const std::string& now,
                                 const std::string& reason) {
  Result<sql::Statement> insert = db_->Cached(
      "INSERT INTO run_configs (run_id, change, from_generation, config,"
      " config_text, config_hash, build_id, recorded_at, reason)"
      " SELECT ?1, COALESCE(MAX(change) + 1, 0), ?2, ?3, ?4, ?5, ?6, ?7, ?8"
      " FROM run_configs WHERE run_id = ?1");
  if (!insert.ok()) return insert.status();
  insert->Bind(1, run)
      .Bind(2, static_cast<int64_t>(from_generation))
      .BindBlob(3, config.SerializeAsString())
      .Bind(4, text)
      .Bind(5, Hex64(protocol::MessageHash(config)))
      .Bind(6, build_id)
      .Bind(7, now)
      .Bind(8, reason);
  return insert->Run();
}

Result<std::vector<RunRow>> Store::Runs() {
  Result<sql::Statement> select = db_->Cached(
      "SELECT run_id, seed, config, config_hash, build_id, started_at,"
      " ended_at, state FROM runs ORDER BY run_id");
  if (!select.ok()) return select.status();
  std::vector<RunRow> runs;
  Status status = select->ForEachRow([&]() -> Status {
    RunRow run;
    run.run_id = select->Int(0);
    run.seed = static_cast<uint64_t>(select->Int(1));
    if (!run.config.ParseFromString(select->Blob(2))) {
      return Status::InvalidArgument(db_->path() + ": run " +
                                     std::to_string(run.run_id) +
                                     " has an unreadable configuration");
    }
    run.config_hash = select->Text(3);
    run.build_id = select->Text(4);
    run.started_at = select->Text(5);
    run.ended_at = select->IsNull(6) ? "" : select->Text(6);
    run.state = select->Text(7);
    runs.push_back(std::move(run));
    return Status::Ok();
  });
  if (!status.ok()) return status;
  return runs;
}

Status Store::FinishRun(int64_t run) {
  Result<sql::Statement> update = db_->Cached(
      "UPDATE runs SET state = 'finished', ended_at = ? WHERE run_id = ?");
  if (!update.ok()) return update.status();
  update->Bind(1, Now()).Bind(2, run);
  return update->Run();
}

Status Store::UpdateRunConfig(int64_t run, int from_generation,
                              const v1::RunConfig& config,
                              const std::string& build_id,
                              const std::string& reason) {
  std::string text;
  google::protobuf::TextFormat::PrintToString(config, &text);
  return InTransaction(*db_, [&]() -> Status {
    Result<sql::Statement> update = db_->Cached(
        "UPDATE runs SET seed = ?, config = ?, config_text = ?,"
        " config_hash = ?, build_id = ?, state = 'running', ended_at = NULL"
        " WHERE run_id = ?");
    if (!update.ok()) return update.status();
    update->Bind(1, static_cast<int64_t>(config.evolution().seed()))
        .BindBlob(2, config.SerializeAsString())
        .Bind(3, text)
        .Bind(4, Hex64(protocol::MessageHash(config)))
        .Bind(5, build_id)
        .Bind(6, run);
    Status status = update->Run();
    if (!status.ok()) return status;
    return InsertConfigChange(run, from_generation, config, text, build_id,
                              Now(), reason);
  });
}

Result<std::vector<RunConfigRow>> Store::ConfigHistory(int64_t run) {
  Result<sql::Statement> select = db_->Cached(
      "SELECT change, from_generation, config, config_hash, build_id,"
      " recorded_at, reason FROM run_configs WHERE run_id = ?"
      " ORDER BY change");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  std::vector<RunConfigRow> history;
  Status status = select->ForEachRow([&]() -> Status {
    RunConfigRow row;
    row.change = static_cast<int>(select->Int(0));
    row.from_generation = static_cast<int>(select->Int(1));
    if (!row.config.ParseFromString(select->Blob(2))) {
      return Status::InvalidArgument(db_->path() + ": configuration " +
                                     std::to_string(row.change) + " of run " +
                                     std::to_string(run) + " is unreadable");
    }
    row.config_hash = select->Text(3);
    row.build_id = select->Text(4);
    row.recorded_at = select->Text(5);
    row.reason = select->Text(6);
    history.push_back(std::move(row));
    return Status::Ok();
  });
  if (!status.ok()) return status;
  return history;
}

Status Store::InsertIndividual(int64_t run, const NewIndividual& n,
                               const std::string& now) {
  Result<sql::Statement> individual = db_->Cached(
      "INSERT INTO births (run_id, id, generation, operators, genome,"
      " genome_hash, elements, created_at) VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  if (!individual.ok()) return individual.status();
  Result<sql::Statement> parent = db_->Cached(
      "INSERT INTO parents (run_id, child, position, parent)"
      " VALUES (?, ?, ?, ?)");
  if (!parent.ok()) return parent.status();
  const protocol::SerializedGenome serialized =
      n.serialized ? protocol::SerializedGenome()
                   : protocol::SerializeGenome(n.genome);
  const protocol::SerializedGenome& genome =
      n.serialized ? *n.serialized : serialized;
  individual->Bind(1, run)
      .Bind(2, static_cast<int64_t>(n.id))
      .Bind(3, static_cast<int64_t>(n.generation))
      .Bind(4, Join(n.operators))
      .BindBlob(5, genome.bytes)
      .Bind(6, Hex64(genome.hash))
      .Bind(7, static_cast<int64_t>(genome.elements))
      .Bind(8, now);
  Status status = individual->Run();
  if (!status.ok()) return status;
  for (size_t k = 0; k < n.parents.size(); ++k) {
    parent->Bind(1, run)
        .Bind(2, static_cast<int64_t>(n.id))
        .Bind(3, static_cast<int64_t>(k))
        .Bind(4, static_cast<int64_t>(n.parents[k]));
    status = parent->Run();
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

Status Store::InsertIndividuals(int64_t run,
                                const std::vector<NewIndividual>& batch) {
  const std::string now = Now();
  for (const NewIndividual& n : batch) {
    Status status = InsertIndividual(run, n, now);
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

Status Store::AddIndividuals(int64_t run,
                             const std::vector<NewIndividual>& batch) {
  return InTransaction(*db_, [&] { return InsertIndividuals(run, batch); });
}

Status Store::InsertTrials(int64_t run, uint64_t id,
                           const v1::EvaluationResult& r) {
  Result<sql::Statement> insert = db_->Cached(
      "INSERT INTO trials (run_id, id, trial, source_distance)"
      " VALUES (?1, ?2, ?3, ?4)");
  if (!insert.ok()) return insert.status();
  for (int k = 0; k < r.source_distances_size(); ++k) {
    insert->Bind(1, run)
        .Bind(2, static_cast<int64_t>(id))
        .Bind(3, static_cast<int64_t>(k))
        .Bind(4, r.source_distances(k));
    Status status = insert->Run();
    if (!status.ok()) return status;
  }
  return Status::Ok();
}

Status Store::RecordEvaluations(int64_t run,
                                const std::vector<Evaluation>& batch) {
  return InTransaction(*db_, [&]() -> Status {
    // The first evaluation of an individual is kept (OR IGNORE); one of
    // an individual never made is not recorded (EXISTS).
    Result<sql::Statement> insert = db_->Cached(
        "INSERT OR IGNORE INTO evaluations (run_id, id, status, reason,"
        " fitness, cells, steps, wall_seconds, worker, state_hash,"
        " evaluated_at, springs, chambers, skin_edges, spread_major,"
        " spread_minor, distance, energy, max_overlap, isa) SELECT ?1, ?2,"
        " ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15, ?16,"
        " ?17, ?18, ?19, ?20"
        " WHERE EXISTS (SELECT 1 FROM births WHERE run_id = ?1 AND id = ?2)");
    if (!insert.ok()) return insert.status();
    const std::string now = Now();
    for (const Evaluation& e : batch) {
      const v1::EvaluationResult& r = e.result;
      const std::string status =
          AsciiLowerCase(v1::EvaluationResult::Status_Name(r.status()));
      insert->Bind(1, run)
          .Bind(2, static_cast<int64_t>(e.id))
          .Bind(3, status)
          .Bind(4, r.reason())
          .Bind(5, r.has_fitness() ? std::optional<double>(r.fitness())
                                   : std::nullopt)
          .Bind(6, static_cast<int64_t>(r.cells()))
          .Bind(7, static_cast<int64_t>(r.steps()))
          .Bind(8, e.wall_seconds)
          .Bind(9, e.worker)
          .Bind(10, Hex64(r.state_hash()))
          .Bind(11, now);
      // The body, when the evaluation built one; NULL otherwise.
      if (r.has_body()) {
        const v1::BodySummary& b = r.body();
        insert->Bind(12, static_cast<int64_t>(b.springs()))
            .Bind(13, static_cast<int64_t>(b.chambers()))
            .Bind(14, static_cast<int64_t>(b.skin_edges()))
            .Bind(15, b.spread_major())
            .Bind(16, b.spread_minor());
      } else {
        for (int column = 12; column <= 16; ++column) insert->BindNull(column);
      }
      // The distance, the energy and the deepest unjoined overlap, when
      // the evaluation is ok.
      const auto optional = [](bool has, double value) {
        return has ? std::optional<double>(value) : std::nullopt;
      };
      insert->Bind(17, optional(r.has_distance(), r.distance()))
          .Bind(18, optional(r.has_energy(), r.energy()))
          .Bind(19, optional(r.has_max_overlap(), r.max_overlap()));
      if (e.isa.empty()) {
        insert->BindNull(20);
      } else {
        insert->Bind(20, e.isa);
      }
      Status s = insert->Run();
      if (!s.ok()) return s;
      // A guidance evaluation's trials, kept with the evaluation they came
      // with: only when it was the one recorded.
      if (r.source_distances_size() > 0 && db_->changes() == 1) {
        s = InsertTrials(run, e.id, r);
        if (!s.ok()) return s;
      }
    }
    return Status::Ok();
  });
}

namespace {

Result<std::vector<uint64_t>> ParentsOf(sql::Database& db, int64_t run,
                                        uint64_t id) {
  Result<sql::Statement> select = db.Cached(
      "SELECT parent FROM parents WHERE run_id = ? AND child = ?"
      " ORDER BY position");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(id));
  std::vector<uint64_t> parents;
  Status status = select->ForEachRow(
      [&] { parents.push_back(static_cast<uint64_t>(select->Int(0))); });
  if (!status.ok()) return status;
  return parents;
}

constexpr const char* kIndividualColumns =
    "SELECT id, generation, operators, genome, status, reason, fitness"
    " FROM individuals";

Status ReadIndividual(sql::Database& db, const sql::Statement& row, int64_t run,
                      IndividualRow* out) {
  out->id = static_cast<uint64_t>(row.Int(0));
  out->generation = static_cast<int>(row.Int(1));
  out->operators = row.Text(2);
  if (!out->genome.ParseFromString(row.Blob(3))) {
    return Status::InvalidArgument(db.path() + ": individual " +
                                   std::to_string(out->id) +
                                   " has an unreadable genome");
  }
  out->evaluated = !row.IsNull(4);
  out->status = out->evaluated ? row.Text(4) : "";
  out->reason = row.IsNull(5) ? "" : row.Text(5);
  if (!row.IsNull(6)) out->fitness = row.Double(6);
  Result<std::vector<uint64_t>> parents = ParentsOf(db, run, out->id);
  if (!parents.ok()) return parents.status();
  out->parents = std::move(parents).value();
  return Status::Ok();
}

}  // namespace

Result<IndividualRow> Store::Individual(int64_t run, uint64_t id) {
  Result<sql::Statement> select = db_->Cached(std::string(kIndividualColumns) +
                                              " WHERE run_id = ? AND id = ?");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(id));
  Result<bool> row = select->Step();
  if (!row.ok()) return row.status();
  if (!*row) {
    return Status::NotFound("no individual " + std::to_string(id) + " in run " +
                            std::to_string(run));
  }
  IndividualRow out;
  Status status = ReadIndividual(*db_, *select, run, &out);
  if (!status.ok()) return status;
  return out;
}

Result<std::vector<IndividualRow>> Store::IndividualsOf(int64_t run,
                                                        int generation) {
  Result<sql::Statement> select =
      db_->Cached(std::string(kIndividualColumns) +
                  " WHERE run_id = ? AND generation = ? ORDER BY id");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
  std::vector<IndividualRow> out;
  Status status = select->ForEachRow([&]() -> Status {
    IndividualRow individual;
    Status read = ReadIndividual(*db_, *select, run, &individual);
    if (!read.ok()) return read;
    out.push_back(std::move(individual));
    return Status::Ok();
  });
  if (!status.ok()) return status;
  return out;
}

namespace {

Result<std::vector<Score>> ReadScores(sql::Statement& select) {
  std::vector<Score> scores;
  Status status = select.ForEachRow([&] {
    Score score;
    score.id = static_cast<uint64_t>(select.Int(0));
    score.evaluated = !select.IsNull(1);
    if (!select.IsNull(2)) score.fitness = select.Double(2);
    scores.push_back(score);
  });
  if (!status.ok()) return status;
  return scores;
}

}  // namespace

Result<std::vector<Score>> Store::ScoresOf(int64_t run, int generation) {
  Result<sql::Statement> select = db_->Cached(
      "SELECT b.id, e.status, e.fitness FROM births b LEFT JOIN evaluations e"
      " ON e.run_id = b.run_id AND e.id = b.id"
      " WHERE b.run_id = ? AND b.generation = ? ORDER BY b.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
  return ReadScores(*select);
}

Result<std::vector<Score>> Store::MemberScores(int64_t run, int generation) {
  Result<sql::Statement> select = db_->Cached(
      "SELECT m.id, e.status, e.fitness FROM members m LEFT JOIN evaluations e"
      " ON e.run_id = m.run_id AND e.id = m.id"
      " WHERE m.run_id = ? AND m.generation = ? ORDER BY m.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
  return ReadScores(*select);
}

Result<std::vector<MemberGenome>> Store::MemberGenomes(int64_t run,
                                                       int generation) {
  Result<sql::Statement> select = db_->Cached(
      "SELECT m.id, e.fitness, b.genome FROM members m"
      " JOIN births b ON b.run_id = m.run_id AND b.id = m.id"
      " LEFT JOIN evaluations e ON e.run_id = m.run_id AND e.id = m.id"
      " WHERE m.run_id = ? AND m.generation = ? ORDER BY m.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
  std::vector<MemberGenome> members;
  Status status = select->ForEachRow([&]() -> Status {
    MemberGenome member;
    member.id = static_cast<uint64_t>(select->Int(0));
    if (!select->IsNull(1)) member.fitness = select->Double(1);
    if (!member.genome.ParseFromString(select->Blob(2))) {
      return Status::InvalidArgument(db_->path() + ": individual " +
                                     std::to_string(member.id) +
                                     " has an unreadable genome");
    }
    members.push_back(std::move(member));
    return Status::Ok();
  });
  if (!status.ok()) return status;
  return members;
}

Result<std::vector<uint64_t>> Store::Unevaluated(int64_t run) {
  Result<sql::Statement> select = db_->Cached(
      "SELECT b.id FROM births b WHERE b.run_id = ?1 AND NOT EXISTS"
      " (SELECT 1 FROM evaluations e WHERE e.run_id = ?1 AND e.id = b.id)"
      " ORDER BY b.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  std::vector<uint64_t> ids;
  Status status = select->ForEachRow(
      [&] { ids.push_back(static_cast<uint64_t>(select->Int(0))); });
  if (!status.ok()) return status;
  return ids;
}

Result<uint64_t> Store::NextId(int64_t run) {
  Result<sql::Statement> select =
      db_->Cached("SELECT MAX(id) FROM births WHERE run_id = ?");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  Result<bool> row = select->Step();
  if (!row.ok()) return row.status();
  if (!*row || select->IsNull(0)) return uint64_t{0};
  return static_cast<uint64_t>(select->Int(0)) + 1;
}

Status Store::AddGeneration(int64_t run, int generation,
                            const std::vector<uint64_t>& members,
                            const std::vector<NewIndividual>& individuals) {
  Result<std::unique_ptr<GenerationWrite>> write =
      BeginGeneration(run, generation, members);
  if (!write.ok()) return write.status();
  Status status = (*write)->Add(individuals);
  if (!status.ok()) return status;
  return (*write)->Commit();
}

Result<std::unique_ptr<GenerationWrite>> Store::BeginGeneration(
    int64_t run, int generation, std::vector<uint64_t> members) {
  Status status = db_->Execute("BEGIN IMMEDIATE");
  if (!status.ok()) return status;
  return std::unique_ptr<GenerationWrite>(
      new GenerationWrite(this, run, generation, std::move(members), Now()));
}

GenerationWrite::~GenerationWrite() {
  if (open_) (void)store_->db_->Execute("ROLLBACK");
}

Status GenerationWrite::Fail(Status status) {
  if (open_) (void)store_->db_->Execute("ROLLBACK");
  open_ = false;
  failed_ = status;
  return status;
}

Status GenerationWrite::Add(const std::vector<NewIndividual>& offspring) {
  if (!open_) return failed_;
  for (const NewIndividual& n : offspring) {
    Status status = store_->InsertIndividual(run_, n, now_);
    if (!status.ok()) return Fail(status);
  }
  return Status::Ok();
}

Result<bool> GenerationWrite::Reuse(uint64_t id, uint64_t source) {
  if (!open_) return failed_;
  sql::Database& db = *store_->db_;
  Result<sql::Statement> copy = db.Cached(
      "INSERT OR IGNORE INTO evaluations (run_id, id, status, reason,"
      " fitness, cells, steps, wall_seconds, worker, state_hash,"
      " evaluated_at, springs, chambers, skin_edges, spread_major,"
      " spread_minor, distance, energy, max_overlap, isa, reused_from)"
      " SELECT run_id, ?2, status, reason, fitness, cells, steps, NULL, NULL,"
      " state_hash, ?4, springs, chambers, skin_edges, spread_major,"
      " spread_minor, distance, energy, max_overlap, NULL,"
      " COALESCE(reused_from, id)"
      " FROM evaluations WHERE run_id = ?1 AND id = ?3"
      " AND status NOT IN ('crashed', 'not_evaluated')"
      " AND EXISTS (SELECT 1 FROM births WHERE run_id = ?1 AND id = ?2)");
  if (!copy.ok()) return Fail(copy.status());
  copy->Bind(1, run_)
      .Bind(2, static_cast<int64_t>(id))
      .Bind(3, static_cast<int64_t>(source))
      .Bind(4, now_);
  Status status = copy->Run();
  if (!status.ok()) return Fail(status);
  if (db.changes() != 1) return false;
  Result<sql::Statement> trials = db.Cached(
      "INSERT INTO trials (run_id, id, trial, source_distance)"
      " SELECT run_id, ?2, trial, source_distance FROM trials"
      " WHERE run_id = ?1 AND id = ?3 ORDER BY trial");
  if (!trials.ok()) return Fail(trials.status());
  trials->Bind(1, run_)
      .Bind(2, static_cast<int64_t>(id))
      .Bind(3, static_cast<int64_t>(source));
  status = trials->Run();
  if (!status.ok()) return Fail(status);
  return true;
}

Status GenerationWrite::Commit() {
  if (!open_) return failed_;
  sql::Database& db = *store_->db_;
  Result<sql::Statement> insert = db.Cached(
      "INSERT INTO generations (run_id, generation, size, created_at)"
      " VALUES (?, ?, ?, ?)");
  if (!insert.ok()) return Fail(insert.status());
  insert->Bind(1, run_)
      .Bind(2, static_cast<int64_t>(generation_))
      .Bind(3, static_cast<int64_t>(members_.size()))
      .Bind(4, now_);
  Status status = insert->Run();
  if (!status.ok()) return Fail(status);
  Result<sql::Statement> member = db.Cached(
      "INSERT INTO members (run_id, generation, id) VALUES (?, ?, ?)");
  if (!member.ok()) return Fail(member.status());
  for (uint64_t id : members_) {
    member->Bind(1, run_)
        .Bind(2, static_cast<int64_t>(generation_))
        .Bind(3, static_cast<int64_t>(id));
    status = member->Run();
    if (!status.ok()) return Fail(status);
  }
  status = db.Execute("COMMIT");
  if (!status.ok()) return Fail(status);
  open_ = false;
  failed_ = Status::Internal("generation " + std::to_string(generation_) +
                             " already committed");
  return Status::Ok();
}

Status Store::CompleteGeneration(int64_t run, int generation,
                                 const std::vector<uint64_t>& ranked,
                                 const GenerationStats& stats) {
  return InTransaction(*db_, [&]() -> Status {
    // The ranks go into a temporary table keyed by id (one statement, from
    // a JSON array whose index is the rank), then into members in one pass
    // over the generation: a statement per member cost twice as much.
    Status status = db_->Execute(
        "CREATE TEMP TABLE IF NOT EXISTS ranking"
        " (id INTEGER PRIMARY KEY, rank INTEGER NOT NULL);"
        "DELETE FROM temp.ranking;");
    if (!status.ok()) return status;
    std::string ids = "[";
    for (size_t r = 0; r < ranked.size(); ++r) {
      if (r > 0) ids += ',';
      ids += std::to_string(ranked[r]);
    }
    ids += ']';
    Result<sql::Statement> fill = db_->Cached(
        "INSERT INTO temp.ranking (id, rank) SELECT value, key FROM "
        "json_each(?)");
    if (!fill.ok()) return fill.status();
    fill->Bind(1, ids);
    status = fill->Run();
    if (!status.ok()) return status;
    Result<sql::Statement> rank = db_->Cached(
        "UPDATE members SET rank = (SELECT r.rank FROM temp.ranking r"
        " WHERE r.id = members.id) WHERE run_id = ? AND generation = ?");
    if (!rank.ok()) return rank.status();
    rank->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
    status = rank->Run();
    if (!status.ok()) return status;
    Result<sql::Statement> update = db_->Cached(
        "UPDATE generations SET completed_at = ?, evaluated = ?, failed = ?,"
        " best_id = ?, best_fitness = ?, mean_fitness = ?,"
        " median_fitness = ? WHERE run_id = ? AND generation = ?");
    if (!update.ok()) return update.status();
    update->Bind(1, Now())
        .Bind(2, static_cast<int64_t>(stats.evaluated))
        .Bind(3, static_cast<int64_t>(stats.failed));
    if (stats.best_id) {
      update->Bind(4, static_cast<int64_t>(*stats.best_id));
    } else {
      update->BindNull(4);
    }
    update->Bind(5, stats.best)
        .Bind(6, stats.mean)
        .Bind(7, stats.median)
        .Bind(8, run)
        .Bind(9, static_cast<int64_t>(generation));
    return update->Run();
  });
}

Result<GenerationRow> Store::Generation(int64_t run, int generation) {
  Result<sql::Statement> select = db_->Cached(
      "SELECT size, completed_at IS NOT NULL FROM generations"
      " WHERE run_id = ? AND generation = ?");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
  Result<bool> row = select->Step();
  if (!row.ok()) return row.status();
  if (!*row) {
    return Status::NotFound("no generation " + std::to_string(generation) +
                            " in run " + std::to_string(run));
  }
  GenerationRow out;
  out.generation = generation;
  out.size = static_cast<int>(select->Int(0));
  out.complete = select->Int(1) != 0;
  Result<sql::Statement> members = db_->Cached(
      "SELECT id FROM members WHERE run_id = ? AND generation = ?"
      " ORDER BY rank, id");
  if (!members.ok()) return members.status();
  members->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
  Status status = members->ForEachRow(
      [&] { out.members.push_back(static_cast<uint64_t>(members->Int(0))); });
  if (!status.ok()) return status;
  return out;
}

Result<std::optional<GenerationRow>> Store::LatestGenerationHead(int64_t run) {
  Result<sql::Statement> select = db_->Cached(
      "SELECT generation, size, completed_at IS NOT NULL FROM generations"
      " WHERE run_id = ? ORDER BY generation DESC LIMIT 1");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  Result<bool> row = select->Step();
  if (!row.ok()) return row.status();
  if (!*row) return std::optional<GenerationRow>();
  GenerationRow out;
  out.generation = static_cast<int>(select->Int(0));
  out.size = static_cast<int>(select->Int(1));
  out.complete = select->Int(2) != 0;
  return std::optional<GenerationRow>(std::move(out));
}

Result<std::optional<GenerationRow>> Store::LatestGeneration(int64_t run) {
  Result<sql::Statement> select =
      db_->Cached("SELECT MAX(generation) FROM generations WHERE run_id = ?");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  Result<bool> row = select->Step();
  if (!row.ok()) return row.status();
  if (!*row || select->IsNull(0)) return std::optional<GenerationRow>();
  Result<GenerationRow> generation =
      Generation(run, static_cast<int>(select->Int(0)));
  if (!generation.ok()) return generation.status();
  return std::optional<GenerationRow>(std::move(generation).value());
}

}  // namespace animat::lineage
