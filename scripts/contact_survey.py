#!/usr/bin/env python3
"""Contacts measured (docs/model.md §7.10, §8.6): how deep bodies fold
through themselves under each contact rule and contact stiffness, and what
folding was worth.

Two surveys, each a table (Markdown) and the numbers (JSON):

  bests   every best of docs/results/bests/ under its own configuration
          (model v2: contacts NONE, its stored fitness), then the same
          configuration with contacts UNJOINED and ALL: fitness and the
          deepest unjoined overlap under each.
  stiffness
          the accuracy report's animat set (bench/data/accuracy/, each with
          its model file) under the default configuration with contacts
          UNJOINED at each contact stiffness k_c given (and each contact
          damping gamma_c, when --damping is given): the deepest
          unjoined overlap of each animat, and its largest over the set.

Every evaluation is `animat simulate --json` of this build; the script
only writes configurations and tabulates. Standard library only.

  scripts/contact_survey.py bests --out docs/results/contacts
  scripts/contact_survey.py stiffness --stiffness 50,100,200,400 \\
      --extra-dir DIR --out docs/accuracy/contacts
  scripts/contact_survey.py stiffness --stiffness 200,800 --damping 0.5,5 \\
      --physics 'substeps: 4' --skip-none --out /tmp/grid
"""

import argparse
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def physics_override(text, fields):
    """`text` (a Config in proto text) with the physics fields given set:
    model v2's `contacts` line removed, the fields added to the first
    physics block (one is made when there is none)."""
    text = re.sub(r"^\s*contacts:\s*\w+\s*(#.*)?$", "", text, flags=re.M)
    inner = " ".join(f"{k}: {v}" for k, v in fields.items())
    if re.search(r"^\s*physics\s*\{", text, flags=re.M):
        return re.sub(r"^(\s*physics\s*\{)", r"\1 " + inner, text, count=1,
                      flags=re.M)
    return text + f"\nphysics {{ {inner} }}\n"


def simulate(animat, genome, config_text):
    """The result of `animat simulate --json` as a dict (exit status
    checked)."""
    with tempfile.NamedTemporaryFile("w", suffix=".txtpb",
                                     delete=False) as config:
        config.write(config_text)
        path = config.name
    try:
        run = subprocess.run(
            [animat, "simulate", "--genome", genome, "--config", path,
             "--json"], capture_output=True, text=True, check=False)
    finally:
        os.unlink(path)
    if run.returncode != 0:
        sys.exit(f"{genome}: animat simulate failed: {run.stderr.strip()}")
    return json.loads(run.stdout)


def run_all(animat, jobs, tasks):
    """tasks: (key, genome, config text); returns {key: result}."""
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {key: pool.submit(simulate, animat, genome, text)
                   for key, genome, text in tasks}
        return {key: f.result() for key, f in futures.items()}


def percent(value):
    return "—" if value is None else f"{100 * value:.1f}%"


def number(value):
    return "—" if value is None else f"{value:.2f}"


def bests(args):
    folder = os.path.join(ROOT, "docs", "results", "bests")
    names = sorted(f[:-len(".json")] for f in os.listdir(folder)
                   if f.endswith(".json") and
                   os.path.exists(os.path.join(folder, f[:-5] +
                                               ".config.txtpb")))
    rules = {"own": None, "unjoined": "UNJOINED", "all": "ALL"}
    tasks = []
    for name in names:
        with open(os.path.join(folder, name + ".config.txtpb")) as f:
            text = f.read()
        genome = os.path.join(folder, name + ".json")
        for rule, value in rules.items():
            config = text if value is None else physics_override(
                text, {"contact_rule": value})
            tasks.append(((name, rule), genome, config))
    results = run_all(args.animat, args.jobs, tasks)
    rows = []
    for name in names:
        row = {"best": name}
        for rule in rules:
            r = results[(name, rule)]
            row[rule] = {"status": r["status"],
                         "fitness": r.get("fitness"),
                         "max_overlap": r.get("max_overlap")}
        rows.append(row)
    lines = [
        "| best | fitness, own (v2: no contacts) | deepest unjoined overlap,"
        " own | fitness, UNJOINED | change | deepest overlap, UNJOINED |"
        " fitness, ALL | change |",
        "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for row in rows:
        own = row["own"]["fitness"]

        def change(rule):
            f = row[rule]["fitness"]
            return "—" if f is None or not own else f"{100 * (f / own - 1):+.0f}%"
        lines.append(
            f"| {row['best']} | {number(own)} |"
            f" {percent(row['own']['max_overlap'])} |"
            f" {number(row['unjoined']['fitness'])} | {change('unjoined')} |"
            f" {percent(row['unjoined']['max_overlap'])} |"
            f" {number(row['all']['fitness'])} | {change('all')} |")
    return rows, "\n".join(lines) + "\n"


def animat_set(extra_dirs):
    """(name, genome path, model text) of the accuracy set and of every
    extra directory laid out the same way, in file-name order."""
    out = []
    for folder in [os.path.join(ROOT, "bench", "data", "accuracy")] + \
            extra_dirs:
        for f in sorted(os.listdir(folder)):
            if not f.endswith(".json"):
                continue
            model = os.path.join(folder, f[:-5] + ".model.txtpb")
            text = open(model).read() if os.path.exists(model) else ""
            out.append((f[:-5], os.path.join(folder, f), text))
    return out


def grid(args):
    """The (k_c, gamma_c) pairs of --stiffness and --damping, in order."""
    ks = [float(v) for v in args.stiffness.split(",")]
    gs = [float(v) for v in args.damping.split(",")] if args.damping \
        else [None]
    return [(k, g) for k in ks for g in gs]


def setting_name(k, g):
    return f"{k:g}" if g is None else f"{k:g}/{g:g}"


def extra_fields(text):
    """`--physics 'a: 1 b: X'` as an ordered dict of fields."""
    pairs = re.findall(r"(\w+)\s*:\s*(\S+)", text or "")
    return dict(pairs)


def stiffness(args):
    settings = grid(args)
    animats = animat_set(args.extra_dir)
    extra = extra_fields(args.physics)
    tasks = []
    for name, genome, model in animats:
        for k, g in settings:
            fields = {"contact_rule": "UNJOINED", "contact_stiffness": k}
            if g is not None:
                fields["contact_damping"] = g
            fields.update(extra)
            tasks.append(((name, setting_name(k, g)), genome,
                          physics_override(model, fields)))
        if not args.skip_none:
            fields = dict(extra, contact_rule="NONE")
            tasks.append(((name, "none"), genome,
                          physics_override(model, fields)))
    results = run_all(args.animat, args.jobs, tasks)
    rows = []
    for name, _, _ in animats:
        row = {"animat": name}
        if not args.skip_none:
            row["none"] = results[(name, "none")].get("max_overlap")
            row["fitness_none"] = results[(name, "none")].get("fitness")
        for k, g in settings:
            r = results[(name, setting_name(k, g))]
            row[setting_name(k, g)] = {"status": r["status"],
                                       "max_overlap": r.get("max_overlap"),
                                       "fitness": r.get("fitness")}
        rows.append(row)
    column = "k_c" if args.damping is None else "k_c / gamma_c"
    header = (f"| {column} | deepest overlap over the set | animat | 90th"
              f" percentile | animats over {percent(args.bound)} | failed |")
    lines = [header, "|---:|---:|---|---:|---:|---:|"]
    keys = ([] if args.skip_none else [None]) + \
        [setting_name(k, g) for k, g in settings]
    for key in keys:
        overlaps = []
        failed = 0
        for row in rows:
            if key is None:
                value = row["none"]
            else:
                value = row[key]["max_overlap"]
                failed += row[key]["status"] != "ok"
            if value is not None:
                overlaps.append((value, row["animat"]))
        overlaps.sort()
        worst = overlaps[-1] if overlaps else (None, "—")
        p90 = overlaps[int(0.9 * (len(overlaps) - 1))][0] if overlaps else None
        over = sum(1 for v, _ in overlaps if v > args.bound)
        label = "NONE" if key is None else key
        lines.append(f"| {label} | {percent(worst[0])} | {worst[1]} |"
                     f" {percent(p90)} | {over} of {len(overlaps)} |"
                     f" {failed} |")
    return rows, "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("survey", choices=["bests", "stiffness"])
    parser.add_argument("--animat",
                        default=os.path.join(ROOT, "build", "bin", "animat"))
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--stiffness", default="50,100,200,400",
                        help="contact stiffnesses k_c, comma-separated")
    parser.add_argument("--damping", default=None,
                        help="contact dampings gamma_c, comma-separated "
                        "(default: the configuration's)")
    parser.add_argument("--physics", default="",
                        help="more physics fields for every setting, e.g. "
                        "'integrator: RK4 substeps: 16'")
    parser.add_argument("--bound", type=float, default=0.10,
                        help="the overlap counted as too deep (default 0.10)")
    parser.add_argument("--skip-none", action="store_true",
                        help="leave out the contact rule NONE column")
    parser.add_argument("--extra-dir", action="append", default=[],
                        help="more genomes laid out as bench/data/accuracy")
    parser.add_argument("--out", required=True,
                        help="writes OUT.md (table) and OUT.json")
    args = parser.parse_args()
    if args.jobs < 1:
        parser.error("--jobs must be at least 1")
    rows, table = bests(args) if args.survey == "bests" else stiffness(args)
    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    with open(args.out + ".md", "w") as f:
        f.write(table)
    with open(args.out + ".json", "w") as f:
        json.dump(rows, f, indent=1, sort_keys=True)
        f.write("\n")
    sys.stdout.write(table)


if __name__ == "__main__":
    main()
