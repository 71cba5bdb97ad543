// The one-command tools over real stores: `animat evolve` runs, logs a
// progress line per generation on standard error (standard output has only
// its closing line) and extends a finished run; `animat lineage` answers
// from the store (checked against SQL on it), its genomes replay to the
// recorded bits under `animat simulate`; bad arguments get a clear error
// and a non-zero exit.
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "animat/v1/evolution.pb.h"
#include "animat/v1/genome.pb.h"
#include "common/evaluation/evaluator.h"
#include "common/evaluation/model_config.h"
#include "common/genome/genome_proto.h"
#include "common/io/proto_file.h"
#include "common/kernels/isa.h"
#include "master/lineage/schema.h"
#include "master/lineage/sqlite.h"
#include "tests/master/master_harness.h"

namespace animat::testing {
namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The fields of a CSV line; quoted fields may hold commas.
std::vector<std::string> CsvFields(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += c;
    }
  }
  return fields;
}

// "real:<bits>" of a number printed as text (%.17g round-trips), "NULL"
// for an empty text.
std::string RealCell(const std::string& text) {
  if (text.empty() || text == "-") return "NULL";
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  if (errno != 0 || end == text.c_str() || *end != '\0') {
    return "unparsable number " + text;
  }
  char cell[32];
  std::snprintf(
      cell, sizeof(cell), "real:%016llx",
      static_cast<unsigned long long>(std::bit_cast<uint64_t>(value)));
  return cell;
}

double CellDouble(const std::string& cell) {
  return std::bit_cast<double>(
      static_cast<uint64_t>(std::stoull(cell.substr(5), nullptr, 16)));
}

// "name: value" lines as a map.
std::map<std::string, std::string> Fields(const std::string& text) {
  std::map<std::string, std::string> fields;
  for (const std::string& line : Lines(text)) {
    const size_t colon = line.find(": ");
    if (colon != std::string::npos) {
      fields[line.substr(0, colon)] = line.substr(colon + 2);
    }
  }
  return fields;
}

class EvolveCliTest : public MasterTest {
 protected:
  // Runs `animat args` to its end; its exit code.
  int Animat(const std::vector<std::string>& args, std::string* out = nullptr,
             std::string* err = nullptr) {
    std::unique_ptr<ChildProcess> animat = StartAnimat(args);
    if (!AwaitExit(*animat, kRunWait, "animat " + args[0])) return -1;
    if (out != nullptr) *out = animat->standard_output();
    if (err != nullptr) *err = animat->standard_error();
    return animat->exit_code();
  }

  // The output convention (README): progress is logged, timestamped, on
  // standard error, one line for each of generations `first` to
  // `generations` - 1 as the store records it; standard output holds only
  // the closing line.
  void ExpectProgressLines(const std::string& out, const std::string& err,
                           int first, int generations) {
    EXPECT_EQ(out,
              "finished; the best: animat lineage best --db " + db_ + "\n");
    static const std::regex kProgressLine(
        R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z evolve: (generation .*))");
    static const std::regex kAnyProgress(R"(generation \d+/\d+: )");
    std::vector<std::string> lines;
    for (const std::string& line : Lines(err)) {
      std::smatch match;
      if (std::regex_match(line, match, kProgressLine)) {
        lines.push_back(match[1]);
      } else {
        EXPECT_FALSE(std::regex_search(line, kAnyProgress))
            << "a progress line without the log's timestamp: " << line;
      }
    }
    ASSERT_EQ(lines.size(), static_cast<size_t>(generations - first)) << err;
    for (int g = first; g < generations; ++g) {
      const std::vector<SqlRow> rows =
          QueryRows(db_,
                    "SELECT best_fitness, best_id, mean_fitness,"
                    " median_fitness, evaluated, failed FROM generations"
                    " WHERE generation = " +
                        std::to_string(g));
      ASSERT_EQ(rows.size(), 1u) << "generation " << g;
      const SqlRow& row = rows[0];
      char expected[256];
      std::snprintf(expected, sizeof(expected),
                    "generation %d/%d: best %.6g (id %s), mean %.6g, median "
                    "%.6g, %s ok, %s failed | ",
                    g, generations, CellDouble(row[0]), row[1].c_str(),
                    CellDouble(row[2]), CellDouble(row[3]), row[4].c_str(),
                    row[5].c_str());
      EXPECT_EQ(lines[g - first].rfind(expected, 0), 0u)
          << lines[g - first] << "\nexpected it to start with " << expected;
    }
  }

  // Runs a store of `generations` generations with `animat evolve`.
  void Evolve(int generations) {
    std::string out, err;
    ASSERT_EQ(Animat({"evolve", "--config", config_, "--db", db_, "--workers",
                      "2", "--generations", std::to_string(generations)},
                     &out, &err),
              0)
        << err;
    ExpectProgressLines(out, err, 0, generations);
  }

  std::string config_;
  std::string db_;
};

TEST_F(EvolveCliTest, EvolveLogsEachGenerationOnStderrAndExtendsAFinishedRun) {
  TestRun run;
  run.seed = 21;
  config_ = WriteConfig("run.txtpb", run);
  db_ = Path("evolve.db");
  Evolve(1);
  if (HasFatalFailure()) return;
  Progress progress = ReadProgress(db_);
  EXPECT_TRUE(progress.finished) << progress.ToString();
  EXPECT_EQ(progress.complete_generations, 1);

  // The same command with more generations (and no --config) extends it.
  std::string out, err;
  ASSERT_EQ(
      Animat({"evolve", "--db", db_, "--workers", "2", "--generations", "3"},
             &out, &err),
      0)
      << err;
  ExpectProgressLines(out, err, 1, 3);
  progress = ReadProgress(db_);
  EXPECT_TRUE(progress.finished) << progress.ToString();
  EXPECT_EQ(progress.complete_generations, 3);

  // An extended run is the run of 3 generations made at once.
  run.generations = 3;
  const std::string reference_db = Path("reference.db");
  RunToEnd(WriteConfig("three.txtpb", run), reference_db, /*workers=*/2);
  if (HasFatalFailure()) return;
  ExpectSameContents(ReadStoreContents(reference_db), ReadStoreContents(db_));
}

TEST_F(EvolveCliTest, FewerGenerationsThanTheRunHasSaySoAndChangeNothing) {
  TestRun run;
  run.seed = 22;
  config_ = WriteConfig("run.txtpb", run);
  db_ = Path("fewer.db");
  Evolve(2);
  if (HasFatalFailure()) return;
  const StoreContents before = ReadStoreContents(db_);

  std::string out, err;
  EXPECT_EQ(
      Animat({"evolve", "--db", db_, "--workers", "1", "--generations", "1"},
             &out, &err),
      1);
  EXPECT_NE(err.find(db_ +
                     " holds run 1 (finished) with 2 generations; "
                     "--generations 1 counts them all, so there is "
                     "nothing to run. To extend it, ask for more than "
                     "2: " +
                     std::string(ANIMAT_BIN_DIR) + "/animat evolve --db " +
                     db_ + " --workers 1 --generations 12"),
            std::string::npos)
      << err;
  EXPECT_EQ(out, "");
  // The run's configuration still says 2 generations.
  ExpectSameContents(before, ReadStoreContents(db_));
}

TEST_F(EvolveCliTest, LineageAnswersAsTheStoreSays) {
  TestRun run;
  run.seed = 6;
  config_ = WriteConfig("run.txtpb", run);
  db_ = Path("lineage.db");
  Evolve(3);
  if (HasFatalFailure()) return;

  // best: the highest fitness, the lowest id among equals.
  const SqlRow best =
      QueryRows(db_,
                "SELECT id, generation, fitness, operators FROM individuals"
                " WHERE status = 'ok' ORDER BY fitness DESC, id LIMIT 1")

          .at(0);
  std::string out, err;
  ASSERT_EQ(Animat({"lineage", "best", "--db", db_}, &out, &err), 0) << err;
  std::map<std::string, std::string> fields = Fields(out);
  EXPECT_EQ(fields["id"], best[0]) << out;
  EXPECT_EQ(fields["generation"], best[1]) << out;
  EXPECT_EQ(RealCell(fields["fitness"]), best[2]) << out;
  EXPECT_EQ(fields["operators"], best[3]) << out;
  // Its body, as recorded.
  const SqlRow body =
      QueryRows(db_,
                "SELECT cells, springs, chambers, skin_edges, spread_major,"
                " spread_minor FROM individuals WHERE id = " +
                    best[0])
          .at(0);
  EXPECT_EQ(fields["cells"], body[0]) << out;
  EXPECT_EQ(fields["springs"], body[1]) << out;
  EXPECT_EQ(fields["chambers"], body[2]) << out;
  EXPECT_EQ(fields["skin_edges"], body[3]) << out;
  EXPECT_EQ(RealCell(fields["spread_major"]), body[4]) << out;
  EXPECT_EQ(RealCell(fields["spread_minor"]), body[5]) << out;
  // The distance swum and the energy, as recorded.
  const SqlRow swum = QueryRows(db_,
                                "SELECT distance, energy FROM individuals"
                                " WHERE id = " +
                                    best[0])
                          .at(0);
  EXPECT_EQ(RealCell(fields["distance"]), swum[0]) << out;
  EXPECT_EQ(RealCell(fields["energy"]), swum[1]) << out;
  // The path that evaluated it: the workers', which share this process's
  // environment and machine; every simulated evaluation records one, and
  // an evaluation reused for a copy of a parent's genome none.
  EXPECT_EQ(fields["isa"], IsaName(ActiveIsa())) << out;
  EXPECT_EQ(QueryRows(db_,
                      "SELECT DISTINCT COALESCE(isa, 'NULL') FROM individuals"
                      " WHERE status IS NOT NULL AND reused_from IS NULL"),
            (std::vector<SqlRow>{{IsaName(ActiveIsa())}}));
  EXPECT_EQ(QueryRows(db_,
                      "SELECT COUNT(*) FROM individuals WHERE reused_from IS"
                      " NOT NULL AND (isa IS NOT NULL OR worker IS NOT NULL"
                      " OR wall_seconds IS NOT NULL)"),
            (std::vector<SqlRow>{{"0"}}));

  // ancestors: every ancestor once, at its shortest distance, nearest
  // first then by id; computed here from the parents table.
  std::multimap<std::string, std::string> parents_of;
  for (const SqlRow& row :
       QueryRows(db_, "SELECT child, parent FROM parents")) {
    parents_of.emplace(row[0], row[1]);
  }
  const std::string youngest =
      QueryCell(db_, "SELECT max(id) FROM individuals");
  for (const std::string& id : {best[0], youngest}) {
    SCOPED_TRACE("ancestors of " + id);
    std::map<std::string, int> distance;
    std::deque<std::string> queue = {id};
    std::map<std::string, int> depth = {{id, 0}};
    while (!queue.empty()) {
      const std::string child = queue.front();
      queue.pop_front();
      const auto [begin, end] = parents_of.equal_range(child);
      for (auto it = begin; it != end; ++it) {
        if (depth.count(it->second) == 0) {
          depth[it->second] = depth[child] + 1;
          distance[it->second] = depth[child] + 1;
          queue.push_back(it->second);
        }
      }
    }
    std::set<std::pair<int, int64_t>> expected;
    for (const auto& [ancestor, d] : distance) {
      expected.insert({d, std::stoll(ancestor)});
    }
    ASSERT_EQ(Animat({"lineage", "ancestors", id, "--db", db_}, &out, &err), 0)
        << err;
    const std::vector<std::string> lines = Lines(out);
    ASSERT_FALSE(lines.empty());
    EXPECT_EQ(lines[0], "distance,id,generation,fitness,status,operators");
    ASSERT_EQ(lines.size(), expected.size() + 1) << out;
    size_t i = 1;
    for (const auto& [d, ancestor] : expected) {
      const std::vector<std::string> f = CsvFields(lines[i++]);
      ASSERT_EQ(f.size(), 6u) << lines[i - 1];
      EXPECT_EQ(f[0], std::to_string(d));
      EXPECT_EQ(f[1], std::to_string(ancestor));
      const SqlRow row =
          QueryRows(db_,
                    "SELECT generation, fitness, coalesce(status, ''),"
                    " operators FROM individuals WHERE id = " +
                        std::to_string(ancestor))

              .at(0);
      EXPECT_EQ(f[2], row[0]);
      EXPECT_EQ(RealCell(f[3]), row[1]);
      EXPECT_EQ(f[4], row[2]);
      EXPECT_EQ(f[5], row[3]);
    }
    // -o writes the same to a file.
    const std::string csv = Path("ancestors-" + id + ".csv");
    std::string file_out;
    ASSERT_EQ(Animat({"lineage", "ancestors", id, "--db", db_, "-o", csv},
                     &file_out, &err),
              0)
        << err;
    EXPECT_EQ(file_out, "");
    Result<std::string> written = ReadFile(csv);
    ASSERT_TRUE(written.ok()) << written.status().ToString();
    EXPECT_EQ(*written, out);
  }
  EXPECT_TRUE(parents_of.count(youngest) > 0)
      << "the youngest individual, " << youngest << ", has no parents";

  // genome: the stored genome, which replays under animat simulate with
  // the run's model configuration to the recorded evaluation.
  const std::string genome_path = Path("best.json");
  ASSERT_EQ(
      Animat({"lineage", "genome", best[0], "--db", db_, "-o", genome_path},
             &out, &err),
      0)
      << err;
  v1::Genome genome;
  ASSERT_TRUE(ReadProtoFile(genome_path, &genome).ok());
  std::string genome_hex = "blob:";
  for (unsigned char c : genome.SerializeAsString()) {
    static constexpr char kHex[] = "0123456789abcdef";
    genome_hex += kHex[c >> 4];
    genome_hex += kHex[c & 15];
  }
  EXPECT_EQ(
      genome_hex,
      QueryCell(db_, "SELECT genome FROM individuals WHERE id = " + best[0]));
  v1::RunConfig stored;
  ASSERT_TRUE(stored.ParseFromString([&] {
    const std::string hex = QueryCell(db_, "SELECT hex(config) FROM runs");
    std::string bytes;
    for (size_t i = 0; i + 1 < hex.size(); i += 2) {
      bytes += static_cast<char>(std::stoi(hex.substr(i, 2), nullptr, 16));
    }
    return bytes;
  }()));
  const std::string model_path = Path("model.json");
  ASSERT_TRUE(WriteProtoFile(model_path, stored.model()).ok());
  ASSERT_EQ(
      Animat({"simulate", "--genome", genome_path, "--config", model_path},
             &out, &err),
      0)
      << err;
  fields = Fields(out);
  const SqlRow recorded =
      QueryRows(db_,
                "SELECT status, fitness, cells, steps, state_hash FROM"
                " individuals WHERE id = " +
                    best[0])

          .at(0);
  EXPECT_EQ(fields["status"], recorded[0]) << out;
  EXPECT_EQ(RealCell(fields["fitness"]), recorded[1]) << out;
  EXPECT_EQ(fields["cells"], recorded[2]) << out;
  EXPECT_EQ(fields["steps"], recorded[3]) << out;
  EXPECT_EQ(fields["state_hash"], recorded[4]) << out;
  EXPECT_EQ(fields["springs"], body[1]) << out;
  EXPECT_EQ(fields["chambers"], body[2]) << out;
  EXPECT_EQ(fields["skin_edges"], body[3]) << out;
  EXPECT_EQ(RealCell(fields["spread_major"]), body[4]) << out;
  EXPECT_EQ(RealCell(fields["spread_minor"]), body[5]) << out;

  // export: one row per individual in id order, with its parents in order.
  const std::string csv = Path("phylogeny.csv");
  ASSERT_EQ(
      Animat({"lineage", "export", "--format", "alife", "--db", db_, "-o", csv},
             &out, &err),
      0)
      << err;
  const std::vector<std::string> rows =
      Lines(ReadFile(csv).ok() ? *ReadFile(csv) : "");
  const std::vector<SqlRow> individuals =
      QueryRows(db_,
                "SELECT id, coalesce((SELECT group_concat(parent, ',') FROM"
                " (SELECT parent FROM parents p WHERE p.child = i.id"
                "  ORDER BY position)), 'NONE'),"
                " generation, fitness, coalesce(status, ''), operators"
                " FROM individuals i ORDER BY id");
  ASSERT_EQ(rows.size(), individuals.size() + 1);
  EXPECT_EQ(rows[0], "id,ancestor_list,origin_time,fitness,status,operators");
  for (size_t r = 0; r < individuals.size(); ++r) {
    const SqlRow& row = individuals[r];
    const std::vector<std::string> f = CsvFields(rows[r + 1]);
    ASSERT_EQ(f.size(), 6u) << rows[r + 1];
    EXPECT_EQ(f[0], row[0]);
    EXPECT_EQ(f[1], "[" + row[1] + "]") << "individual " << row[0];
    EXPECT_EQ(f[2], row[2]);
    EXPECT_EQ(RealCell(f[3]), row[3]) << "individual " << row[0];
    EXPECT_EQ(f[4], row[4]);
    EXPECT_EQ(f[5], row[5]);
  }
}

// The bytes of a "blob:<hex>" cell.
std::string BlobBytes(const std::string& cell) {
  std::string bytes;
  for (size_t i = 5; i + 1 < cell.size(); i += 2) {
    bytes += static_cast<char>(std::stoi(cell.substr(i, 2), nullptr, 16));
  }
  return bytes;
}

// A double as a "real:<bits>" cell.
std::string RealBits(double value) {
  char cell[32];
  std::snprintf(
      cell, sizeof(cell), "real:%016llx",
      static_cast<unsigned long long>(std::bit_cast<uint64_t>(value)));
  return cell;
}

// A real run records with every evaluation the body it built, as the
// evaluation gives it: each individual's body columns are those of its
// genome evaluated here again (NULL where no body was built), every
// individual that swims has a body with a chamber, and the chambers
// histogram of the store is that of the evaluations.
TEST_F(EvolveCliTest, StoreRecordsTheBodyOfEveryEvaluation) {
  TestRun run;
  run.seed = 6;
  run.generations = 2;
  config_ = WriteConfig("run.txtpb", run);
  db_ = Path("bodies.db");
  Evolve(2);
  if (HasFatalFailure()) return;

  v1::RunConfig stored;
  ASSERT_TRUE(stored.ParseFromString(
      BlobBytes(QueryCell(db_, "SELECT config FROM runs"))));
  ModelConfig model;
  ASSERT_TRUE(ConfigFromProto(stored.model(), &model).ok());
  const std::vector<SqlRow> rows =
      QueryRows(db_,
                "SELECT id, genome, status, springs, chambers, skin_edges,"
                " spread_major, spread_minor, distance, energy"
                " FROM individuals ORDER BY id");
  ASSERT_GT(rows.size(), 1000u);
  std::map<std::string, int64_t> histogram;  // Chambers -> individuals.
  int with_body = 0;
  for (const SqlRow& row : rows) {
    SCOPED_TRACE("individual " + row[0]);
    v1::Genome message;
    ASSERT_TRUE(message.ParseFromString(BlobBytes(row[1])));
    Result<Genome> genome = GenomeFromProto(message);
    ASSERT_TRUE(genome.ok()) << genome.status().ToString();
    const EvaluationResult result = Evaluate(*genome, model);
    ASSERT_EQ(row[2], EvalStatusName(result.status));
    SqlRow expected(5, "NULL");
    if (result.body) {
      ++with_body;
      expected = {std::to_string(result.body->springs),
                  std::to_string(result.body->chambers),
                  std::to_string(result.body->skin_edges),
                  RealBits(result.body->spread_major),
                  RealBits(result.body->spread_minor)};
    }
    // The distance swum and the energy, when ok.
    expected.push_back(result.distance ? RealBits(*result.distance) : "NULL");
    expected.push_back(result.energy ? RealBits(*result.energy) : "NULL");
    EXPECT_EQ(SqlRow(row.begin() + 3, row.end()), expected);
    ++histogram[expected[1]];
  }
  EXPECT_GT(with_body, run.population);

  std::map<std::string, int64_t> stored_histogram;
  for (const SqlRow& row :
       QueryRows(db_,
                 "SELECT chambers, COUNT(*) FROM individuals"
                 " GROUP BY chambers")) {
    stored_histogram[row[0]] = std::stoll(row[1]);
  }
  EXPECT_EQ(stored_histogram, histogram);
  EXPECT_GT(QueryInt(db_,
                     "SELECT COUNT(*) FROM individuals"
                     " WHERE status = 'ok'"),
            0);
  EXPECT_EQ(QueryInt(db_,
                     "SELECT COUNT(*) FROM individuals WHERE status = 'ok'"
                     " AND (chambers IS NULL OR chambers < 1)"),
            0);
}

// A guidance run (docs/model.md §10.2) records each ok evaluation's trials:
// their final distances to the sources are those of the genome evaluated
// here again, and `lineage best` prints the best's.
TEST_F(EvolveCliTest, GuidanceRunRecordsEveryTrial) {
  config_ = Path("guidance.txtpb");
  ASSERT_TRUE(WriteFile(config_,
                        "model {\n"
                        "  development { max_cells: 8 }\n"
                        "  evaluation { equilibration_steps: 50"
                        " motion_steps: 200 }\n"
                        "  guidance { enabled: true trials: 2 }\n"
                        "}\n"
                        "evolution { seed: 3 population: 4 generations: 2"
                        " elite: 1 initial_min_fitness: 0 }\n")
                  .ok());
  db_ = Path("guidance.db");
  Evolve(2);
  if (HasFatalFailure()) return;

  v1::RunConfig stored;
  ASSERT_TRUE(stored.ParseFromString(
      BlobBytes(QueryCell(db_, "SELECT config FROM runs"))));
  ModelConfig model;
  ASSERT_TRUE(ConfigFromProto(stored.model(), &model).ok());
  const std::vector<SqlRow> ok = QueryRows(
      db_,
      "SELECT id, genome FROM individuals WHERE status = 'ok' ORDER BY id");
  ASSERT_GE(ok.size(), 4u);
  for (const SqlRow& row : ok) {
    SCOPED_TRACE("individual " + row[0]);
    v1::Genome message;
    ASSERT_TRUE(message.ParseFromString(BlobBytes(row[1])));
    Result<Genome> genome = GenomeFromProto(message);
    ASSERT_TRUE(genome.ok()) << genome.status().ToString();
    const EvaluationResult result = Evaluate(*genome, model);
    ASSERT_EQ(result.source_distances.size(), 2u);
    std::vector<SqlRow> expected;
    for (size_t k = 0; k < result.source_distances.size(); ++k) {
      expected.push_back(
          {std::to_string(k), RealBits(result.source_distances[k])});
    }
    EXPECT_EQ(
        QueryRows(db_, "SELECT trial, source_distance FROM trials WHERE id = " +
                           row[0] + " ORDER BY trial"),
        expected);
  }
  EXPECT_EQ(QueryInt(db_,
                     "SELECT COUNT(*) FROM trials t JOIN individuals i"
                     " ON i.run_id = t.run_id AND i.id = t.id"
                     " WHERE i.status IS NOT 'ok'"),
            0);

  std::string out, err;
  ASSERT_EQ(Animat({"lineage", "best", "--db", db_}, &out, &err), 0) << err;
  const std::string best_id = Fields(out)["id"];
  const std::vector<SqlRow> trials = QueryRows(
      db_, "SELECT source_distance FROM trials WHERE id = " + best_id +
               " ORDER BY trial");
  ASSERT_EQ(trials.size(), 2u);
  const std::string printed = Fields(out)["source_distances"];
  ASSERT_GE(printed.size(), 2u) << out;
  const std::vector<std::string> values =
      CsvFields(printed.substr(1, printed.size() - 2));
  ASSERT_EQ(values.size(), 2u) << out;
  for (size_t k = 0; k < 2; ++k) {
    std::string value = values[k];
    value.erase(0, value.find_first_not_of(' '));
    EXPECT_EQ(RealCell(value), trials[k][0]) << out;
  }

  // The fitness figure names what a guidance run's fitness measures.
  const std::string svg = Path("fitness.svg");
  ASSERT_EQ(Animat({"figure", "fitness", "--db", db_, "-o", svg}, &out, &err),
            0)
      << err;
  Result<std::string> text = ReadFile(svg);
  ASSERT_TRUE(text.ok()) << text.status().ToString();
  EXPECT_NE(text->find("fitness (radii closer to the source, mean)"),
            std::string::npos);
  EXPECT_EQ(text->find("radii swum"), std::string::npos);
}

// A store written by schema version 2 or 3 (the same run, its rows copied
// into that version's schema) is refused by the questions with a pointer to
// `animat lineage upgrade`, which brings it to this build's schema: then it
// holds what the original holds, but for the body columns, which are NULL,
// and answers the same.
TEST_F(EvolveCliTest, UpgradeBringsAnOlderStoreToThisSchema) {
  TestRun run;
  run.seed = 23;
  run.generations = 2;
  config_ = WriteConfig("run.txtpb", run);
  db_ = Path("current.db");
  Evolve(2);
  if (HasFatalFailure()) return;
  // The columns of individuals up to version 3, and those version 4 added.
  const std::string old_columns =
      "run_id, id, generation, operators, genome, genome_hash, elements,"
      " created_at, status, reason, fitness, cells, steps, wall_seconds,"
      " worker, state_hash, evaluated_at";
  const std::string body_columns =
      "springs, chambers, skin_edges, spread_major, spread_minor";
  ASSERT_GT(QueryInt(db_,
                     "SELECT COUNT(*) FROM individuals WHERE chambers"
                     " IS NOT NULL"),
            0);
  const std::map<int, std::string> copy_individuals = {
      {2, "INSERT INTO individuals SELECT " + old_columns +
              " FROM current.individuals;"},
      {3,
       "INSERT INTO births SELECT * FROM current.births;"
       "INSERT INTO evaluations SELECT run_id, id, status, reason, fitness,"
       " cells, steps, wall_seconds, worker, state_hash, evaluated_at"
       " FROM current.evaluations;"}};
  for (const auto& [version, copy] : copy_individuals) {
    SCOPED_TRACE("schema version " + std::to_string(version));
    const std::string old_db =
        Path(std::string("v") + std::to_string(version) + ".db");
    {
      Result<std::unique_ptr<sql::Database>> db = sql::Database::Open(old_db);
      ASSERT_TRUE(db.ok()) << db.status().ToString();
      ASSERT_TRUE(lineage::Migrate(**db, version).ok());
      const Status copied = (*db)->Execute(
          "ATTACH DATABASE '" + db_ +
          "' AS current;"
          "INSERT INTO runs SELECT * FROM current.runs;" +
          copy +
          "INSERT INTO parents SELECT * FROM current.parents;"
          "INSERT INTO generations SELECT * FROM current.generations;"
          "INSERT INTO members SELECT * FROM current.members;"
          "DETACH DATABASE current;");
      ASSERT_TRUE(copied.ok()) << copied.ToString();
    }
    std::string out, err;
    EXPECT_NE(Animat({"lineage", "best", "--db", old_db}, &out, &err), 0);
    EXPECT_NE(err.find("schema version " + std::to_string(version)),
              std::string::npos)
        << err;
    EXPECT_NE(err.find("animat lineage upgrade --db " + old_db),
              std::string::npos)
        << err;

    ASSERT_EQ(Animat({"lineage", "upgrade", "--db", old_db}, &out, &err), 0)
        << err;
    EXPECT_EQ(out, old_db + ": upgraded from schema version " +
                       std::to_string(version) + " to " +
                       std::to_string(lineage::kSchemaVersion) + "\n");
    for (const char* table : {"runs", "parents", "generations", "members"}) {
      const std::string query =
          std::string("SELECT * FROM ") + table + " ORDER BY 1, 2, 3";
      EXPECT_EQ(QueryRows(old_db, query), QueryRows(db_, query)) << table;
    }
    const std::string individuals =
        "SELECT " + old_columns + " FROM individuals ORDER BY 1, 2, 3";
    EXPECT_EQ(QueryRows(old_db, individuals), QueryRows(db_, individuals));
    EXPECT_EQ(QueryInt(old_db,
                       "SELECT COUNT(*) FROM individuals WHERE"
                       " COALESCE(" +
                           body_columns + ") IS NOT NULL"),
              0);
    std::string best_old, best_current;
    ASSERT_EQ(Animat({"lineage", "best", "--db", old_db}, &best_old, &err), 0)
        << err;
    ASSERT_EQ(Animat({"lineage", "best", "--db", db_}, &best_current, &err), 0)
        << err;
    // The same but for the body, which the old store did not record.
    EXPECT_EQ(best_current.rfind(best_old, 0), 0u) << best_current;
    EXPECT_EQ(Lines(best_old).size(), 4u) << best_old;
    EXPECT_NE(best_current.find("\nchambers: "), std::string::npos)
        << best_current;

    ASSERT_EQ(Animat({"lineage", "upgrade", "--db", old_db}, &out, &err), 0)
        << err;
    EXPECT_EQ(out, old_db + ": already at schema version " +
                       std::to_string(lineage::kSchemaVersion) + "\n");
  }
  std::string out, err;
  const std::string missing = Path("missing.db");
  EXPECT_NE(Animat({"lineage", "upgrade", "--db", missing}, &out, &err), 0);
  EXPECT_NE(err.find(missing + ": no such lineage store"), std::string::npos)
      << err;
  EXPECT_FALSE(std::filesystem::exists(missing));
}

TEST_F(EvolveCliTest, BadArgumentsGetAClearErrorAndANonZeroExit) {
  TestRun run;
  run.seed = 40;
  run.generations = 1;
  config_ = WriteConfig("run.txtpb", run);
  db_ = Path("small.db");
  Evolve(1);
  if (HasFatalFailure()) return;

  struct Case {
    std::vector<std::string> args;
    std::string message;  // What the error must say.
  };
  const std::string missing = Path("missing.db");
  const std::vector<Case> cases = {
      {{"lineage", "best", "--db", missing},
       missing + ": no such lineage store"},
      {{"lineage", "ancestors", "99999999", "--db", db_},
       "no individual 99999999"},
      {{"lineage", "genome", "99999999", "--db", db_, "-o", Path("g.json")},
       "no individual 99999999"},
      {{"lineage", "best", "--db", db_, "--run", "7"}, "no run 7"},
      {{"lineage", "export", "--format", "newick", "--db", db_},
       "--format: only alife"},
      {{"lineage", "genome", "1", "--db", db_}, "--output is required"},
      {{"lineage", "ancestors", "x", "--db", db_}, "id"},
      {{"evolve", "--config", Path("missing.txtpb"), "--db", Path("new.db")},
       Path("missing.txtpb")},
      {{"evolve", "--db", Path("new.db")},
       Path("new.db") +
           ": no such lineage store; --config is needed to start a run"},
      {{"evolve", "--config", config_}, "--db is required"},
      // The store's path, and what is wrong with it, in words.
      {{"lineage", "best", "--db", Path("")}, Path("") + " is a directory"},
      {{"evolve", "--config", config_, "--db", Path("nowhere/x.db")},
       "cannot create " + Path("nowhere/x.db") + ": the folder " +
           Path("nowhere") + " does not exist"},
  };
  for (const Case& c : cases) {
    std::string joined;
    for (const std::string& a : c.args) joined += " " + a;
    SCOPED_TRACE("animat" + joined);
    std::string out, err;
    EXPECT_NE(Animat(c.args, &out, &err), 0);
    EXPECT_NE(err.find(c.message), std::string::npos) << err;
  }
  // Nothing was made on the way.
  EXPECT_FALSE(std::filesystem::exists(Path("g.json")));
  EXPECT_FALSE(std::filesystem::exists(Path("new.db")));
  EXPECT_FALSE(std::filesystem::exists(missing));
  EXPECT_FALSE(std::filesystem::exists(Path("nowhere")));
}

}  // namespace
}  // namespace animat::testing
