#include "master/lineage/queries.h"

#include "common/base/text.h"

namespace animat::lineage {

Result<int64_t> ChooseRun(Store& store, std::optional<int64_t> run) {
  Result<std::vector<RunRow>> runs = store.Runs();
  if (!runs.ok()) return runs.status();
  if (runs->empty()) {
    return Status::NotFound(store.database().path() + ": holds no run");
  }
  if (!run) return runs->back().run_id;
  for (const RunRow& r : *runs) {
    if (r.run_id == *run) return *run;
  }
  return Status::NotFound(store.database().path() + ": no run " +
                          std::to_string(*run));
}

Result<Summary> Best(Store& store, int64_t run) {
  Result<sql::Statement> select = store.database().Prepare(
      "SELECT b.id, i.generation, i.operators, i.status, i.fitness, i.cells,"
      " i.springs, i.chambers, i.skin_edges, i.spread_major, i.spread_minor"
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
  return best;
}

Result<std::vector<Summary>> Ancestors(Store& store, int64_t run, uint64_t id) {
  Result<IndividualRow> self = store.Individual(run, id);
  if (!self.ok()) return self.status();
  Result<sql::Statement> select = store.database().Prepare(
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
  for (;;) {
    Result<bool> row = select->Step();
    if (!row.ok()) return row.status();
    if (!*row) break;
    Summary s;
    s.id = static_cast<uint64_t>(select->Int(0));
    s.generation = static_cast<int>(select->Int(1));
    s.operators = select->Text(2);
    s.status = select->IsNull(3) ? "" : select->Text(3);
    if (!select->IsNull(4)) s.fitness = select->Double(4);
    s.distance = static_cast<int>(select->Int(5));
    out.push_back(std::move(s));
  }
  return out;
}

Status ExportAlife(Store& store, int64_t run, std::ostream& out) {
  Result<sql::Statement> select = store.database().Prepare(
      "SELECT i.id, i.generation, i.status, i.fitness, i.operators,"
      "  (SELECT group_concat(parent, ',') FROM"
      "     (SELECT parent FROM parents p"
      "      WHERE p.run_id = i.run_id AND p.child = i.id"
      "      ORDER BY position))"
      " FROM individuals i WHERE i.run_id = ? ORDER BY i.id");
  if (!select.ok()) return select.status();
  select->Bind(1, run);
  out << "id,ancestor_list,origin_time,fitness,status,operators\n";
  for (;;) {
    Result<bool> row = select->Step();
    if (!row.ok()) return row.status();
    if (!*row) break;
    const std::string parents = select->IsNull(5) ? "" : select->Text(5);
    out << select->Int(0) << ",\"["
        << (parents.empty() ? std::string("NONE") : parents) << "]\","
        << select->Int(1) << ","
        << (select->IsNull(3) ? std::string()
                              : ShortestDouble(select->Double(3)))
        << "," << (select->IsNull(2) ? std::string() : select->Text(2)) << ",\""
        << select->Text(4) << "\"\n";
  }
  return out ? Status::Ok() : Status::IoError("write failed");
}

}  // namespace animat::lineage
