// Read-only looks at a lineage store from the tests, through SQLite's own
// C API (not the store's code, which is what the tests check): rows as
// text, a run's progress while a master writes, and the contents a run's
// seed and configuration decide, for comparing two stores.
//
// A cell reads as "NULL", a decimal integer, "real:" and the 16 hex digits
// of a double's bits, the text itself, or "blob:" and the bytes in hex, so
// equal text means equal bits.
#ifndef ANIMAT_TESTS_MASTER_STORE_READER_H_
#define ANIMAT_TESTS_MASTER_STORE_READER_H_

#include <sqlite3.h>

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "common/base/status.h"

namespace animat::testing {

using SqlRow = std::vector<std::string>;

inline std::string CellText(sqlite3_stmt* statement, int column) {
  switch (sqlite3_column_type(statement, column)) {
    case SQLITE_NULL:
      return "NULL";
    case SQLITE_INTEGER:
      return std::to_string(sqlite3_column_int64(statement, column));
    case SQLITE_FLOAT: {
      char bits[32];
      std::snprintf(bits, sizeof(bits), "real:%016llx",
                    static_cast<unsigned long long>(std::bit_cast<uint64_t>(
                        sqlite3_column_double(statement, column))));
      return bits;
    }
    case SQLITE_BLOB: {
      const auto* bytes = static_cast<const unsigned char*>(
          sqlite3_column_blob(statement, column));
      const int size = sqlite3_column_bytes(statement, column);
      std::string text = "blob:";
      static constexpr char kHex[] = "0123456789abcdef";
      for (int i = 0; i < size; ++i) {
        text += kHex[bytes[i] >> 4];
        text += kHex[bytes[i] & 15];
      }
      return text;
    }
    default: {
      const auto* text = sqlite3_column_text(statement, column);
      return std::string(
          reinterpret_cast<const char*>(text),
          static_cast<size_t>(sqlite3_column_bytes(statement, column)));
    }
  }
}

// Every row of `query` on the store at `path`, opened read-only (a master
// may be writing it). Fails on a missing file or bad SQL, saying which.
inline Result<std::vector<SqlRow>> QueryStore(const std::string& path,
                                              const std::string& query) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) !=
      SQLITE_OK) {
    Status status = Status::IoError(path + ": " + sqlite3_errmsg(db));
    sqlite3_close(db);
    return status;
  }
  sqlite3_busy_timeout(db, 5000);
  sqlite3_stmt* statement = nullptr;
  std::vector<SqlRow> rows;
  Status status;
  if (sqlite3_prepare_v2(db, query.c_str(), -1, &statement, nullptr) !=
      SQLITE_OK) {
    status = Status::IoError(path + ": " + sqlite3_errmsg(db) + " in " + query);
  } else {
    int rc;
    while ((rc = sqlite3_step(statement)) == SQLITE_ROW) {
      SqlRow row;
      for (int c = 0; c < sqlite3_column_count(statement); ++c) {
        row.push_back(CellText(statement, c));
      }
      rows.push_back(std::move(row));
    }
    if (rc != SQLITE_DONE) {
      status =
          Status::IoError(path + ": " + sqlite3_errmsg(db) + " in " + query);
    }
  }
  sqlite3_finalize(statement);
  sqlite3_close(db);
  if (!status.ok()) return status;
  return rows;
}

// Every row of `query`; fails the test (and gives none) on an error.
inline std::vector<SqlRow> QueryRows(const std::string& path,
                                     const std::string& query) {
  Result<std::vector<SqlRow>> rows = QueryStore(path, query);
  if (!rows.ok()) {
    ADD_FAILURE() << rows.status().ToString();
    return {};
  }
  return std::move(rows).value();
}

// The single cell of a query that gives one row of one column; fails the
// test (and gives "") otherwise.
inline std::string QueryCell(const std::string& path,
                             const std::string& query) {
  Result<std::vector<SqlRow>> rows = QueryStore(path, query);
  if (!rows.ok()) {
    ADD_FAILURE() << rows.status().ToString();
    return "";
  }
  if (rows->size() != 1 || (*rows)[0].size() != 1) {
    ADD_FAILURE() << query << ": " << rows->size() << " rows, expected one";
    return "";
  }
  return (*rows)[0][0];
}

inline int64_t QueryInt(const std::string& path, const std::string& query) {
  const std::string cell = QueryCell(path, query);
  return cell.empty() || cell == "NULL" ? -1 : std::stoll(cell);
}

// A run's progress as the store shows it; all zero before a master has
// created the store and its run.
struct Progress {
  bool has_run = false;
  bool finished = false;    // The latest run's state.
  int64_t individuals = 0;  // Made.
  int64_t evaluated = 0;    // With a recorded evaluation.
  int64_t generations = 0;  // Recorded.
  int64_t complete_generations = 0;

  std::string ToString() const {
    return std::string(has_run ? (finished ? "finished" : "running")
                               : "no run") +
           ", " + std::to_string(individuals) + " individuals, " +
           std::to_string(evaluated) + " evaluated, " +
           std::to_string(generations) + " generations, " +
           std::to_string(complete_generations) + " complete";
  }
};

inline Progress ReadProgress(const std::string& path) {
  Result<std::vector<SqlRow>> rows = QueryStore(
      path,
      "SELECT (SELECT count(*) FROM runs),"
      " (SELECT state FROM runs ORDER BY run_id DESC LIMIT 1),"
      " (SELECT count(*) FROM individuals),"
      " (SELECT count(*) FROM individuals WHERE status IS NOT NULL),"
      " (SELECT count(*) FROM generations),"
      " (SELECT count(*) FROM generations WHERE completed_at IS NOT NULL)");
  Progress progress;
  if (!rows.ok() || rows->size() != 1) return progress;  // Not made yet.
  const SqlRow& row = (*rows)[0];
  progress.has_run = row[0] != "0";
  progress.finished = row[1] == "finished";
  progress.individuals = std::stoll(row[2]);
  progress.evaluated = std::stoll(row[3]);
  progress.generations = std::stoll(row[4]);
  progress.complete_generations = std::stoll(row[5]);
  return progress;
}

// What a run's seed and configuration decide, table by table, in a fixed
// order: everything but times, workers and wall times, and the history of
// how the run was run (run_configs: an extended run has one more change
// than the same run made at once).
struct StoreContents {
  std::vector<SqlRow> runs, individuals, parents, generations, members;
};

inline StoreContents ReadStoreContents(const std::string& path) {
  StoreContents contents;
  const auto read = [&](const std::string& query, std::vector<SqlRow>* out) {
    Result<std::vector<SqlRow>> rows = QueryStore(path, query);
    if (!rows.ok()) {
      ADD_FAILURE() << rows.status().ToString();
      return;
    }
    *out = std::move(rows).value();
  };
  read(
      "SELECT run_id, seed, config, config_text, config_hash, build_id, state"
      " FROM runs ORDER BY run_id",
      &contents.runs);
  read(
      "SELECT run_id, id, generation, operators, genome, genome_hash,"
      " elements, status, reason, fitness, cells, steps, state_hash,"
      " springs, chambers, skin_edges, spread_major, spread_minor"
      " FROM individuals ORDER BY run_id, id",
      &contents.individuals);
  read(
      "SELECT run_id, child, position, parent FROM parents"
      " ORDER BY run_id, child, position",
      &contents.parents);
  read(
      "SELECT run_id, generation, size, completed_at IS NOT NULL, evaluated,"
      " failed, best_id, best_fitness, mean_fitness, median_fitness"
      " FROM generations ORDER BY run_id, generation",
      &contents.generations);
  read(
      "SELECT run_id, generation, id, rank FROM members"
      " ORDER BY run_id, generation, id",
      &contents.members);
  return contents;
}

inline std::string RowText(const SqlRow& row) {
  std::string text;
  for (const std::string& cell : row) {
    if (!text.empty()) text += " | ";
    const std::string shown = cell.size() > 80
                                  ? cell.substr(0, 60) + "...(" +
                                        std::to_string(cell.size()) + " chars)"
                                  : cell;
    for (char c : shown) text += c == '\n' ? ' ' : c;
  }
  return text;
}

// Expects equal tables; a difference is reported by its first row.
inline void ExpectSameTable(const std::string& table,
                            const std::vector<SqlRow>& expected,
                            const std::vector<SqlRow>& actual) {
  for (size_t i = 0; i < expected.size() && i < actual.size(); ++i) {
    if (expected[i] != actual[i]) {
      std::string which;
      for (size_t c = 0; c < expected[i].size() && c < actual[i].size(); ++c) {
        if (expected[i][c] != actual[i][c]) {
          which += ' ';
          which += std::to_string(c);
        }
      }
      ADD_FAILURE() << table << ": row " << i << " differs (columns" << which
                    << ")\n  expected: " << RowText(expected[i])
                    << "\n  actual:   " << RowText(actual[i]);
      return;
    }
  }
  EXPECT_EQ(actual.size(), expected.size()) << table << ": row counts differ";
}

inline void ExpectSameContents(const StoreContents& expected,
                               const StoreContents& actual) {
  ExpectSameTable("runs", expected.runs, actual.runs);
  ExpectSameTable("individuals", expected.individuals, actual.individuals);
  ExpectSameTable("parents", expected.parents, actual.parents);
  ExpectSameTable("generations", expected.generations, actual.generations);
  ExpectSameTable("members", expected.members, actual.members);
}

}  // namespace animat::testing

#endif  // ANIMAT_TESTS_MASTER_STORE_READER_H_
