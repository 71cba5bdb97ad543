#include "master/lineage/schema.h"

#include <string>

namespace animat::lineage {
namespace {

// Migration k brings a store from version k to k + 1. Never edit a
// migration that has shipped: append a new one.
constexpr const char* kMigrations[] = {
    // 0 -> 1: the first schema.
    R"sql(
CREATE TABLE runs (
  run_id       INTEGER PRIMARY KEY,
  seed         INTEGER NOT NULL,
  config       BLOB    NOT NULL,  -- animat.v1.RunConfig, binary protobuf
  config_text  TEXT    NOT NULL,  -- the same in proto text format
  config_hash  TEXT    NOT NULL,  -- 16 hex digits
  build_id     TEXT    NOT NULL,  -- the simulator build that evaluates
  started_at   TEXT    NOT NULL,  -- UTC, ISO 8601
  ended_at     TEXT,
  state        TEXT    NOT NULL CHECK (state IN ('running', 'finished'))
);

CREATE TABLE individuals (
  run_id       INTEGER NOT NULL REFERENCES runs (run_id),
  id           INTEGER NOT NULL,
  generation   INTEGER NOT NULL,  -- the generation it was made for
  operators    TEXT    NOT NULL,  -- comma-separated, e.g. 'crossover,sign'
  genome       BLOB    NOT NULL,  -- animat.v1.Genome, binary protobuf
  genome_hash  TEXT    NOT NULL,  -- 16 hex digits
  elements     INTEGER NOT NULL,
  created_at   TEXT    NOT NULL,
  -- The evaluation: all NULL until it comes back.
  status       TEXT,              -- 'ok', 'non_viable', ...
  reason       TEXT,              -- why, when status is not 'ok'
  fitness      REAL,              -- only when status = 'ok'
  cells        INTEGER,
  steps        INTEGER,
  wall_seconds REAL,
  worker       TEXT,              -- host:pid
  state_hash   TEXT,              -- 16 hex digits
  evaluated_at TEXT,
  PRIMARY KEY (run_id, id)
) WITHOUT ROWID;
CREATE INDEX individuals_to_evaluate ON individuals (run_id, id)
  WHERE status IS NULL;

CREATE TABLE parents (
  run_id       INTEGER NOT NULL,
  child        INTEGER NOT NULL,
  position     INTEGER NOT NULL,  -- 0: the first (or only) parent
  parent       INTEGER NOT NULL,
  PRIMARY KEY (run_id, child, position)
) WITHOUT ROWID;
CREATE INDEX parents_by_parent ON parents (run_id, parent);

CREATE TABLE generations (
  run_id         INTEGER NOT NULL REFERENCES runs (run_id),
  generation     INTEGER NOT NULL,
  size           INTEGER NOT NULL,
  created_at     TEXT    NOT NULL,
  completed_at   TEXT,             -- NULL while evaluations are pending
  evaluated      INTEGER,          -- members with status 'ok'
  failed         INTEGER,          -- members with another status
  best_id        INTEGER,
  best_fitness   REAL,
  mean_fitness   REAL,             -- over members with status 'ok'
  median_fitness REAL,
  PRIMARY KEY (run_id, generation)
) WITHOUT ROWID;

CREATE TABLE members (
  run_id       INTEGER NOT NULL,
  generation   INTEGER NOT NULL,
  id           INTEGER NOT NULL,
  rank         INTEGER,           -- 0 = best; set when the generation completes
  PRIMARY KEY (run_id, generation, id)
) WITHOUT ROWID;

CREATE VIEW generation_statistics AS
  SELECT run_id, generation, size, evaluated, failed, best_id, best_fitness,
         mean_fitness, median_fitness, created_at, completed_at
  FROM generations;

CREATE VIEW best AS
  SELECT run_id, id, generation, fitness FROM (
    SELECT run_id, id, generation, fitness,
           ROW_NUMBER() OVER (PARTITION BY run_id
                              ORDER BY fitness DESC, id) AS place
    FROM individuals WHERE status = 'ok')
  WHERE place = 1;

CREATE VIEW ancestry AS
  WITH RECURSIVE up (run_id, descendant, ancestor, distance) AS (
    SELECT run_id, child, parent, 1 FROM parents
    UNION
    SELECT up.run_id, up.descendant, p.parent, up.distance + 1
    FROM up JOIN parents p ON p.run_id = up.run_id AND p.child = up.ancestor)
  SELECT run_id, descendant, ancestor, MIN(distance) AS distance
  FROM up GROUP BY run_id, descendant, ancestor;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
    // 1 -> 2: individuals becomes a rowid table. In a WITHOUT ROWID table
    // a row of about 1 kB (the genome) spills into an overflow page of its
    // own, so each individual took 5 kB and reading any column of a run
    // read them all. Generations get a covering index for the run loop.
    R"sql(
DROP VIEW best;
DROP VIEW line_of_descent;
CREATE TABLE individuals_v2 (
  run_id       INTEGER NOT NULL REFERENCES runs (run_id),
  id           INTEGER NOT NULL,
  generation   INTEGER NOT NULL,
  operators    TEXT    NOT NULL,
  genome       BLOB    NOT NULL,
  genome_hash  TEXT    NOT NULL,
  elements     INTEGER NOT NULL,
  created_at   TEXT    NOT NULL,
  status       TEXT,
  reason       TEXT,
  fitness      REAL,
  cells        INTEGER,
  steps        INTEGER,
  wall_seconds REAL,
  worker       TEXT,
  state_hash   TEXT,
  evaluated_at TEXT,
  PRIMARY KEY (run_id, id)
);
INSERT INTO individuals_v2 SELECT * FROM individuals ORDER BY run_id, id;
DROP TABLE individuals;
ALTER TABLE individuals_v2 RENAME TO individuals;
CREATE INDEX individuals_to_evaluate ON individuals (run_id, id)
  WHERE status IS NULL;
-- Covers the run loop's reading of a generation's scores.
CREATE INDEX individuals_by_generation
  ON individuals (run_id, generation, id, status, fitness);

CREATE VIEW best AS
  SELECT run_id, id, generation, fitness FROM (
    SELECT run_id, id, generation, fitness,
           ROW_NUMBER() OVER (PARTITION BY run_id
                              ORDER BY fitness DESC, id) AS place
    FROM individuals WHERE status = 'ok')
  WHERE place = 1;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
    // 2 -> 3: an individual's evaluation moves to a table of its own.
    // Recording a result in individuals rewrote the whole row, genome
    // included, and two of its indexes; an insert into a small table keyed
    // like the individual costs a fraction of that. `individuals` becomes a
    // view with the same columns in the same order, so queries read as
    // before.
    R"sql(
DROP VIEW best;
DROP VIEW line_of_descent;
CREATE TABLE births (
  run_id       INTEGER NOT NULL REFERENCES runs (run_id),
  id           INTEGER NOT NULL,
  generation   INTEGER NOT NULL,
  operators    TEXT    NOT NULL,
  genome       BLOB    NOT NULL,
  genome_hash  TEXT    NOT NULL,
  elements     INTEGER NOT NULL,
  created_at   TEXT    NOT NULL,
  PRIMARY KEY (run_id, id)
);
INSERT INTO births
  SELECT run_id, id, generation, operators, genome, genome_hash, elements,
         created_at
  FROM individuals ORDER BY run_id, id;
CREATE INDEX births_by_generation ON births (run_id, generation, id);

CREATE TABLE evaluations (
  run_id       INTEGER NOT NULL,
  id           INTEGER NOT NULL,  -- of an individual in births
  status       TEXT    NOT NULL,
  reason       TEXT,
  fitness      REAL,
  cells        INTEGER,
  steps        INTEGER,
  wall_seconds REAL,
  worker       TEXT,
  state_hash   TEXT,
  evaluated_at TEXT,
  PRIMARY KEY (run_id, id)
) WITHOUT ROWID;
INSERT INTO evaluations
  SELECT run_id, id, status, reason, fitness, cells, steps, wall_seconds,
         worker, state_hash, evaluated_at
  FROM individuals WHERE status IS NOT NULL ORDER BY run_id, id;

DROP TABLE individuals;
CREATE VIEW individuals AS
  SELECT b.run_id, b.id, b.generation, b.operators, b.genome, b.genome_hash,
         b.elements, b.created_at, e.status, e.reason, e.fitness, e.cells,
         e.steps, e.wall_seconds, e.worker, e.state_hash, e.evaluated_at
  FROM births b LEFT JOIN evaluations e
    ON e.run_id = b.run_id AND e.id = b.id;

CREATE VIEW best AS
  SELECT run_id, id, generation, fitness FROM (
    SELECT e.run_id, e.id, b.generation, e.fitness,
           ROW_NUMBER() OVER (PARTITION BY e.run_id
                              ORDER BY e.fitness DESC, e.id) AS place
    FROM evaluations e JOIN births b ON b.run_id = e.run_id AND b.id = e.id
    WHERE e.status = 'ok')
  WHERE place = 1;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
    // 3 -> 4: each evaluation that built a body records what kind of body
    // it was (the cell count is already there); NULL for the others and
    // for evaluations recorded before. The view individuals appends the
    // new columns after schema version 3's, so queries read as before.
    R"sql(
ALTER TABLE evaluations ADD COLUMN springs INTEGER;
ALTER TABLE evaluations ADD COLUMN chambers INTEGER;
ALTER TABLE evaluations ADD COLUMN skin_edges INTEGER;
ALTER TABLE evaluations ADD COLUMN spread_major REAL;
ALTER TABLE evaluations ADD COLUMN spread_minor REAL;

DROP VIEW line_of_descent;
DROP VIEW individuals;
CREATE VIEW individuals AS
  SELECT b.run_id, b.id, b.generation, b.operators, b.genome, b.genome_hash,
         b.elements, b.created_at, e.status, e.reason, e.fitness, e.cells,
         e.steps, e.wall_seconds, e.worker, e.state_hash, e.evaluated_at,
         e.springs, e.chambers, e.skin_edges, e.spread_major, e.spread_minor
  FROM births b LEFT JOIN evaluations e
    ON e.run_id = b.run_id AND e.id = b.id;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
    // 4 -> 5: the configurations a run has had, from which generation each.
    // runs holds only the one in force: a run resumed with --force (another
    // configuration or build) or extended lost what it had run with before.
    // A store written before keeps what its runs hold now, as in force from
    // generation 0 (earlier changes, if any, were never recorded).
    R"sql(
CREATE TABLE run_configs (
  run_id          INTEGER NOT NULL REFERENCES runs (run_id),
  change          INTEGER NOT NULL,  -- 0: as started, then 1, 2, ...
  from_generation INTEGER NOT NULL,  -- the first generation made under it
  config          BLOB    NOT NULL,  -- animat.v1.RunConfig, binary protobuf
  config_text     TEXT    NOT NULL,  -- the same in proto text format
  config_hash     TEXT    NOT NULL,  -- 16 hex digits
  build_id        TEXT    NOT NULL,  -- the simulator build that evaluates
  recorded_at     TEXT    NOT NULL,  -- UTC, ISO 8601
  reason          TEXT    NOT NULL,  -- 'started', or what changed and why
  PRIMARY KEY (run_id, change)
);
INSERT INTO run_configs
  SELECT run_id, 0, 0, config, config_text, config_hash, build_id,
         started_at, 'in force when the store was upgraded to schema '
                     || 'version 5; earlier changes were not recorded'
  FROM runs ORDER BY run_id;
)sql",
    // 5 -> 6: each ok evaluation records the distance swum and the
    // actuators' work (docs/model.md §10.1), beside the fitness, which is
    // the distance under the paper's fitness and the distance within an
    // energy budget under the energy-aware one. NULL for the others and
    // for evaluations recorded before. The view individuals appends the
    // new columns after schema version 5's, so queries read as before.
    R"sql(
ALTER TABLE evaluations ADD COLUMN distance REAL;
ALTER TABLE evaluations ADD COLUMN energy REAL;

DROP VIEW line_of_descent;
DROP VIEW individuals;
CREATE VIEW individuals AS
  SELECT b.run_id, b.id, b.generation, b.operators, b.genome, b.genome_hash,
         b.elements, b.created_at, e.status, e.reason, e.fitness, e.cells,
         e.steps, e.wall_seconds, e.worker, e.state_hash, e.evaluated_at,
         e.springs, e.chambers, e.skin_edges, e.spread_major, e.spread_minor,
         e.distance, e.energy
  FROM births b LEFT JOIN evaluations e
    ON e.run_id = b.run_id AND e.id = b.id;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
    // 6 -> 7: with active guidance (docs/model.md §10.2) an evaluation
    // swims K trials, and its fitness is their mean score; each trial's
    // final distance to its source gets a row, so that which directions an
    // animat reaches is a query. Evaluations without guidance, and those
    // recorded before, have no rows.
    R"sql(
CREATE TABLE trials (
  run_id          INTEGER NOT NULL,
  id              INTEGER NOT NULL,  -- of an evaluated individual
  trial           INTEGER NOT NULL,  -- k = 0 ... K - 1
  source_distance REAL    NOT NULL,  -- d_k at the end of the trial, radii
  PRIMARY KEY (run_id, id, trial)
) WITHOUT ROWID;
)sql",
    // 7 -> 8: each ok evaluation records the deepest overlap of two cells
    // not joined by a spring (docs/model.md §8.6, model v3), so that "do
    // bodies pass through themselves" is a query. NULL for the others and
    // for evaluations recorded before. The view individuals appends the
    // new column after schema version 7's, so queries read as before.
    R"sql(
ALTER TABLE evaluations ADD COLUMN max_overlap REAL;

DROP VIEW line_of_descent;
DROP VIEW individuals;
CREATE VIEW individuals AS
  SELECT b.run_id, b.id, b.generation, b.operators, b.genome, b.genome_hash,
         b.elements, b.created_at, e.status, e.reason, e.fitness, e.cells,
         e.steps, e.wall_seconds, e.worker, e.state_hash, e.evaluated_at,
         e.springs, e.chambers, e.skin_edges, e.spread_major, e.spread_minor,
         e.distance, e.energy, e.max_overlap
  FROM births b LEFT JOIN evaluations e
    ON e.run_id = b.run_id AND e.id = b.id;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
    // 8 -> 9: each evaluation records the instruction-set path of the
    // vector kernels that ran it ('baseline', 'avx2', 'avx512'; every path
    // gives the same bits, so this says where, not what). NULL when not
    // known: nothing simulated, a crash, or recorded before. Appended to
    // the view individuals after version 8's columns.
    R"sql(
ALTER TABLE evaluations ADD COLUMN isa TEXT;

DROP VIEW line_of_descent;
DROP VIEW individuals;
CREATE VIEW individuals AS
  SELECT b.run_id, b.id, b.generation, b.operators, b.genome, b.genome_hash,
         b.elements, b.created_at, e.status, e.reason, e.fitness, e.cells,
         e.steps, e.wall_seconds, e.worker, e.state_hash, e.evaluated_at,
         e.springs, e.chambers, e.skin_edges, e.spread_major, e.spread_minor,
         e.distance, e.energy, e.max_overlap, e.isa
  FROM births b LEFT JOIN evaluations e
    ON e.run_id = b.run_id AND e.id = b.id;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
    // 9 -> 10: an offspring whose genome is byte for byte a member's of
    // the generation before is not simulated again: its evaluation is the
    // member's, copied (evaluation is a pure function of the genome and
    // the run's configuration), and reused_from names the individual
    // whose simulation it is. NULL for every simulated evaluation and for
    // those recorded before. Appended to the view individuals after
    // version 9's columns.
    R"sql(
ALTER TABLE evaluations ADD COLUMN reused_from INTEGER;

DROP VIEW line_of_descent;
DROP VIEW individuals;
CREATE VIEW individuals AS
  SELECT b.run_id, b.id, b.generation, b.operators, b.genome, b.genome_hash,
         b.elements, b.created_at, e.status, e.reason, e.fitness, e.cells,
         e.steps, e.wall_seconds, e.worker, e.state_hash, e.evaluated_at,
         e.springs, e.chambers, e.skin_edges, e.spread_major, e.spread_minor,
         e.distance, e.energy, e.max_overlap, e.isa, e.reused_from
  FROM births b LEFT JOIN evaluations e
    ON e.run_id = b.run_id AND e.id = b.id;

CREATE VIEW line_of_descent AS
  WITH RECURSIVE line (run_id, id, step) AS (
    SELECT run_id, id, 0 FROM best
    UNION ALL
    SELECT line.run_id, p.parent, line.step + 1
    FROM line JOIN parents p
      ON p.run_id = line.run_id AND p.child = line.id AND p.position = 0)
  SELECT line.run_id, line.step, i.id, i.generation, i.operators, i.fitness
  FROM line JOIN individuals i ON i.run_id = line.run_id AND i.id = line.id;
)sql",
};

constexpr int kKnown = static_cast<int>(std::size(kMigrations));
static_assert(kKnown == kSchemaVersion, "one migration per version");

}  // namespace

Result<int> SchemaVersion(sql::Database& db) {
  Result<sql::Statement> statement = db.Prepare("PRAGMA user_version");
  if (!statement.ok()) return statement.status();
  Result<bool> row = statement->Step();
  if (!row.ok()) return row.status();
  return static_cast<int>(statement->Int(0));
}

Status Migrate(sql::Database& db, int target) {
  if (target < 0 || target > kSchemaVersion) {
    return Status::InvalidArgument("no lineage schema version " +
                                   std::to_string(target));
  }
  Result<int> version = SchemaVersion(db);
  if (!version.ok()) return version.status();
  if (*version > kSchemaVersion) {
    return Status::InvalidArgument(
        db.path() + ": lineage schema version " + std::to_string(*version) +
        " was written by a newer animat; this build knows up to " +
        std::to_string(kSchemaVersion));
  }
  for (int v = *version; v < target; ++v) {
    Status status = db.Execute(
        std::string("BEGIN IMMEDIATE;") + kMigrations[v] +
        "PRAGMA user_version = " + std::to_string(v + 1) + ";COMMIT;");
    if (!status.ok()) {
      (void)db.Execute("ROLLBACK");
      return status.WithPrefix("migration to schema version " +
                               std::to_string(v + 1));
    }
  }
  return Status::Ok();
}

}  // namespace animat::lineage
