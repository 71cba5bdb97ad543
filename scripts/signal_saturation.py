#!/usr/bin/env python3
"""Signal saturation measured (docs/analysis.md, "Signal saturation"): for
each best, the share of (cell, morphogen, motion step) values at the cap
M = 1, per morphogen and in all, and the steps a signal takes to cross the
body. Every number is `animat signals --json` of this build; the script
only finds the bests and tabulates, as a table (Markdown) and the numbers
(JSON).

  model v2   every replication best of docs/results/bests/ (dn*-seed*),
             under its own configuration (model v2: no contacts);
  model v3   the best of each run given with --db: a lineage store (its
             best individual, the run's own configuration) or a run
             record's folder (scripts/run_record.py; its best's genome and
             model files), e.g. docs/results/runs/v3k1500-dn0.1-seed1.

With --group LABEL=REGEX (repeatable, in order), OUT.md ends with one row
per group: the bests whose name matches REGEX (Python re.search), and
their share of values at the cap (median and range), how many have a
morphogen at the cap in at least 97% of its values, their mean kernel
sums and their crossing steps (ranges); OUT.json holds the same under
"groups". A group that matches no best is an error.

With --kernel-lengths 3,1.5,1 it also prints, for each v2 best's body
(its rest positions, from `animat simulate --trace`), the cells' mean and
largest kernel sum at each kernel length: the body as it grew, the kernel
changed alone (a run at another length grows other bodies).

  scripts/signal_saturation.py [--animat build/bin/animat] \\
      [--db RUN.db ...] [--group LABEL=REGEX ...] [--kernel-lengths L,...] \\
      --out docs/results/saturation

Exit 0 when every animat was measured, 1 otherwise. Standard library only.
"""

import argparse
import glob
import json
import math
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(command):
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise RuntimeError(" ".join(command) + ": " + done.stderr.strip())
    return done.stdout


def measure(animat, source):
    return json.loads(run([animat, "signals", "--json"] + source))


def v2_bests():
    pattern = os.path.join(ROOT, "docs", "results", "bests", "dn*-seed*-*.json")
    for path in sorted(glob.glob(pattern)):
        name = os.path.basename(path)[:-len(".json")]
        config = path[:-len(".json")] + ".config.txtpb"
        yield name, ["--genome", path, "--config", config]


def model_of(config_text):
    """"v2" for a configuration without contacts (contact_rule NONE, or
    model v2's contacts: false), else "v3"."""
    if re.search(r"contact_rule:\s*NONE\b|\bcontacts:\s*false\b",
                 config_text):
        return "v2"
    return "v3"


def run_bests(animat, dbs):
    """(model, name, source) of the best of each store or record folder."""
    for db in dbs:
        record = os.path.join(db, "record.json")
        if os.path.isfile(record):
            with open(record) as f:
                data = json.load(f)
            genome = data["best"]["genome"]
            stem = os.path.join(db, genome)
            yield model_of(data["config_text"]), genome, [
                "--genome", stem + ".json", "--config",
                stem + ".config.txtpb"]
            continue
        best = run([animat, "lineage", "best", "--db", db])
        found = re.search(r"^id: (\d+)$", best, re.MULTILINE)
        if not found:
            raise RuntimeError(f"{db}: no best individual")
        name = os.path.basename(db)[:-len(".db")] + "-" + found.group(1)
        yield "v3", name, ["--db", db, "--individual", found.group(1)]


def row(model, name, s):
    values = s["values"]
    shares = [m["share"] for m in s["morphogens"]]
    return {
        "model": model,
        "animat": name,
        "cells": s["cells"],
        "diameter": s["diameter"],
        "crossing_steps": s["crossing_steps"],
        "kernel_sum_mean": s["kernel_sum_mean"],
        "kernel_sum_max": s["kernel_sum_max"],
        "morphogens": len(shares),
        "capped_share": s["capped"] / values if values else 0.0,
        "morphogen_shares": shares,
    }


def markdown(rows):
    lines = [
        "| model | best | cells | diameter (radii) | steps to cross | "
        "kernel sum, mean (max) | morphogens in motion | values at the cap "
        "| per morphogen |",
        "|---|---|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in rows:
        per = ", ".join(f"{s:.2f}" for s in r["morphogen_shares"]) or "—"
        lines.append(
            f"| {r['model']} | {r['animat']} | {r['cells']} | "
            f"{r['diameter']:.1f} | {r['crossing_steps']} | "
            f"{r['kernel_sum_mean']:.1f} ({r['kernel_sum_max']:.1f}) | "
            f"{r['morphogens']} | {r['capped_share']:.2f} | {per} |")
    return "\n".join(lines) + "\n"


# A morphogen at the cap in at least this share of its values reads a
# nearly constant 1.
HOT_SHARE = 0.97


def median(values):
    ordered = sorted(values)
    middle = len(ordered) // 2
    if len(ordered) % 2:
        return ordered[middle]
    return (ordered[middle - 1] + ordered[middle]) / 2


def summary(rows, groups):
    """One dict per (label, pattern) of `groups`, over the rows whose
    animat matches the pattern; ValueError for a group without rows."""
    out = []
    for label, pattern in groups:
        members = [r for r in rows if re.search(pattern, r["animat"])]
        if not members:
            raise ValueError(f"group {label}: no best matches {pattern!r}")
        capped = [r["capped_share"] for r in members]
        kernel = [r["kernel_sum_mean"] for r in members]
        steps = [r["crossing_steps"] for r in members]
        out.append({
            "group": label,
            "bests": len(members),
            "capped_share_median": median(capped),
            "capped_share_min": min(capped),
            "capped_share_max": max(capped),
            "with_hot_morphogen": sum(
                1 for r in members
                if any(s >= HOT_SHARE for s in r["morphogen_shares"])),
            "kernel_sum_mean_min": min(kernel),
            "kernel_sum_mean_max": max(kernel),
            "crossing_steps_min": min(steps),
            "crossing_steps_max": max(steps),
        })
    return out


def summary_markdown(groups):
    lines = [
        "| condition | bests | values at the cap: median (range) | "
        "bests with a morphogen at the cap in ≥ 97% of its values | "
        "kernel sum, mean | steps to cross |",
        "|---|---:|---|---:|---|---|",
    ]
    for g in groups:
        lines.append(
            f"| {g['group']} | {g['bests']} | "
            f"{100 * g['capped_share_median']:.0f}% "
            f"({100 * g['capped_share_min']:.0f}–"
            f"{100 * g['capped_share_max']:.0f}%) | "
            f"{g['with_hot_morphogen']} of {g['bests']} | "
            f"{g['kernel_sum_mean_min']:.1f}–{g['kernel_sum_mean_max']:.1f} | "
            f"{g['crossing_steps_min']}–{g['crossing_steps_max']} |")
    return "\n".join(lines) + "\n"


def body_positions(animat, source):
    with tempfile.TemporaryDirectory() as scratch:
        trace = os.path.join(scratch, "trace.json")
        run([animat, "simulate", "--trace", trace, "--every", "1000000"] +
            source)
        with open(trace) as f:
            nodes = json.load(f)["body"]["nodes"]
    return [(n.get("x", 0.0), n.get("y", 0.0)) for n in nodes]


def kernel_sums(positions, length):
    sums = [sum(math.exp(-math.dist(p, q) / length) for q in positions)
            for p in positions]
    return sum(sums) / len(sums), max(sums)


def kernel_table(animat, lengths):
    header = "| v2 best | " + " | ".join(
        f"kernel length {l:g}: mean (max)" for l in lengths) + " |"
    lines = [header, "|---|" + "---:|" * len(lengths)]
    for name, source in v2_bests():
        positions = body_positions(animat, source)
        cells = []
        for length in lengths:
            mean, largest = kernel_sums(positions, length)
            cells.append(f"{mean:.2f} ({largest:.2f})")
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--animat", default=os.path.join(ROOT, "build", "bin",
                                                         "animat"))
    parser.add_argument("--db", action="append", default=[])
    parser.add_argument("--group", action="append", default=[],
                        metavar="LABEL=REGEX",
                        help="a summary row over the bests matching REGEX")
    parser.add_argument("--kernel-lengths", default="",
                        help="comma-separated kernel lengths (radii)")
    parser.add_argument("--out", required=True,
                        help="writes OUT.md and OUT.json")
    args = parser.parse_args()
    groups = []
    for spec in args.group:
        label, sep, pattern = spec.partition("=")
        if not sep or not label or not pattern:
            parser.error(f"--group {spec!r}: expected LABEL=REGEX")
        try:
            re.compile(pattern)
        except re.error as error:
            parser.error(f"--group {spec!r}: {error}")
        groups.append((label, pattern))
    rows, failures = [], 0
    sources = [("v2", name, source) for name, source in v2_bests()]
    try:
        sources += list(run_bests(args.animat, args.db))
    except RuntimeError as error:
        print(f"signal_saturation.py: {error}", file=sys.stderr)
        failures += 1
    for model, name, source in sources:
        try:
            rows.append(row(model, name, measure(args.animat, source)))
        except RuntimeError as error:
            print(f"signal_saturation.py: {error}", file=sys.stderr)
            failures += 1
    try:
        grouped = summary(rows, groups)
    except ValueError as error:
        print(f"signal_saturation.py: {error}", file=sys.stderr)
        grouped, failures = [], failures + 1
    text = markdown(rows)
    if grouped:
        text += "\n" + summary_markdown(grouped)
    with open(args.out + ".json", "w") as f:
        json.dump({"bests": rows, "groups": grouped}, f, indent=1)
        f.write("\n")
    with open(args.out + ".md", "w") as f:
        f.write(text)
    print(text, end="")
    if args.kernel_lengths:
        lengths = [float(l) for l in args.kernel_lengths.split(",")]
        if not lengths or min(lengths) <= 0:
            parser.error("--kernel-lengths: lengths must be > 0")
        table = kernel_table(args.animat, lengths)
        with open(args.out + "-kernels.md", "w") as f:
            f.write(table)
        print()
        print(table, end="")
    sys.exit(1 if failures or not rows else 0)


if __name__ == "__main__":
    main()
