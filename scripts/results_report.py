#!/usr/bin/env python3
"""The third edition's runs (docs/results.md): from the run records
(scripts/run_record.py), a table of every run with its build, the fitness
curves of each condition, each run's best kept in docs/results/bests/ and
simulated again from those files, and Fig. 4-style panels with a replay
page for one phenotype of each label that scripts/strategy_report.py found.

  scripts/results_report.py --animat build/bin/animat \\
      --condition 'v3-dn0.1=docs/results/runs/v3-dn0.1-seed*' ... \\
      [--strategies docs/results/strategies.json] \\
      [--dest docs/results/third] [--bests docs/results/bests]

- A condition is a name and a glob of run-record folders.
- The bests: each run's best genome and model, copied to BESTS/RUN-ID.json
  and RUN-ID.config.txtpb, then simulated from there by --animat; its
  fitness must equal the record's to the last bit and its final-state
  hash the record's (the tests check these files again).
- The panels (with --strategies, the JSON of strategy_report.py over the
  same records): for each label found, the phenotype that carries it most
  clearly (stable under the classifier's ±20% test first, then the widest
  margin, then the fittest), drawn by `animat figure strip|activity|cells`
  and `animat render`.

- The claims' measurements (docs/results.md, "The paper's claims"), per
  run: the best against generation 0's best; the cells of the best and of
  each phenotype (simulated); how the best's centre of mass moves within
  its strokes (steps moving backward, quiet steps and the speed while
  quiet: replication_report.py's glide); with --strategies, Spearman's
  rank correlation of amplitude and frequency over the run's phenotypes
  ("undefined", null in the JSON, when they share one amplitude or one
  period); and pooled per condition, that correlation and the
  phenotypes' amplitudes.

Writes DEST/runs.json (every number), DEST/runs.md (the tables),
DEST/fitness-CONDITION.svg and the panels. Exit 0 when every best replays
and every figure was drawn, 1 otherwise, 2 on a usage error. Standard
library only.
"""

import argparse
import glob
import json
import math
import os
import shutil
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from replication_report import glide, spearman  # noqa: E402
from replication_report import try_run as tool  # noqa: E402
from strategy_report import (natural_key, parse_pairs,  # noqa: E402
                             read_json_object, read_record)

PANELS = ("strip", "activity", "cells")


def read_records(conditions):
    """[(condition, folder, record)] in the order given, each condition's
    folders in natural order."""
    out = []
    for name, pattern in conditions:
        folders = sorted((p for p in glob.glob(pattern)
                          if os.path.isfile(os.path.join(p, "record.json"))),
                         key=natural_key)
        if not folders:
            sys.exit(f"results_report.py: {name}: no run record matches "
                     f"{pattern!r}")
        for folder in folders:
            out.append((name, folder, read_record(folder)))
    return out


def keep_best(animat, folder, record, bests, problems):
    """Copies the run's best to BESTS and simulates it from there; returns
    the copy's path (without .json) and whether it gave the record's
    fitness bits and state hash."""
    best = record["best"]
    stem = os.path.join(bests, best["genome"])
    for ext in (".json", ".config.txtpb"):
        shutil.copyfile(os.path.join(folder, best["genome"] + ext), stem + ext)
    out = tool([animat, "simulate", "--genome", stem + ".json", "--config",
                stem + ".config.txtpb", "--json"], problems)
    if out is None:
        return stem, False
    again = json.loads(out)
    same = (again.get("fitness") is not None and
            float.hex(again["fitness"]) == float.hex(best["fitness"]) and
            again.get("state_hash") == best["state_hash"])
    if not same:
        problems.append(f"{stem}.json: stored fitness {best['fitness']!r} "
                        f"and hash {best['state_hash']}, simulated again "
                        f"{again.get('fitness')!r} and "
                        f"{again.get('state_hash')}")
    return stem, same


def labels_of(strategies):
    """{run: best_label}, every phenotype, and {run: [its phenotypes'
    features]}, from strategy_report's JSON."""
    best, phenotypes, features = {}, [], {}
    for condition in strategies["conditions"]:
        for run in condition["runs"]:
            best[run["run"]] = run["best_label"]
            phenotypes += run["phenotypes"]
            features[run["run"]] = [p["features"] for p in run["phenotypes"]]
    return best, phenotypes, features


def clearest(phenotypes):
    """{label: the phenotype that carries it most clearly}."""
    chosen = {}
    for p in phenotypes:
        key = (p["stable"], p["margin"], p["fitness"])
        old = chosen.get(p["label"])
        if old is None or key > (old["stable"], old["margin"], old["fitness"]):
            chosen[p["label"]] = p
    return chosen


def draw_panels(animat, chosen, folders, dest, problems):
    """The panels and replay page of each chosen phenotype; returns
    {label: file stem}."""
    drawn = {}
    for label in sorted(chosen):
        p = chosen[label]
        genome = os.path.join(folders[p["run"]], f"{p['run']}-{p['id']}")
        source = ["--genome", genome + ".json",
                  "--config", genome + ".config.txtpb"]
        base = os.path.join(dest, f"{label}-{p['run']}-{p['id']}")
        ok = all(tool([animat, "figure", kind, *source, "-o",
                       f"{base}-{kind}.svg"], problems) is not None
                 for kind in PANELS)
        ok = tool([animat, "render", *source, "--every", "10", "-o",
                   base + ".html"], problems) is not None and ok
        drawn[label] = {"stem": os.path.basename(base), "run": p["run"],
                        "id": p["id"], "fitness": p["fitness"],
                        "margin": p["margin"], "stable": p["stable"],
                        "drawn": ok}
    return drawn


def cells_of(animat, folder, genome, problems):
    """The cells of a record's animat, simulated again."""
    stem = os.path.join(folder, genome)
    out = tool([animat, "simulate", "--genome", stem + ".json", "--config",
                stem + ".config.txtpb", "--json"], problems)
    return json.loads(out).get("cells") if out is not None else None


def trade(points):
    """Spearman's rho of amplitude against frequency over phenotypes with
    both, and their count: None below three points, or when every point
    has the same amplitude or the same period (no ranks to correlate)."""
    points = [p for p in points if p["period_steps"] and
              p["amplitude_mean"] is not None]
    if len(points) < 3:
        return None, len(points)
    rho = spearman([p["amplitude_mean"] for p in points],
                   [1.0 / p["period_steps"] for p in points])
    return (None if math.isnan(rho) else rho), len(points)


def rho_text(rho, n):
    """A Spearman cell: the value, "—" below three points, "undefined"
    when one variable is constant."""
    return "undefined" if rho is None and n >= 3 else number(rho, "+.2f")


def claims_of(animat, folder, record, stem, features, problems):
    """One run's measurements for the claims table."""
    best = record["best"]
    rho, n = trade(features)
    return {
        "best_over_generation_0": best["fitness"] /
        record["statistics"][0]["best_fitness"],
        "best_cells": best["cells"],
        "phenotype_cells": [cells_of(animat, folder, p["genome"], problems)
                            for p in record["phenotypes"]],
        "glide": glide(animat, stem + ".json", stem + ".config.txtpb"),
        "spearman_amplitude_frequency": rho,
        "spearman_points": n,
    }


def pooled(conditions, rows, features_of):
    """Per condition, and over all when there are several ("all"): the
    amplitude-frequency trade and the amplitudes over every phenotype of
    its runs."""
    out = {}
    names = [name for name, _ in conditions]
    for name in names + (["all"] if len(names) > 1 else []):
        points = [f for r in rows if name in (r["condition"], "all")
                  for f in features_of.get(r["run"], [])]
        rho, n = trade(points)
        amplitudes = [p["amplitude_mean"] for p in points
                      if p["amplitude_mean"] is not None]
        out[name] = {
            "spearman_amplitude_frequency": rho, "phenotypes": n,
            "amplitude_median": statistics.median(amplitudes)
            if amplitudes else None,
            "amplitude_max": max(amplitudes, default=None),
        }
    return out


def run_row(name, record, stem, same, best_label, claims):
    stats = record["statistics"]
    best = record["best"]
    return {
        "condition": name, "run": record["run"],
        "build": record["build_id"], "seed": record["seed"],
        "generations": record["generations"], "state": record["state"],
        "best_at_0": stats[0]["best_fitness"],
        "best": best, "best_genome": os.path.relpath(stem + ".json"),
        "replays": same, "best_label": best_label,
        "last_mean": stats[-1]["mean_fitness"],
        "last_median": stats[-1]["median_fitness"],
        "overlap": record["overlap"], "claims": claims,
    }


def table(rows):
    lines = ["| condition | run | build | generations | best at 0 | best (id, "
             "generation) | last mean | cells, springs, chambers, skin "
             "| ok individuals | deepest unjoined overlap | above the bound "
             "| best's label | replays |",
             "|---|---|---|---:|---:|---|---:|---|---:|---:|---:|---|---|"]
    for r in rows:
        b, o = r["best"], r["overlap"]
        build = r["build"].split()[2] if len(r["build"].split()) > 2 else \
            r["build"]
        lines.append(
            f"| {r['condition']} | {r['run']} | {build} | "
            f"{r['generations']} | {r['best_at_0']:.2f} | "
            f"**{b['fitness']:.2f}** ({b['id']}, {b['generation']}) | "
            f"{r['last_mean']:.2f} | {b['cells']}, {b['springs']}, "
            f"{b['chambers']}, {b['skin_edges']} | {o['ok']:,} | "
            f"{o['deepest']:.3f} | {o['above_bound']} | "
            f"{r['best_label'] or '—'} | "
            f"{'same bits' if r['replays'] else 'NO'} |")
    return "\n".join(lines) + "\n"


def number(x, form):
    return "—" if x is None else format(x, form)


def claims_table(rows):
    lines = ["| run | best / best at generation 0 | cells: best; phenotypes "
             "with 32 | steps moving backward | quiet steps | speed while "
             "quiet / mean | Spearman (amplitude, frequency), phenotypes |",
             "|---|---:|---|---:|---:|---:|---:|"]
    for r in rows:
        c = r["claims"]
        g = c["glide"] or {}
        cells = c["phenotype_cells"]
        rho = c["spearman_amplitude_frequency"]
        lines.append(
            f"| {r['run']} | {c['best_over_generation_0']:.1f} | "
            f"{c['best_cells']}; {sum(x == 32 for x in cells)} of "
            f"{len(cells)} | {number(g.get('backward_share'), '.0%')} | "
            f"{number(g.get('quiet_share'), '.0%')} | "
            f"{number(g.get('quiet_speed'), '+.2f')} | "
            f"{rho_text(rho, c['spearman_points'])} "
            f"({c['spearman_points']}) |")
    return "\n".join(lines) + "\n"


def pooled_table(conditions):
    lines = ["| condition | Spearman (amplitude, frequency), pooled | "
             "phenotypes | amplitude: median, largest |",
             "|---|---:|---:|---|"]
    for name, c in conditions.items():
        lines.append(
            f"| {name} | "
            f"{rho_text(c['spearman_amplitude_frequency'], c['phenotypes'])}"
            f" | {c['phenotypes']} | {number(c['amplitude_median'], '.2f')}, "
            f"{number(c['amplitude_max'], '.2f')} |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--animat", default="build/bin/animat")
    parser.add_argument("--condition", action="append", default=[],
                        help="NAME=GLOB of run-record folders (repeatable)")
    parser.add_argument("--strategies", default=None,
                        help="strategy_report.py's JSON over the same runs")
    parser.add_argument("--dest", default="docs/results/third")
    parser.add_argument("--bests", default="docs/results/bests")
    args = parser.parse_args()
    if not args.condition:
        parser.error("give at least one --condition NAME=GLOB")
    conditions = parse_pairs(args.condition, "--condition")
    records = read_records(conditions)
    os.makedirs(args.dest, exist_ok=True)
    os.makedirs(args.bests, exist_ok=True)
    best_label, phenotypes, features_of = {}, [], {}
    if args.strategies:
        best_label, phenotypes, features_of = labels_of(
            read_json_object(args.strategies, ("conditions",)))

    problems, rows = [], []
    for name, folder, record in records:
        stem, same = keep_best(args.animat, folder, record, args.bests,
                               problems)
        claims = claims_of(args.animat, folder, record, stem,
                           features_of.get(record["run"], []), problems)
        rows.append(run_row(name, record, stem, same,
                            best_label.get(record["run"]), claims))
    for name, _ in conditions:
        folders = [x for c, folder, _ in records if c == name
                   for x in ("--record", folder)]
        tool([args.animat, "figure", "fitness", *folders, "-o",
              os.path.join(args.dest, f"fitness-{name}.svg")], problems)
    folders = {r["run"]: folder for _, folder, r in records}
    known = [p for p in phenotypes if p["run"] in folders]
    panels = draw_panels(args.animat, clearest(known), folders, args.dest,
                         problems)

    per_condition = pooled(conditions, rows, features_of)
    with open(os.path.join(args.dest, "runs.json"), "w") as f:
        json.dump({"runs": rows, "panels": panels,
                   "conditions": per_condition,
                   "problems": problems}, f, indent=1, sort_keys=True,
                  allow_nan=False)
    with open(os.path.join(args.dest, "runs.md"), "w") as f:
        f.write(table(rows) + "\n" + claims_table(rows) + "\n" +
                pooled_table(per_condition))
    for problem in problems:
        print(problem, file=sys.stderr)
    print(f"{len(rows)} runs, {sum(r['replays'] for r in rows)} bests "
          f"replay, {len(panels)} labels drawn", file=sys.stderr)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
