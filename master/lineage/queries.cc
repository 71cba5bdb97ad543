#include "master/lineage/queries.h"

#include <initializer_list>

#include "common/base/text.h"
#include "master/lineage/store_access.h"

namespace animat::lineage {

Result<int64_t> ChooseRun(Store& store, std::optional<int64_t> run) {
  Result<std::vector<RunRow>> runs = store.Runs();
  if (!runs.ok()) return runs.status();
  if (runs->empty()) {
    return Status::NotFound(store.path() + ": holds no run");
  }
  if (!run) return runs->back().run_id;
  for (const RunRow& r : *runs) {
    if (r.run_id == *run) return *run;
  }
  return Status::NotFound(store.path() + ": no run " + std::to_string(*run));
}

Result<Summary> Best(Store& store, int64_t run) {
  Result<sql::Statement> select = StoreAccess::Database(store).Prepare(
      "SELECT b.id, i.generation, i.operators, i.status, i.fitness, i.cells,"
      " i.springs, i.chambers, i.skin_edges, i.spread_major, i.spread_minor,"
      " i.distance, i.energy, i.max_overlap, i.isa"
      " FROM best b JOIN individuals i ON i.run_id = b.run_id AND i.id = b.id"
      " WHERE b.run_id = ?");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  Result<bool> row = select->Step();
  if (!row.ok()) return row.status();
  if (!*row) {
    return Status::NotFound("run " + std::to_string(run) +
                            " has no individual with a fitness yet");
  }
  Summary best;
  best.id = static_cast<uint64_t>(select->Int(0));
  best.generation = static_cast<int>(select->Int(1));
  best.operators = select->Text(2);
  best.status = select->Text(3);
  best.fitness = select->Double(4);
  if (!select->IsNull(6)) {
    v1::BodySummary& body = best.body.emplace();
    body.set_cells(static_cast<int32_t>(select->Int(5)));
    body.set_springs(static_cast<int32_t>(select->Int(6)));
    body.set_chambers(static_cast<int32_t>(select->Int(7)));
    body.set_skin_edges(static_cast<int32_t>(select->Int(8)));
    body.set_spread_major(select->Double(9));
    body.set_spread_minor(select->Double(10));
  }
  if (!select->IsNull(11)) best.swum = select->Double(11);
  if (!select->IsNull(12)) best.energy = select->Double(12);
  if (!select->IsNull(13)) best.max_overlap = select->Double(13);
  if (!select->IsNull(14)) best.isa = select->Text(14);
  Result<sql::Statement> trials = StoreAccess::Database(store).Prepare(
      "SELECT source_distance FROM trials WHERE run_id = ? AND id = ?"
      " ORDER BY trial");
  if (!trials.ok()) return trials.status();
  trials->Bind(1, run).Bind(2, static_cast<int64_t>(best.id));
  Status status = trials->ForEachRow(
      [&] { best.source_distances.push_back(trials->Double(0)); });
  if (!status.ok()) return status;
  return best;
}

Result<std::vector<Summary>> Ancestors(Store& store, int64_t run, uint64_t id) {
  Result<IndividualRow> self = store.Individual(run, id);
  if (!self.ok()) return self.status();
  Result<sql::Statement> select = StoreAccess::Database(store).Prepare(
      "WITH RECURSIVE up (ancestor, distance) AS ("
      "  SELECT parent, 1 FROM parents WHERE run_id = ?1 AND child = ?2"
      "  UNION"
      "  SELECT p.parent, up.distance + 1 FROM up JOIN parents p"
      "    ON p.run_id = ?1 AND p.child = up.ancestor)"
      " SELECT i.id, i.generation, i.operators, i.status, i.fitness,"
      "   MIN(up.distance) AS d"
      " FROM up JOIN individuals i ON i.run_id = ?1 AND i.id = up.ancestor"
      " GROUP BY i.id ORDER BY d, i.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(id));
  std::vector<Summary> out;
  Status status = select->ForEachRow([&] {
    Summary s;
    s.id = static_cast<uint64_t>(select->Int(0));
    s.generation = static_cast<int>(select->Int(1));
    s.operators = select->Text(2);
    s.status = select->IsNull(3) ? "" : select->Text(3);
    if (!select->IsNull(4)) s.fitness = select->Double(4);
    s.distance = static_cast<int>(select->Int(5));
    out.push_back(std::move(s));
  });
  if (!status.ok()) return status;
  return out;
}

Result<std::vector<Score>> Scores(Store& store, int64_t run) {
  Result<sql::Statement> select = StoreAccess::Database(store).Prepare(
      "SELECT b.id, e.status, e.fitness FROM births b LEFT JOIN evaluations e"
      " ON e.run_id = b.run_id AND e.id = b.id WHERE b.run_id = ?"
      " ORDER BY b.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  std::vector<Score> scores;
  Status status = select->ForEachRow([&] {
    Score score;
    score.id = static_cast<uint64_t>(select->Int(0));
    score.evaluated = !select->IsNull(1);
    if (!select->IsNull(2)) score.fitness = select->Double(2);
    scores.push_back(score);
  });
  if (!status.ok()) return status;
  return scores;
}

Result<std::vector<CompletedGeneration>> CompletedGenerations(Store& store,
                                                              int64_t run) {
  Result<sql::Statement> select = StoreAccess::Database(store).Prepare(
      "SELECT generation, evaluated, failed, best_id, best_fitness,"
      " mean_fitness, median_fitness FROM generation_statistics"
      " WHERE run_id = ? AND completed_at IS NOT NULL ORDER BY generation");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  std::vector<CompletedGeneration> out;
  Status status = select->ForEachRow([&] {
    CompletedGeneration g;
    g.generation = static_cast<int>(select->Int(0));
    g.stats.evaluated = static_cast<int>(select->Int(1));
    g.stats.failed = static_cast<int>(select->Int(2));
    if (!select->IsNull(3)) {
      g.stats.best_id = static_cast<uint64_t>(select->Int(3));
    }
    if (!select->IsNull(4)) g.stats.best = select->Double(4);
    if (!select->IsNull(5)) g.stats.mean = select->Double(5);
    if (!select->IsNull(6)) g.stats.median = select->Double(6);
    out.push_back(g);
  });
  if (!status.ok()) return status;
  return out;
}

Result<std::vector<Phenotype>> TopDistinctPhenotypes(Store& store, int64_t run,
                                                     int count) {
  Result<std::vector<CompletedGeneration>> completed =
      CompletedGenerations(store, run);
  if (!completed.ok()) return completed.status();
  if (completed->empty()) {
    return Status::NotFound(store.path() + ": run " + std::to_string(run) +
                            " has completed no generation");
  }
  const int generation = completed->back().generation;
  Result<sql::Statement> select = StoreAccess::Database(store).Prepare(
      "SELECT m.id, e.fitness, e.state_hash FROM members m"
      " JOIN evaluations e ON e.run_id = m.run_id AND e.id = m.id"
      " WHERE m.run_id = ? AND m.generation = ? AND e.status = 'ok'"
      " AND e.fitness IS NOT NULL ORDER BY e.fitness DESC, m.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run).Bind(2, static_cast<int64_t>(generation));
  std::vector<Phenotype> all;  // One per hash, fittest first.
  Status status = select->ForEachRow([&] {
    const std::string hash = select->Text(2);
    for (Phenotype& seen : all) {
      if (!hash.empty() && seen.state_hash == hash) {
        ++seen.members;
        return;
      }
    }
    Phenotype p;
    p.id = static_cast<uint64_t>(select->Int(0));
    p.generation = generation;
    p.fitness = select->Double(1);
    p.state_hash = hash;
    p.members = 1;
    all.push_back(p);
  });
  if (!status.ok()) return status;
  if (count >= 0 && all.size() > static_cast<size_t>(count)) all.resize(count);
  return all;
}

namespace {

// The integers of the one row `sql` gives with ?1 bound to `run`, into
// `columns` in order (NULL reads as 0).
Status ReadCounts(sql::Database& db, const char* sql, int64_t run,
                  std::initializer_list<int64_t*> columns) {
  Result<sql::Statement> select = db.Prepare(sql);
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  Result<bool> row = select->Step();
  if (!row.ok()) return row.status();
  int c = 0;
  for (int64_t* column : columns) {
    *column = *row ? select->Int(c) : 0;
    ++c;
  }
  return Status::Ok();
}

}  // namespace

Result<RunCounts> CountRun(Store& store, int64_t run) {
  sql::Database& db = StoreAccess::Database(store);
  RunCounts n;
  int64_t finished = 0;
  Status status = ReadCounts(
      db, "SELECT SUM(state = 'finished') FROM runs WHERE run_id = ?1", run,
      {&finished});
  n.finished = finished > 0;
  if (status.ok()) {
    status = ReadCounts(
        db,
        "SELECT COUNT(*), COUNT(status), SUM(status = 'ok'), COUNT(fitness),"
        " SUM(worker <> ''), COUNT(evaluated_at),"
        " SUM(length(genome) > 0 AND elements > 0), SUM(generation > 0),"
        " SUM(status IS NULL AND (generation > 0 OR id IN"
        " (SELECT id FROM members WHERE run_id = ?1)))"
        " FROM individuals WHERE run_id = ?1",
        run,
        {&n.individuals, &n.evaluated, &n.ok, &n.with_fitness, &n.with_worker,
         &n.with_evaluation_time, &n.with_genome, &n.offspring,
         &n.needed_unevaluated});
  }
  if (status.ok()) {
    status = ReadCounts(
        db,
        "SELECT COUNT(*) FROM individuals i WHERE i.run_id = ?1"
        " AND i.generation > 0 AND NOT EXISTS (SELECT 1 FROM parents p"
        " WHERE p.run_id = i.run_id AND p.child = i.id)",
        run, {&n.offspring_without_parents});
  }
  if (status.ok()) {
    status = ReadCounts(
        db,
        "SELECT COUNT(*), COUNT(completed_at), SUM(evaluated)"
        " FROM generations WHERE run_id = ?1",
        run,
        {&n.generations, &n.complete_generations, &n.generations_evaluated});
  }
  if (status.ok()) {
    status = ReadCounts(
        db, "SELECT COUNT(*), COUNT(rank) FROM members WHERE run_id = ?1", run,
        {&n.members, &n.ranked_members});
  }
  if (!status.ok()) return status;
  return n;
}

Status ExportAlife(Store& store, int64_t run, std::ostream& out) {
  Result<sql::Statement> select = StoreAccess::Database(store).Prepare(
      "SELECT i.id, i.generation, i.status, i.fitness, i.operators,"
      "  (SELECT group_concat(parent, ',') FROM"
      "     (SELECT parent FROM parents p"
      "      WHERE p.run_id = i.run_id AND p.child = i.id"
      "      ORDER BY position))"
      " FROM individuals i WHERE i.run_id = ? ORDER BY i.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  out << "id,ancestor_list,origin_time,fitness,status,operators\n";
  Status status = select->ForEachRow([&] {
    const std::string parents = select->IsNull(5) ? "" : select->Text(5);
    out << select->Int(0) << ",\"["
        << (parents.empty() ? std::string("NONE") : parents) << "]\","
        << select->Int(1) << ","
        << (select->IsNull(3) ? std::string()
                              : ShortestDouble(select->Double(3)))
        << "," << (select->IsNull(2) ? std::string() : select->Text(2)) << ",\""
        << select->Text(4) << "\"\n";
  });
  if (!status.ok()) return status;
  return out ? Status::Ok() : Status::IoError("write failed");
}

}  // namespace animat::lineage
