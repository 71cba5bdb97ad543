#!/usr/bin/env python3
"""A run's record: what the reports of docs/results.md need from one
lineage store, small enough to keep in the repository when the store is
not kept (a store of 150 generations is about 100 MB; its record is about
40 kB).

  scripts/run_record.py --db out/v3/dn1-seed1.db --name v3-dn1-seed1 \\
      [--animat BIN/animat] [--top 5] [--overlap-bound 0.1] \\
      [--dest docs/results/runs]

Writes DEST/NAME/:
- record.json: the run's configuration (text), build id, seed, generations
  completed, each generation's statistics, the statuses of its initial
  genomes (generation 0, every one tried) and of its offspring,
  its best, the deepest unjoined overlap of its ok individuals and how many
  lie above --overlap-bound (docs/model.md §8.6), and its last completed
  generation's --top distinct phenotypes (ok members by fitness, each state
  hash once: the rule of `animat cluster --top`), each with its state hash,
  fitness and how many members share it;
- NAME-ID.json and NAME-ID.config.txtpb for the best and each phenotype:
  its genome and the model it ran under, so that `animat simulate
  --genome NAME-ID.json --config NAME-ID.config.txtpb` re-simulates it to
  the state hash recorded.

Every number comes from the store by SQL (read only); the genomes are
written by `animat lineage genome`. Exit 0 when written, 1 when the store
cannot be read or holds no completed generation, 2 on a usage error.
Standard library only.
"""

import argparse
import json
import os
import sqlite3
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from replication_report import model_text, write_model  # noqa: E402


def query_all(db, sql, args=()):
    return [dict(r) for r in db.execute(sql, args)]


def top_phenotypes(db, run_id, generation, top):
    """The fittest ok members of GENERATION, each state hash once (fitness
    descending, then id), with the members sharing each hash."""
    found = []
    for r in db.execute(
            "SELECT m.id, e.fitness, e.state_hash FROM members m"
            " JOIN evaluations e ON e.run_id = m.run_id AND e.id = m.id"
            " WHERE m.run_id = ? AND m.generation = ? AND e.status = 'ok'"
            " AND e.fitness IS NOT NULL ORDER BY e.fitness DESC, m.id",
            (run_id, generation)):
        same = [p for p in found if r["state_hash"] and
                p["state_hash"] == r["state_hash"]]
        if same:
            same[0]["members"] += 1
        else:
            found.append({"id": r["id"], "fitness": r["fitness"],
                          "state_hash": r["state_hash"], "members": 1})
    return found[:top]


def overlap_counts(db, run_id, bound):
    """The run's ok individuals, their deepest unjoined overlap (a fraction
    of r_i + r_j, docs/model.md §8.6; None without one) and how many lie
    above `bound`."""
    ok, deepest, above = db.execute(
        "SELECT COUNT(*), MAX(max_overlap), COALESCE(SUM(max_overlap > ?), 0)"
        " FROM individuals WHERE run_id = ? AND status = 'ok'",
        (bound, run_id)).fetchone()
    return {"bound": bound, "ok": ok, "deepest": deepest,
            "above_bound": above}


def overlap_bound(text):
    """argparse type of --overlap-bound: a finite fraction >= 0."""
    try:
        bound = float(text)
    except ValueError:
        bound = float("nan")
    if not 0.0 <= bound < float("inf"):
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a finite fraction >= 0")
    return bound


def read_store(path, top, bound):
    """Everything the record holds but the genomes."""
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    db.row_factory = sqlite3.Row
    try:
        run = db.execute(
            "SELECT run_id, seed, config_text, build_id, state FROM runs "
            "ORDER BY run_id DESC LIMIT 1").fetchone()
        if run is None:
            raise ValueError("no run")
        run_id = run["run_id"]
        stats = query_all(
            db, "SELECT generation, size, evaluated, failed, best_id, "
            "best_fitness, mean_fitness, median_fitness FROM "
            "generation_statistics WHERE run_id = ? AND completed_at IS NOT "
            "NULL ORDER BY generation", (run_id,))
        if not stats:
            raise ValueError("no completed generation")
        last = stats[-1]["generation"]
        best = dict(db.execute(
            "SELECT id, generation, fitness, state_hash, cells, springs, "
            "chambers, skin_edges, max_overlap FROM individuals WHERE "
            "run_id = ? AND id = ?", (run_id, stats[-1]["best_id"])).fetchone())
        statuses = {}
        for part, test in (("initial", "= 0"), ("offspring", "> 0")):
            statuses[part] = {r[0]: r[1] for r in db.execute(
                "SELECT status, COUNT(*) FROM individuals WHERE run_id = ? "
                f"AND generation {test} AND status IS NOT NULL GROUP BY "
                "status ORDER BY status", (run_id,))}
        return {
            "seed": run["seed"], "build_id": run["build_id"],
            "state": run["state"], "config_text": run["config_text"],
            "generations": last + 1, "statistics": stats, "best": best,
            "statuses": statuses,
            "overlap": overlap_counts(db, run_id, bound),
            "phenotypes": top_phenotypes(db, run_id, last, top),
        }
    finally:
        db.close()


def write_genome(animat, db, name, ident, model, dest):
    stem = os.path.join(dest, f"{name}-{ident}")
    result = subprocess.run(
        [animat, "lineage", "genome", str(ident), "--db", db, "-o",
         stem + ".json"], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"run_record.py: {db}: individual {ident}: "
                 f"{result.stderr.strip()}")
    write_model(stem + ".config.txtpb", f"The model of run {name}.", model)
    return os.path.basename(stem)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--db", required=True)
    parser.add_argument("--name", required=True)
    parser.add_argument("--animat", default="build/bin/animat")
    parser.add_argument("--top", type=int, default=5)
    parser.add_argument("--overlap-bound", type=overlap_bound, default=0.1)
    parser.add_argument("--dest", default="docs/results/runs")
    args = parser.parse_args()
    if args.top < 1:
        parser.error("--top must be at least 1")
    if not os.path.isfile(args.db):
        sys.exit(f"run_record.py: {args.db}: no such store")
    try:
        record = read_store(args.db, args.top, args.overlap_bound)
    except (sqlite3.Error, ValueError) as e:
        sys.exit(f"run_record.py: {args.db}: {e}")
    dest = os.path.join(args.dest, args.name)
    os.makedirs(dest, exist_ok=True)
    model = model_text(record["config_text"])
    for entry in [record["best"]] + record["phenotypes"]:
        entry["genome"] = write_genome(args.animat, args.db, args.name,
                                       entry["id"], model, dest)
    record["run"] = args.name
    record["top"] = args.top
    with open(os.path.join(dest, "record.json"), "w") as f:
        json.dump(record, f, indent=1, sort_keys=True)
        f.write("\n")
    print(f"{dest}: {record['generations']} generations, best "
          f"{record['best']['fitness']:.4g}, {len(record['phenotypes'])} "
          f"phenotypes, {record['overlap']['above_bound']} of "
          f"{record['overlap']['ok']} ok above {args.overlap_bound:g}")


if __name__ == "__main__":
    main()
