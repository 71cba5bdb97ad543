#!/usr/bin/env python3
"""Reads the energy-aware runs' stores (configs/energy.txtpb evolved by
`scripts/seeded_runs.sh --config configs/energy.txtpb --name energy-dn1`)
and the replication's d_N = 1 runs (docs/results/replication.json and their bests in
docs/results/bests/: the distance-only side) and writes what docs/results.md
reports under "Energy": per run the best's distance, energy and distance per
energy, its strategy, the last generation's spending, and the generations'
bests over time.

  scripts/energy_report.py [--name energy-dn1] [--report energy]
      [--partners EARLIER.json ...] [--out out/NAME] [--dest docs/results]
      [--replication DEST/replication.json] [--animat out/NAME/bin/animat]

NAME names the runs: their stores are NAME-seedS.db, as
scripts/seeded_runs.sh --name NAME or a campaign's runs named NAME write
them. Every best it compares with (the replication's d_N = 1 bests, and
the energy-aware bests of each --partners report) is simulated under the
arm's own model, so that distance, energy and energy-aware fitness are
counted by one cost model: e.g. the energy-holding arm
(configs/energy-holding.txtpb) against the work-only bests of
docs/results/energy.json, with holding charged. Each is also analysed
again by this build under its own model, so that every label in the
table is the present classifier's. When the arm charges holding
(evaluation.holding_cost c_h > 0), each row's energy E is split into the
work W (E simulated with c_h = 0) and the held actuation per motion step,
(E - W) / c_h / motion_steps (docs/model.md §10.1).

Only Python's standard library; the simulator work is done by `animat`
(lineage, simulate, analyze). Writes DEST/REPORT.json (every number),
DEST/REPORT.md (the tables), DEST/NAME.svg (the bests' distance over
the generations), each of the arm's bests' strip and activity figures
(DEST/NAME-seedS-strip.svg, -activity.svg), and their genomes and models
in DEST/bests/. A run still going is reported as far as it has gone.
"""

import argparse
import json
import math
import os
import re
import sqlite3
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import replication_report as rr  # noqa: E402  (its store and analysis code)
from strategy_report import read_json_object  # noqa: E402

def energy_extras(path, run_id, budget):
    """What the replication's summary lacks: distance and energy of the
    generations' bests and of the last generation's members."""
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    per_generation = [
        {"generation": g, "fitness": f, "distance": d, "energy": e}
        for g, f, d, e in db.execute(
            "SELECT s.generation, i.fitness, i.distance, i.energy "
            "FROM generation_statistics s JOIN individuals i "
            "ON i.run_id = s.run_id AND i.id = s.best_id "
            "WHERE s.run_id = ? AND s.completed_at IS NOT NULL "
            "ORDER BY s.generation", (run_id,))]
    last = per_generation[-1]["generation"]
    members = [(d, e) for d, e in db.execute(
        "SELECT i.distance, i.energy FROM members m JOIN individuals i "
        "ON i.run_id = m.run_id AND i.id = m.id "
        "WHERE m.run_id = ? AND m.generation = ? AND i.status = 'ok'",
        (run_id, last))]
    db.close()
    distances = [d for d, _ in members]
    energies = [e for _, e in members]
    return per_generation, {
        "ok_members": len(members),
        "over_budget": sum(1 for e in energies if e > budget),
        "median_distance": statistics.median(distances) if members else None,
        "median_energy": statistics.median(energies) if members else None,
    }


def simulate(animat, genome, config):
    out = rr.run([animat, "simulate", "--genome", genome, "--config", config])
    values = dict(re.findall(r"^(\w+): (\S+)$", out, re.M))
    return {k: float(values[k]) for k in ("fitness", "distance", "energy")}


def holding_cost_of(model_text):
    m = re.search(r"holding_cost: ([0-9.e+-]+)", model_text)
    return float(m.group(1)) if m else 0.0


def split_energy(animat, genome, arm_config, energy):
    """(work W, holding H per motion step) of a genome's energy E under the
    arm's model, E = W + c_h H (docs/model.md §10.1): W is E simulated
    with c_h = 0. (None, None) when the arm charges no holding."""
    with open(arm_config) as f:
        text = f.read()
    c_h = holding_cost_of(text)
    if c_h <= 0.0:
        return None, None
    steps = re.search(r"motion_steps: ([0-9]+)", text)
    with tempfile.NamedTemporaryFile("w", suffix=".txtpb") as f:
        f.write(re.sub(r"holding_cost: [0-9.e+-]+", "holding_cost: 0", text))
        f.flush()
        work = simulate(animat, genome, f.name)["energy"]
    return work, (energy - work) / c_h / int(steps.group(1) if steps
                                             else 6000)


def budget_of(model_text):
    m = re.search(r"energy_budget: ([0-9.e+]+)", model_text)
    return float(m.group(1)) if m else 10000.0


def row(r, split):
    """R's table row; with SPLIT, its work and holding columns too."""
    a = r["analysis"]
    f = a.get("features", {})

    def feature(name):
        v = f.get(name)
        return f"{v:+.2f}" if isinstance(v, (int, float)) else "—"

    period = (f"{a['period_steps']:.0f}"
              if isinstance(a.get("period_steps"), (int, float)) else "—")
    return (f"| {r['name']} | {r['fitness_kind']} | {r['generations']} | "
            f"{r['best_id']} (g{r['best_generation']}) | "
            f"{r['distance']:.2f} | {r['energy']:,.0f} | " +
            (f"{r['work']:,.0f} | {r['held_per_step']:.1f} | " if split
             else "") +
            f"{1000 * r['distance'] / r['energy']:.2f} | "
            f"{r['energy_fitness']:.2f} | {a['label']} (nearest "
            f"{a['nearest']}) | {period} | "
            f"{(a.get('amplitude_mean') or 0):.2f} | {feature('synchrony')} | "
            f"{feature('coasting')} | {feature('holding')} |")


def nice_ticks(top):
    """0 and multiples of 1, 2 or 5 times a power of ten up to `top`,
    about five of them."""
    step = 10 ** math.floor(math.log10(max(top, 1e-9) / 5))
    for factor in (1, 2, 5, 10):
        if top / (step * factor) <= 6:
            step *= factor
            break
    return [step * i for i in range(int(top / step) + 1)]


def svg(runs, path):
    """Best distance per generation, one line per run."""
    w, h, left, bottom, top, right = 640, 360, 56, 40, 16, 150
    gmax = max(len(r["curve"]) for r in runs) - 1
    dmax = max(max(p for p in r["curve"]) for r in runs) * 1.05
    x = lambda g: left + (w - left - right) * g / max(1, gmax)  # noqa: E731
    y = lambda d: h - bottom - (h - bottom - top) * d / dmax  # noqa: E731
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" '
           f'height="{h}" font-family="sans-serif" font-size="11">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<line x1="{left}" y1="{h - bottom}" x2="{w - right}" '
           f'y2="{h - bottom}" stroke="black"/>',
           f'<line x1="{left}" y1="{top}" x2="{left}" y2="{h - bottom}" '
           'stroke="black"/>',
           f'<text x="{(left + w - right) / 2}" y="{h - 8}" '
           'text-anchor="middle">generation</text>',
           f'<text x="14" y="{(top + h - bottom) / 2}" text-anchor="middle" '
           f'transform="rotate(-90 14 {(top + h - bottom) / 2})">'
           'distance swum by the best (radii)</text>']
    for d in nice_ticks(dmax):
        out.append(f'<text x="{left - 4}" y="{y(d) + 4:.1f}" '
                   f'text-anchor="end">{d:g}</text>')
    for t in nice_ticks(gmax):
        out.append(f'<text x="{x(t):.1f}" y="{h - bottom + 14}" '
                   f'text-anchor="middle">{t:g}</text>')
    for i, r in enumerate(runs):
        colour = {"energy": "#c0392b", "distance": "#2c3e50"}.get(
            r["fitness_kind"], "#e67e22")  # Orange: an earlier arm's.
        dash = ["", "6 3", "2 2", "8 2 2 2"][i % 4]
        points = " ".join(f"{x(g):.1f},{y(d):.1f}"
                          for g, d in enumerate(r["curve"]))
        out.append(f'<polyline fill="none" stroke="{colour}" '
                   f'stroke-dasharray="{dash}" points="{points}"/>')
        ly = top + 14 * i + 8
        out.append(f'<line x1="{w - right + 8}" y1="{ly}" x2="{w - right + 30}"'
                   f' y2="{ly}" stroke="{colour}" stroke-dasharray="{dash}"/>')
        out.append(f'<text x="{w - right + 34}" y="{ly + 4}">{r["name"]}'
                   '</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def arm_run(animat, path, name, seed, dest):
    """One run of the arm from its store: its best kept in DEST/bests/ and
    simulated again (its stored fitness to the bit), its strip and
    activity figures, its curve and last generation."""
    s = rr.store_summary(path)
    budget = budget_of(s["model_text"])
    curve, last = energy_extras(path, s["run_id"], budget)
    best = s["best"]
    stem = rr.write_best(animat, path, name, best["id"], s["model_text"], dest)
    again = simulate(animat, stem + ".json", stem + ".config.txtpb")
    for kind in ("strip", "activity"):
        rr.run([animat, "figure", kind, "--genome", stem + ".json",
                "--config", stem + ".config.txtpb", "-o",
                os.path.join(dest, f"{name}-{kind}.svg")])
    if float.hex(again["fitness"]) != float.hex(best["fitness"]):
        sys.exit(f"{stem}: simulated again, fitness {again['fitness']} "
                 f"is not the stored {best['fitness']}")
    work, held = split_energy(animat, stem + ".json", stem + ".config.txtpb",
                              again["energy"])
    return {
        "work": work, "held_per_step": held,
        "name": name, "fitness_kind": "energy", "seed": seed,
        "budget": budget, "generations": s["generations"],
        "best_id": best["id"], "best_generation": best["generation"],
        "fitness": best["fitness"], "distance": again["distance"],
        "energy": again["energy"], "energy_fitness": again["fitness"],
        "genome": stem + ".json", "config": stem + ".config.txtpb",
        "analysis": rr.analyze(animat, path, best["id"]),
        "curve": [p["distance"] for p in curve],
        "per_generation": curve, "last_generation": last,
    }


def partner(animat, arm_config, kind, **fields):
    """A best evolved under another fitness, simulated under the arm's
    model (ARM_CONFIG): its distance, and its energy and fitness as this
    arm's cost model counts them; and analysed again under its own model
    by this build, so that its label is the present classifier's, as the
    arm's are (the earlier report's analysis may be an earlier one's)."""
    here = simulate(animat, fields["genome"], arm_config)
    own_config = fields["genome"][:-len(".json")] + ".config.txtpb"
    work, held = split_energy(animat, fields["genome"], arm_config,
                              here["energy"])
    return dict(fields, fitness_kind=kind, distance=here["distance"],
                energy=here["energy"], energy_fitness=here["fitness"],
                work=work, held_per_step=held,
                analysis=rr.analyze_genome(animat, fields["genome"],
                                           own_config))


def partners_of(animat, args, arm_config):
    """The distance-only side (the replication's d_N = 1 runs and bests)
    and the runs of each --partners report, under the arm's model."""
    out = []
    replication = read_json_object(args.replication, ("runs",),
                                   "--replication")
    for r in replication["runs"]:
        if r["drag"] != 1:
            continue
        out.append(partner(
            animat, arm_config, "distance", name=r["name"], seed=r["seed"],
            generations=r["generations"], best_id=r["best"]["id"],
            best_generation=r["best"]["generation"],
            fitness=r["best"]["fitness"], genome=r["best_genome"],
            curve=[x["best_fitness"] for x in r["stats"]]))
    for path in args.partners:
        report = read_json_object(path, ("runs",), "--partners")
        for r in report["runs"]:
            if r["fitness_kind"] != "energy":
                continue
            out.append(partner(
                animat, arm_config, f"energy ({report_name(path)}.json)",
                name=r["name"], seed=r["seed"], generations=r["generations"],
                best_id=r["best_id"], best_generation=r["best_generation"],
                fitness=r["fitness"], genome=r["genome"], curve=r["curve"]))
    return out


def report_name(path):
    """The report's name: energy for docs/results/energy.json."""
    return os.path.splitext(os.path.basename(path))[0]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--name", default="energy-dn1",
                        help="the runs' name: stores NAME-seedS.db")
    parser.add_argument("--report", default="energy",
                        help="writes DEST/REPORT.md and DEST/REPORT.json")
    parser.add_argument("--partners", action="append", default=[],
                        help="an earlier energy report's JSON whose "
                        "energy-aware bests are compared under this arm's "
                        "model (repeatable)")
    parser.add_argument("--out", default=None,
                        help="the stores' folder (default out/NAME)")
    parser.add_argument("--dest", default="docs/results")
    parser.add_argument("--replication", default=None,
                        help="the replication's report, whose d_N = 1 bests "
                        "are the distance-only side (default "
                        "DEST/replication.json)")
    parser.add_argument("--animat", default=None)
    args = parser.parse_args()
    args.replication = args.replication or os.path.join(args.dest,
                                                        "replication.json")
    args.out = args.out or os.path.join("out", args.name)
    animat = args.animat or os.path.join(args.out, "bin", "animat")
    os.makedirs(os.path.join(args.dest, "bests"), exist_ok=True)

    stores = rr.seeded_stores(args.out, args.name)
    # The reports compared with are read before any simulation.
    for path, flag in [(args.replication, "--replication")] + [
            (p, "--partners") for p in args.partners]:
        read_json_object(path, ("runs",), flag)
    runs = [arm_run(animat, path, name, seed, args.dest)
            for path, name, seed in stores]
    budget = runs[0]["budget"]
    runs += partners_of(animat, args, runs[0]["config"])

    # With a holding cost, E = W + c_h H is split into its two parts.
    split = runs[0]["work"] is not None
    lines = [
        "| run | fitness | generations | best (generation) | distance | "
        "energy | " + ("work | held per step | " if split else "") +
        "distance per 1000 energy | energy-aware fitness | strategy |"
        " period (steps) | amplitude | synchrony | coasting | holding |",
        "|---|---|---:|---|---:|---:|" + ("---:|---:|" if split else "") +
        "---:|---:|---|---:|---:|---:|---:|---:|"]
    lines += [row(r, split) for r in runs]
    lines += ["", "| run | ok members, last generation | above the budget | "
              "median distance | median energy |", "|---|---:|---:|---:|---:|"]
    for r in runs:
        last = r.get("last_generation")
        if last:
            lines.append(
                f"| {r['name']} | {last['ok_members']} | "
                f"{last['over_budget']} | {last['median_distance']:.2f} | "
                f"{last['median_energy']:,.0f} |")
    with open(os.path.join(args.dest, f"{args.report}.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    with open(os.path.join(args.dest, f"{args.report}.json"), "w") as f:
        json.dump({"budget": budget, "runs": runs}, f, indent=2)
        f.write("\n")
    svg(runs, os.path.join(args.dest, f"{args.name}.svg"))
    print(f"wrote {args.dest}/{args.report}.md, {args.report}.json, "
          f"{args.name}.svg")


if __name__ == "__main__":
    main()
