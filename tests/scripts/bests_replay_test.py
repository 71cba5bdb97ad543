#!/usr/bin/env python3
"""Every best kept in docs/results/bests/ still gives its stored fitness, to
the last bit, when simulated with its own configuration by this build: runs
made under an earlier model (v2: no contacts, its stored `contacts: false`)
replay unchanged (docs/model.md §7.10, §12).

The stored fitness of each best is the one its report recorded from the
run's lineage store: docs/results/replication.json, energy.json,
guidance.json, third/runs.json (the main runs), arms/runs.json (the arms)
and, once written, energy-holding.json and guidance-lead.json. Every run record in
docs/results/runs/ (scripts/run_record.py) holds its best and top
phenotypes with the fitness and final-state hash its store recorded: each
must give both again.

  bests_replay_test.py [--every K] ANIMAT   (exit 0 when every best
                                            replays)

--every K replays, of each report and each run record, the first, the
(K+1)-th, ... only: the sanitizer builds, whose simulation is some 15 times
slower, check their bits on a sample that still spans every report and
record, while the Release build replays them all.
"""

import argparse
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))


def stored_bests():
    """One list per report: (genome path, stored fitness, None) of every
    best it recorded."""
    results = os.path.join(ROOT, "docs", "results")
    # (report, key of the genome, key of the fitness's object or None,
    # whether the report must be there)
    reports = [("replication.json", "best_genome", "best", True),
               ("energy.json", "genome", None, True),
               ("guidance.json", "genome", None, True),
               # The third edition's energy and guidance arms.
               ("energy-holding.json", "genome", None, False),
               ("guidance-lead.json", "genome", None, False),
               # The third edition's bests, main runs and arms, copied from
               # their run records by scripts/results_report.py.
               (os.path.join("third", "runs.json"), "best_genome", "best",
                False),
               (os.path.join("arms", "runs.json"), "best_genome", "best",
                False)]
    groups = []
    for report, genome_key, fitness_of, required in reports:
        path = os.path.join(results, report)
        if not required and not os.path.isfile(path):
            continue
        with open(path) as f:
            runs = json.load(f)["runs"]
        groups.append([(run[genome_key],
                        (run[fitness_of] if fitness_of else run)["fitness"],
                        None) for run in runs])
    return groups


def recorded_animats():
    """One list per run record: (genome path, stored fitness, stored state
    hash) of its best and its phenotypes."""
    folder = os.path.join(ROOT, "docs", "results", "runs")
    groups = []
    if not os.path.isdir(folder):
        return groups
    for run in sorted(os.listdir(folder)):
        path = os.path.join(folder, run, "record.json")
        if not os.path.isfile(path):
            continue
        with open(path) as f:
            record = json.load(f)
        groups.append([(os.path.join("docs", "results", "runs", run,
                                     entry["genome"] + ".json"),
                        entry["fitness"], entry["state_hash"])
                       for entry in [record["best"]] + record["phenotypes"]])
    return groups


def positive_int(text):
    """argparse type: a whole number of at least 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}")
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1: {value}")
    return value


def main():
    parser = argparse.ArgumentParser(
        description="Every kept best replays to its stored bits.")
    parser.add_argument("--every", type=positive_int, default=1,
                        help="replay every K-th best only (default 1: all)")
    parser.add_argument("animat", help="the animat binary")
    args = parser.parse_args()
    animat = args.animat
    groups = stored_bests() + recorded_animats()
    listed = sum(len(group) for group in groups)
    bests = [entry for group in groups for entry in group[::args.every]]
    failures = []
    for genome, fitness, state_hash in bests:
        path = os.path.join(ROOT, genome)
        config = path[:-len(".json")] + ".config.txtpb"
        run = subprocess.run(
            [animat, "simulate", "--genome", path, "--config", config,
             "--json"], capture_output=True, text=True, check=False)
        if run.returncode != 0:
            failures.append(f"{genome}: exit {run.returncode}: "
                            f"{run.stderr.strip()}")
            continue
        result = json.loads(run.stdout)
        again = result.get("fitness")
        if again is None or float.hex(again) != float.hex(fitness):
            failures.append(f"{genome}: stored fitness {fitness!r}, "
                            f"simulated again {again!r}")
        elif state_hash is not None and result.get("state_hash") != \
                state_hash:
            failures.append(f"{genome}: stored state hash {state_hash}, "
                            f"simulated again {result.get('state_hash')}")
    for failure in failures:
        print(failure, file=sys.stderr)
    sample = "" if args.every == 1 else \
        f" (every {args.every}th of each report and record, of {listed})"
    print(f"{len(bests) - len(failures)} of {len(bests)} bests{sample} "
          "replay to their stored fitness bits")
    sys.exit(1 if failures or not bests else 0)


if __name__ == "__main__":
    main()
