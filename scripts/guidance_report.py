#!/usr/bin/env python3
"""Reads the guidance runs' stores (configs/guidance.txtpb evolved by
`scripts/seeded_runs.sh --config configs/guidance.txtpb --name guidance`)
and writes what docs/results.md reports under "Active guidance": per run
the best's score, the final distance to each trial's source, whether it
ends closer to all of them, its knock-outs (the chemical and each
morphogen silenced during motion, `animat analyze --knockouts`), and per
generation the share of the population that ends closer to every source,
and the run's ok individuals with their deepest unjoined overlap and how
many lie above --overlap-bound.

  scripts/guidance_report.py [--name guidance] [--out out/NAME]
      [--dest docs/results] [--animat build/bin/animat]
      [--overlap-bound 0.1]

NAME names the runs (default guidance): their stores are NAME-seedS.db,
as scripts/seeded_runs.sh --name NAME or a campaign's runs named NAME
write them (e.g. guidance-lead, configs/guidance-lead.txtpb).

Only Python's standard library; the simulator work is done by `animat`
(lineage, simulate, analyze, figure, render). Writes DEST/NAME.json
(every number), DEST/NAME.md (the tables), for each run
DEST/NAME-seedS-trials.svg (the best's K paths around their sources),
DEST/NAME-seedS-untrained.svg (its paths with 2K sources, all in
directions between the K it evolved with),
its score with the sources at other distances (FARTHER),
DEST/NAME-seedS.html (the best's replay page, trial 0),
DEST/NAME-fitness.svg (every run's best, mean and median score per
generation) and the bests' genomes and models in DEST/bests/. A trial
"ends closer" to its source when it ends at least CLOSER radii closer.
A run still going is reported as far as it has gone.
"""

import argparse
import json
import os
import re
import sqlite3
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import replication_report as rr  # noqa: E402  (its store and analysis code)
from run_record import overlap_bound, overlap_counts  # noqa: E402

# A trial counts as ending closer to its source when it ends at least this
# much closer (radii): a body that does not swim drifts by about 1e-8.
CLOSER = 0.01

# Source distances (radii) the bests are tried at besides the run's own.
FARTHER = (15.0, 45.0, 60.0)


def guidance_of(model_text):
    """K and D of the run's model (docs/model.md §10.2 defaults if absent)."""
    trials = re.search(r"\btrials: ([0-9]+)", model_text)
    distance = re.search(r"\bsource_distance: ([0-9.e+]+)", model_text)
    return (int(trials.group(1)) if trials else 4,
            float(distance.group(1)) if distance else 30.0)


def closer_count(distances, source_distance):
    """How many trials end at least CLOSER nearer their source than D."""
    return sum(1 for d in distances if d < source_distance - CLOSER)


def trial_summary(result, source_distance):
    """A simulation's status, score, final distances and closer count."""
    ds = result.get("source_distances", [])
    return {"status": result["status"], "fitness": result.get("fitness"),
            "source_distances": ds,
            "closer": closer_count(ds, source_distance)}


def distances_text(distances):
    return " ".join(f"{d:.2f}" for d in distances)


def closer_by_generation(path, run_id, source_distance):
    """Per completed generation: members ok, and of them those that end
    closer than they started to every trial's source by CLOSER (from
    `trials`)."""
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    rows = db.execute(
        "SELECT m.generation, COUNT(*),"
        " SUM(t.farthest < ?) FROM members m"
        " JOIN generations g ON g.run_id = m.run_id"
        "  AND g.generation = m.generation AND g.completed_at IS NOT NULL"
        " JOIN (SELECT run_id, id, MAX(source_distance) AS farthest"
        "       FROM trials GROUP BY run_id, id) t"
        "  ON t.run_id = m.run_id AND t.id = m.id"
        " WHERE m.run_id = ? GROUP BY m.generation ORDER BY m.generation",
        (source_distance - CLOSER, run_id)).fetchall()
    db.close()
    return [{"generation": g, "ok": n, "closer_to_all": c}
            for g, n, c in rows]


def overlap(path, run_id, bound):
    """The run's ok individuals, their deepest unjoined overlap and how
    many lie above `bound` (run_record.overlap_counts)."""
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    try:
        return overlap_counts(db, run_id, bound)
    finally:
        db.close()


def simulate(animat, genome, config):
    return json.loads(rr.run([animat, "simulate", "--genome", genome,
                              "--config", config, "--json"]))


def with_guidance(model_text, field, value):
    """MODEL_TEXT with guidance's FIELD set to VALUE."""
    text = re.sub(rf"\b{field}: [0-9.e+]+", f"{field}: {value}", model_text)
    if text == model_text:
        text = model_text.replace("guidance {",
                                  f"guidance {{\n  {field}: {value}")
    return text


def untrained(animat, stem, model_text, dest, name):
    """The best with sources in UNTRAINED directions: 2K trials, whose
    angles 2 pi (k + 1/2) / 2K all lie between the K trained ones. Returns
    the simulation and draws its paths (DEST/NAME-untrained.svg)."""
    trials, _ = guidance_of(model_text)
    config = stem + ".untrained.config.txtpb"
    rr.write_model(config, f"The model of run {name} with {2 * trials} "
                   "trials, in directions the run never saw "
                   "(docs/results.md).",
                   with_guidance(model_text, "trials", 2 * trials))
    rr.run([animat, "figure", "guidance", "--genome", stem + ".json",
            "--config", config, "--every", "10", "-o",
            os.path.join(dest, f"{name}-untrained.svg")])
    return simulate(animat, stem + ".json", config)


def other_distances(animat, stem, model_text):
    """The best with its sources nearer and farther than the run's D (the
    trained directions): per distance in FARTHER, its score and final
    distances."""
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for distance in FARTHER:
            config = os.path.join(tmp, f"d{distance:g}.config.txtpb")
            with open(config, "w") as f:
                f.write(with_guidance(model_text, "source_distance",
                                      f"{distance:g}"))
            out.append({"source_distance": distance, **trial_summary(
                simulate(animat, stem + ".json", config), distance)})
    return out


def knockouts(animat, db, individual):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "knockouts.json")
        rr.run([animat, "analyze", "--db", db, "--individual",
                str(individual), "--knockouts", "-o", path])
        with open(path) as f:
            return json.load(f)


def knockout_rows(name, k, source_distance):
    """The table rows of one best's knock-outs."""
    rows = []
    for entry in [k["intact"]] + k.get("knockout", []):
        kind = entry.get("kind", "NONE")
        if kind == "NONE":
            what = "nothing (intact)"
        elif kind == "CHEMICAL":
            what = "CHEMICAL"
        else:
            what = (f"M of unit_{entry.get('unit_element', 0)} "
                    f"(node {entry.get('node', 0)})")
        r = entry["result"]
        ds = r.get("source_distances", [])
        closer = closer_count(ds, source_distance)
        change = entry.get("fitness_change")
        paths = "".join([
            "from CHEMICAL " if entry.get("chemical_path") else "",
            "to actuators" if entry.get("actuator_path") else ""]).strip()
        rows.append(
            f"| {name} | {what} | {r.get('status', '').lower()} | "
            + (f"{r['fitness']:.4g}" if "fitness" in r else "—") + " | "
            + (f"{change:+.4g}" if change is not None else "—") + " | "
            + (f"{r['distance']:.2f}" if "distance" in r else "—") + " | "
            + f"{closer}/{len(ds)} | "
            + distances_text(ds) + f" | {paths or '—'} |")
    return rows


def report_run(animat, path, name, seed, dest, bound):
    s = rr.store_summary(path)
    trials, source_distance = guidance_of(s["model_text"])
    best = s["best"]
    stem = rr.write_best(animat, path, name, best["id"], s["model_text"],
                         dest)
    config = stem + ".config.txtpb"
    again = simulate(animat, stem + ".json", config)
    if float.hex(again["fitness"]) != float.hex(best["fitness"]):
        sys.exit(f"{stem}: simulated again, fitness {again['fitness']} "
                 f"is not the stored {best['fitness']}")
    figure = os.path.join(dest, f"{name}-trials.svg")
    rr.run([animat, "figure", "guidance", "--genome", stem + ".json",
            "--config", config, "--every", "10", "-o", figure])
    rr.run([animat, "render", "--genome", stem + ".json", "--config", config,
            "--every", "20", "-o", os.path.join(dest, f"{name}.html")])
    distances = again["source_distances"]
    other = untrained(animat, stem, s["model_text"], dest, name)
    return {
        "name": name, "seed": seed, "trials": trials,
        "source_distance": source_distance,
        "generations": s["generations"], "initial_tried": s["initial_tried"],
        "best_id": best["id"], "best_generation": best["generation"],
        "fitness": best["fitness"], "distance": again["distance"],
        "energy": again["energy"], "source_distances": distances,
        "closer": closer_count(distances, source_distance),
        "genome": stem + ".json",
        "untrained": trial_summary(other, source_distance),
        "other_distances": other_distances(animat, stem, s["model_text"]),
        "curve": [x["best_fitness"] for x in s["stats"]],
        "closer_by_generation": closer_by_generation(
            path, s["run_id"], source_distance),
        "knockouts": knockouts(animat, path, best["id"]),
        "overlap": overlap(path, s["run_id"], bound),
    }


def tables(runs):
    lines = [
        "| run | generations | random genomes tried | best (generation) | "
        "score | distance swum | ends closer to | final distances to the "
        "sources (start: D) |",
        "|---|---:|---:|---|---:|---:|---:|---|"]
    for r in runs:
        lines.append(
            f"| {r['name']} | {r['generations']} | {r['initial_tried']:,} | "
            f"{r['best_id']} (g{r['best_generation']}) | {r['fitness']:.4g} |"
            f" {r['distance']:.2f} | {r['closer']}/{r['trials']} | "
            + distances_text(r["source_distances"]) + " |")
    lines += ["", "| run | untrained directions | status | score | ends "
              "closer to | final distances |", "|---|---:|---|---:|---:|---|"]
    for r in runs:
        u = r["untrained"]
        ds = u["source_distances"]
        lines.append(
            f"| {r['name']} | {len(ds)} | {u['status'].lower()} | "
            + (f"{u['fitness']:.4g}" if u["fitness"] is not None else "—")
            + f" | {u['closer']}/{len(ds)} | " + distances_text(ds) + " |")
    lines += ["", "| run | source distance D | status | score | score / D | "
              "ends closer to | final distances |",
              "|---|---:|---|---:|---:|---:|---|"]
    for r in runs:
        own = {"source_distance": r["source_distance"], "status": "ok",
               "fitness": r["fitness"],
               "source_distances": r["source_distances"],
               "closer": r["closer"]}
        for o in sorted(r["other_distances"] + [own],
                        key=lambda o: o["source_distance"]):
            ds = o["source_distances"]
            fit = o["fitness"]
            lines.append(
                f"| {r['name']} | {o['source_distance']:g} | "
                f"{o['status'].lower()} | "
                + (f"{fit:.4g} | {fit / o['source_distance']:.1%}"
                   if fit is not None else "— | —")
                + f" | {o['closer']}/{len(ds)} | " + distances_text(ds) + " |")
    lines += ["", "| run | generation | members ok | closer to every "
              "source |", "|---|---:|---:|---:|"]
    for r in runs:
        per = r["closer_by_generation"]
        step = max(1, len(per) // 5)
        for p in per[::step] + ([per[-1]] if (len(per) - 1) % step else []):
            lines.append(f"| {r['name']} | {p['generation']} | {p['ok']} | "
                         f"{p['closer_to_all']} |")
    lines += ["", "| run | ok individuals | deepest unjoined overlap | "
              "above the bound |", "|---|---:|---:|---:|"]
    for r in runs:
        o = r["overlap"]
        deepest = "—" if o["deepest"] is None else f"{o['deepest']:.1%}"
        lines.append(f"| {r['name']} | {o['ok']:,} | {deepest} | "
                     f"{o['above_bound']} (bound {o['bound']:.0%}) |")
    lines += ["", "| run | silenced | status | score | change | distance "
              "swum | ends closer to | final distances | paths |",
              "|---|---|---|---:|---:|---:|---:|---|---|"]
    for r in runs:
        lines += knockout_rows(r["name"], r["knockouts"],
                               r["source_distance"])
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--name", default="guidance",
                        help="the runs' name: stores NAME-seedS.db; writes "
                        "NAME.md, NAME.json and NAME-fitness.svg")
    parser.add_argument("--out", default=None,
                        help="the stores' folder (default out/NAME)")
    parser.add_argument("--dest", default="docs/results")
    # This build's animat, not the runs' copy: knock-outs may be newer
    # than the runs, and each best is checked to give its stored fitness
    # to the bit.
    parser.add_argument("--animat", default="build/bin/animat")
    parser.add_argument("--overlap-bound", type=overlap_bound, default=0.1,
                        help="the deepest unjoined overlap allowed, a "
                        "fraction of r_i + r_j (docs/model.md §8.6); ok "
                        "individuals above it are counted per run")
    args = parser.parse_args()
    animat = args.animat
    args.out = args.out or os.path.join("out", args.name)
    os.makedirs(os.path.join(args.dest, "bests"), exist_ok=True)

    runs = [report_run(animat, path, name, seed, args.dest,
                       args.overlap_bound)
            for path, name, seed in rr.seeded_stores(args.out, args.name)]
    dbs = []
    for r in runs:
        dbs += ["--db", os.path.join(args.out, r["name"] + ".db")]
    rr.run([animat, "figure", "fitness", *dbs, "-o",
            os.path.join(args.dest, f"{args.name}-fitness.svg")])
    with open(os.path.join(args.dest, f"{args.name}.md"), "w") as f:
        f.write("\n".join(tables(runs)) + "\n")
    with open(os.path.join(args.dest, f"{args.name}.json"), "w") as f:
        json.dump({"runs": runs}, f, indent=2)
        f.write("\n")
    print(f"wrote {args.dest}/{args.name}.md, {args.name}.json and each "
          "run's figures and replay page")


if __name__ == "__main__":
    main()
