#!/usr/bin/env python3
"""Reads the replication's stores (scripts/replicate.sh) and writes what
docs/results.md reports: per run the fitness over the generations, the best,
its body and strategy; per drag the fitness curves; the bests' genomes with
their model configuration; Fig. 4-style panels and a replay page for one best
of each strategy found; and the measurements behind the claim-by-claim table.

  scripts/replication_report.py [--out out/replication] [--dest docs/results]
      [--animat out/replication/bin/animat] [--top 10]

Only Python's standard library; the simulator work is done by `animat`
(lineage, analyze, figure, render). Writes DEST/replication.json (every number)
and DEST/replication.md (the tables), and the figures, genomes and pages
beside them.
"""

import argparse
import json
import math
import os
import re
import sqlite3
import statistics
import subprocess
import sys
import tempfile

RUN_NAME = re.compile(r"^dn([0-9.]+)-seed([0-9]+)\.db$")


def run(cmd, **kwargs):
    """Runs a command, failing loudly with its output."""
    result = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(cmd)}\n"
                 f"{result.stdout}{result.stderr}")
    return result.stdout


def try_run(cmd, problems):
    """Runs a command; on failure records its message and returns None."""
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        problems.append(f"{' '.join(cmd)}: {result.stderr.strip()}")
        return None
    return result.stdout


def seeded_stores(folder, name):
    """[(path, run name, seed)] of the stores NAME-seedS.db in FOLDER (as
    scripts/seeded_runs.sh --name NAME or a campaign's runs named NAME
    write them), in name order; exits saying why when FOLDER is missing or
    holds none."""
    if not os.path.isdir(folder):
        sys.exit(f"{folder}: no such folder (the stores of --name {name})")
    pattern = re.compile("^" + re.escape(name) + r"-seed([0-9]+)\.db$")
    stores = [(os.path.join(folder, f), f[:-3], int(m.group(1)))
              for f in sorted(os.listdir(folder))
              for m in [pattern.match(f)] if m]
    if not stores:
        sys.exit(f"no stores {name}-seedS.db in {folder}")
    return stores


def model_text(config_text):
    """The `model { ... }` block of a RunConfig's text, as a Config's text."""
    start = config_text.index("model {")
    depth = 0
    for i in range(start, len(config_text)):
        if config_text[i] == "{":
            depth += 1
        elif config_text[i] == "}":
            depth -= 1
            if depth == 0:
                body = config_text[config_text.index("{", start) + 1:i]
                return "\n".join(line[2:] if line.startswith("  ") else line
                                 for line in body.strip("\n").split("\n")) + "\n"
    raise ValueError("no model block")


def store_summary(path):
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    db.row_factory = sqlite3.Row
    run_row = db.execute(
        "SELECT run_id, config_text FROM runs ORDER BY run_id DESC LIMIT 1"
    ).fetchone()
    run_id = run_row["run_id"]
    stats = [dict(r) for r in db.execute(
        "SELECT generation, size, evaluated, failed, best_id, best_fitness, "
        "mean_fitness, median_fitness FROM generation_statistics "
        "WHERE run_id = ? AND completed_at IS NOT NULL ORDER BY generation",
        (run_id,))]
    last = stats[-1]["generation"]
    best = dict(db.execute(
        "SELECT id, generation, fitness, cells, springs, chambers, skin_edges, "
        "spread_major, spread_minor FROM individuals WHERE run_id = ? AND id = ?",
        (run_id, stats[-1]["best_id"])).fetchone())
    members = [dict(r) for r in db.execute(
        "SELECT m.rank, i.id, i.status, i.fitness, i.cells, i.chambers "
        "FROM members m JOIN individuals i ON i.run_id = m.run_id "
        "AND i.id = m.id WHERE m.run_id = ? AND m.generation = ? "
        "ORDER BY m.rank", (run_id, last))]
    chains = db.execute(
        "SELECT COUNT(*) FROM individuals WHERE run_id = ? AND status = 'ok' "
        "AND chambers = 0", (run_id,)).fetchone()[0]
    tried = db.execute(
        "SELECT COUNT(*) FROM individuals WHERE run_id = ? AND generation = 0",
        (run_id,)).fetchone()[0]
    statuses = {r[0]: r[1] for r in db.execute(
        "SELECT status, COUNT(*) FROM individuals WHERE run_id = ? "
        "AND generation > 0 AND status IS NOT NULL GROUP BY status",
        (run_id,))}
    db.close()
    return {
        "run_id": run_id,
        "model_text": model_text(run_row["config_text"]),
        "generations": last + 1,
        "stats": stats,
        "best": best,
        "members": members,
        "ok_chains": chains,
        "initial_tried": tried,
        "offspring_statuses": statuses,
    }


def write_model(path, description, model_text):
    """Writes MODEL_TEXT (an animat.v1.Config) to PATH as a text proto
    file, headed by the comment DESCRIPTION."""
    with open(path, "w") as f:
        f.write("# proto-file: proto/animat/v1/config.proto\n"
                "# proto-message: animat.v1.Config\n"
                f"# {description}\n")
        f.write(model_text)


def write_best(animat, db, name, individual, model_text, dest):
    """Writes run NAME's individual from DB as DEST/bests/NAME-ID.json, with
    the model it ran under beside it (.config.txtpb); returns the stem."""
    stem = os.path.join(dest, "bests", f"{name}-{individual}")
    run([animat, "lineage", "genome", str(individual), "--db", db,
         "-o", stem + ".json"])
    write_model(stem + ".config.txtpb",
                f"The model of run {name} (docs/results.md).", model_text)
    return stem


def analyze(animat, db, individual):
    """`animat analyze` of an individual of a store, summarised."""
    return analysis_of(run([animat, "analyze", "--db", db, "--individual",
                            str(individual), "-o", "-"]))


def analyze_genome(animat, genome, config):
    """`animat analyze` of a genome file under a configuration file,
    summarised as analyze() summarises a stored individual."""
    return analysis_of(run([animat, "analyze", "--genome", genome,
                            "--config", config, "-o", "-"]))


def analysis_of(out):
    """The label, nearest label, criteria, scores and features of `animat
    analyze`'s JSON output."""
    a = json.loads(out)
    strategy = a.get("strategy", {})
    scores = {x["label"].lower(): x.get("score", 0.0)
              for x in strategy.get("score", [])}
    # A label's score is the geometric mean of its criteria's memberships,
    # so one criterion clearly missed gives 0. The nearest label is the one with the most criteria met (membership
    # at least 0.5), then the highest mean membership.
    criteria = {}
    for x in strategy.get("score", []):
        terms = x.get("term", [])
        met = [t["feature"] for t in terms if t.get("membership", 0.0) >= 0.5]
        mean = (sum(t.get("membership", 0.0) for t in terms) / len(terms)
                if terms else 0.0)
        criteria[x["label"].lower()] = {"met": met, "of": len(terms),
                                        "mean_membership": mean}
    nearest = max(sorted(criteria), key=lambda k: (
        len(criteria[k]["met"]) / criteria[k]["of"],
        criteria[k]["mean_membership"])) if criteria else "none"
    return {
        "label": strategy.get("label", "OTHER").lower(),
        "nearest": nearest,
        "nearest_score": scores.get(nearest, 0.0),
        "criteria": criteria,
        "margin": strategy.get("margin", 0.0),
        "scores": scores,
        "features": strategy.get("features", {}),
        "period_steps": a.get("periodSteps", a.get("period_steps")),
        "amplitude_mean": a.get("amplitudeMean", a.get("amplitude_mean")),
        "amplitude_max": a.get("amplitudeMax", a.get("amplitude_max")),
        "distance_per_cycle": a.get("distancePerCycle",
                                    a.get("distance_per_cycle")),
        "fitness": a.get("fitness"),
    }


def glide(animat, genome, config, start=3000):
    """How the centre of mass moves within the strokes, from a trace of every
    motion step from `start`: v is its velocity along the window's net
    displacement, a each step's mean |change of e - c| over the cells.
    Returns the share of steps that move backward (v < 0), the share of
    quiet steps (a below a quarter of its maximum) and the mean v over the
    quiet steps relative to the mean v over all: near 1 or above, the body
    keeps moving forward while its cells are still (it coasts); near 0 or
    below, it stops or backs between strokes."""
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, "trace.json")
        run([animat, "simulate", "--genome", genome, "--config", config,
             "--trace", trace, "--every", "1"])
        with open(trace) as f:
            frames = [x for x in json.load(f)["frames"]
                      if x["phase"] == "MOTION" and x["step"] >= start]
    n = len(frames[0]["x"])
    cx = [sum(x["x"]) / n for x in frames]
    cy = [sum(x["y"]) / n for x in frames]
    dx, dy = cx[-1] - cx[0], cy[-1] - cy[0]
    length = math.hypot(dx, dy)
    if not length > 0:
        return None
    ux, uy = dx / length, dy / length
    v = [(sum(x["vx"]) * ux + sum(x["vy"]) * uy) / n for x in frames[1:]]
    act = [sum(abs((b["expand"][i] - b["contract"][i]) -
                   (a["expand"][i] - a["contract"][i])) for i in range(n)) / n
           for a, b in zip(frames, frames[1:])]
    quiet = [vv for vv, aa in zip(v, act) if aa < 0.25 * max(act)]
    mean = statistics.mean(v)
    return {
        "backward_share": sum(1 for x in v if x < 0) / len(v),
        "quiet_share": len(quiet) / len(v),
        "quiet_speed": statistics.mean(quiet) / mean if quiet else None,
    }


def finite(value):
    """VALUE with every non-finite float (an undefined correlation) as
    None, so that it is written as JSON's null, not as NaN."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    if isinstance(value, dict):
        return {k: finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [finite(v) for v in value]
    return value


def spearman(xs, ys):
    """Spearman's rank correlation (average ranks for ties)."""
    def ranks(v):
        order = sorted(range(len(v)), key=lambda i: v[i])
        r = [0.0] * len(v)
        i = 0
        while i < len(order):
            j = i
            while j + 1 < len(order) and v[order[j + 1]] == v[order[i]]:
                j += 1
            for k in range(i, j + 1):
                r[order[k]] = (i + j) / 2.0
            i = j + 1
        return r
    rx, ry = ranks(xs), ranks(ys)
    mx, my = statistics.mean(rx), statistics.mean(ry)
    num = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    den = math.sqrt(sum((a - mx) ** 2 for a in rx) *
                    sum((b - my) ** 2 for b in ry))
    return num / den if den > 0 else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", default="out/replication")
    parser.add_argument("--dest", default="docs/results")
    parser.add_argument("--animat", default=None)
    parser.add_argument("--top", type=int, default=10,
                        help="members of each run's last generation analysed "
                        "for amplitude against frequency")
    args = parser.parse_args()
    animat = args.animat or os.path.join(args.out, "bin", "animat")
    os.makedirs(os.path.join(args.dest, "bests"), exist_ok=True)

    runs = []
    for name in sorted(os.listdir(args.out)):
        m = RUN_NAME.match(name)
        if not m:
            continue
        path = os.path.join(args.out, name)
        summary = store_summary(path)
        summary.update(name=name[:-3], drag=float(m.group(1)),
                       drag_text=m.group(1), seed=int(m.group(2)), db=path)
        runs.append(summary)
    runs.sort(key=lambda r: (r["drag"], r["seed"]))
    if not runs:
        sys.exit(f"no stores dnD-seedS.db in {args.out}")

    # The bests: genome, model configuration, analysis.
    for r in runs:
        best = r["best"]
        stem = write_best(animat, r["db"], r["name"], best["id"],
                          r["model_text"], args.dest)
        r["best_genome"] = stem + ".json"
        # The stored genome and model, simulated again here, must give the
        # stored fitness to the last bit.
        again = run([animat, "simulate", "--genome", stem + ".json",
                     "--config", stem + ".config.txtpb"])
        fitness = re.search(r"^fitness: (\S+)$", again, re.M)
        r["resimulated_fitness"] = float(fitness.group(1)) if fitness else None
        r["resimulated_same_bits"] = (r["resimulated_fitness"] is not None and
                                      float.hex(r["resimulated_fitness"]) ==
                                      float.hex(best["fitness"]))
        r["best_analysis"] = analyze(animat, r["db"], best["id"])
        r["best_glide"] = glide(animat, stem + ".json", stem + ".config.txtpb")
        # Amplitude against frequency over the fittest members.
        members = [m for m in r["members"] if m["status"] == "ok"][:args.top]
        points = []
        for m in members:
            a = analyze(animat, r["db"], m["id"])
            if a["period_steps"] and a["amplitude_mean"] is not None:
                points.append({"id": m["id"], "fitness": m["fitness"],
                               "frequency": 1.0 / a["period_steps"],
                               "amplitude": a["amplitude_mean"],
                               "label": a["label"]})
        r["top_members"] = points
        r["spearman_amplitude_frequency"] = spearman(
            [p["amplitude"] for p in points],
            [p["frequency"] for p in points]) if len(points) > 2 else None
        print(f"{r['name']}: best {best['fitness']:.3f} "
              f"({r['best_analysis']['label']}), {r['generations']} "
              "generations", file=sys.stderr)

    # Fitness curves, one figure per drag.
    for drag in sorted({r["drag_text"] for r in runs}, key=float):
        dbs = [x for r in runs if r["drag_text"] == drag
               for x in ("--db", r["db"])]
        run([animat, "figure", "fitness", *dbs, "-o",
             os.path.join(args.dest, f"fitness-dn{drag}.svg")])

    # Panels: the fittest best of each label found, and for each of the
    # paper's labels the best that scores highest on it (when above 0), so
    # that the nearest animats are drawn even when none is labelled.
    shown = {}
    for r in sorted(runs, key=lambda r: -r["best"]["fitness"]):
        label = r["best_analysis"]["label"]
        if label not in shown:
            shown[label] = r
    for label in ("turtle", "shark", "worm", "jellyfish"):
        if label in shown:
            continue
        def closeness(r):
            c = r["best_analysis"]["criteria"].get(label)
            return (len(c["met"]) / c["of"], c["mean_membership"]) if c else (0, 0)
        scored = [r for r in runs if closeness(r)[0] > 0.0]
        if scored:
            top = max(scored, key=lambda r: (
                r["best_analysis"]["scores"].get(label, 0.0), closeness(r),
                r["best"]["fitness"]))
            shown["nearest-" + label] = top
    problems = []
    drawn = set()
    for label, r in shown.items():
        if r["name"] in drawn:
            continue  # Already drawn under another label.
        drawn.add(r["name"])
        base = os.path.join(args.dest, f"{label}-{r['name']}")
        ident = ["--db", r["db"], "--individual", str(r["best"]["id"])]
        for kind in ("strip", "activity", "cells"):
            try_run([animat, "figure", kind, *ident, "-o", f"{base}-{kind}.svg"],
                    problems)
        try_run([animat, "render", *ident, "--every", "10", "-o",
                 base + ".html"], problems)

    # Amplitude against frequency, pooled over the runs' fittest members.
    pooled = [p for r in runs for p in r["top_members"]]
    trade = {
        "members": len(pooled),
        "spearman_amplitude_frequency": spearman(
            [p["amplitude"] for p in pooled], [p["frequency"] for p in pooled])
        if len(pooled) > 2 else None,
        "amplitude_median": statistics.median(p["amplitude"] for p in pooled)
        if pooled else None,
        "amplitude_max": max((p["amplitude"] for p in pooled), default=None),
    }

    summary = {"runs": [{k: v for k, v in r.items()
                         if k not in ("members", "db")} for r in runs],
               "strategy_figures": {k: v["name"] for k, v in shown.items()},
               "amplitude_frequency": trade,
               "figure_problems": problems}
    with open(os.path.join(args.dest, "replication.json"), "w") as f:
        json.dump(finite(summary), f, indent=1, sort_keys=True,
                  allow_nan=False)

    # The tables.
    lines = ["| run | d_N | seed | generations | random genomes tried | best at 0 "
             "| best (id) | mean | median | cells | springs | chambers | skin "
             "| spreads | strategy (margin); nearest label and score |",
             "|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:"
             "|---|---|"]
    for r in runs:
        s0, sl, b = r["stats"][0], r["stats"][-1], r["best"]
        a = r["best_analysis"]
        lines.append(
            f"| {r['name']} | {r['drag_text']} | {r['seed']} | "
            f"{r['generations']} | {r['initial_tried']:,} | "
            f"{s0['best_fitness']:.2f} | **{b['fitness']:.2f}** ({b['id']}) | "
            f"{sl['mean_fitness']:.2f} | {sl['median_fitness']:.2f} | "
            f"{b['cells']} | {b['springs']} | {b['chambers']} | "
            f"{b['skin_edges']} | {b['spread_major']:.2f}, "
            f"{b['spread_minor']:.2f} | {a['label']} ({a['margin']:.2f}); "
            f"nearest {a['nearest']} {a['nearest_score']:.2f} |")
    lines.append("")
    labels = ("turtle", "shark", "worm", "jellyfish")
    lines.append("| run | " + " | ".join(
        f"{k}: criteria met" for k in labels) + " |")
    lines.append("|---|" + "---|" * len(labels))
    for r in runs:
        c = r["best_analysis"]["criteria"]
        cells = []
        for k in labels:
            x = c.get(k)
            cells.append("—" if not x else
                         f"{len(x['met'])}/{x['of']}" +
                         (f" ({', '.join(m.replace('_', ' ') for m in x['met'])})"
                          if x["met"] else ""))
        lines.append(f"| {r['name']} | " + " | ".join(cells) + " |")
    lines.append("")
    lines.append("| run | ok individuals with no chamber | best / best at "
                 "generation 0 | Spearman (amplitude, frequency), fittest "
                 "members of the last generation | steps moving backward "
                 "| quiet steps | speed while quiet / mean |")
    lines.append("|---|---:|---:|---:|---:|---:|---:|")
    for r in runs:
        s0, b = r["stats"][0], r["best"]
        rho = r["spearman_amplitude_frequency"]
        lines.append(
            f"| {r['name']} | {r['ok_chains']} | "
            f"{b['fitness'] / s0['best_fitness']:.1f} | "
            f"{'—' if rho is None else 'undefined, one period' if math.isnan(rho) else f'{rho:+.2f}'} "
            f"({len(r['top_members'])}) | " +
            ("— | — | — |" if not r["best_glide"] else
             f"{r['best_glide']['backward_share']:.0%} | "
             f"{r['best_glide']['quiet_share']:.0%} | " +
             ("—" if r["best_glide"]["quiet_speed"] is None else
              f"{r['best_glide']['quiet_speed']:+.2f}") + " |"))
    lines.append("")
    keys = ["synchrony", "stroke_asymmetry", "holding", "coasting",
            "lr_symmetry", "fb_symmetry", "fb_lag", "lr_lag",
            "fb_amplitude_gradient", "elongation", "end_taper",
            "back_protrusion", "irregularity"]
    lines.append("| run | period (steps) | amplitude | " +
                 " | ".join(k.replace("_", " ") for k in keys) + " |")
    lines.append("|---|" + "---:|" * (len(keys) + 2))
    for r in runs:
        a = r["best_analysis"]
        values = []
        for k in keys:
            v = a["features"].get(k)
            values.append("—" if v is None else f"{v:+.2f}")
        period = a["period_steps"]
        amplitude = a["amplitude_mean"]
        lines.append(
            f"| {r['name']} | {period:.0f} | {amplitude:.2f} | "
            if period and amplitude is not None else f"| {r['name']} | — | — | ")
        lines[-1] += " | ".join(values) + " |"
    lines.append("")
    statuses = sorted({k for r in runs for k in r["offspring_statuses"]},
                      key=lambda k: (k != "ok", k))
    lines.append("| run | offspring (generations ≥ 1) | " + " | ".join(
        k.replace("_", " ") for k in statuses) + " |")
    lines.append("|---|---:|" + "---:|" * len(statuses))
    for r in runs:
        total = sum(r["offspring_statuses"].values())
        lines.append(f"| {r['name']} | {total:,} | " + " | ".join(
            f"{r['offspring_statuses'].get(k, 0) / total:.1%}"
            for k in statuses) + " |")
    lines.append("")
    lines.append("| run | cells of the ok members of the last generation |")
    lines.append("|---|---|")
    for r in runs:
        counts = {}
        for m in r["members"]:
            if m["status"] == "ok":
                counts[m["cells"]] = counts.get(m["cells"], 0) + 1
        text = ", ".join(f"{c}: {n}" for c, n in
                         sorted(counts.items(), key=lambda kv: -kv[0]))
        lines.append(f"| {r['name']} | {text} |")
    with open(os.path.join(args.dest, "replication.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(json.dumps(trade), file=sys.stderr)
    for r in runs:
        if not r["resimulated_same_bits"]:
            print(f"{r['name']}: the best simulated again gives "
                  f"{r['resimulated_fitness']!r}, stored "
                  f"{r['best']['fitness']!r}", file=sys.stderr)
    for problem in problems:
        print("not drawn: " + problem, file=sys.stderr)


if __name__ == "__main__":
    main()
