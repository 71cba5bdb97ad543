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

  bests_replay_test.py ANIMAT   (exit 0 when every best replays)
"""

import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))


def stored_bests():
    """(genome path, stored fitness) of every best the reports recorded."""
    results = os.path.join(ROOT, "docs", "results")
    out = []
    with open(os.path.join(results, "replication.json")) as f:
        for run in json.load(f)["runs"]:
            out.append((run["best_genome"], run["best"]["fitness"]))
    for report in ("energy.json", "guidance.json"):
        with open(os.path.join(results, report)) as f:
            for run in json.load(f)["runs"]:
                out.append((run["genome"], run["fitness"]))
    # The third edition's energy and guidance arms, once reported.
    for report in ("energy-holding.json", "guidance-lead.json"):
        path = os.path.join(results, report)
        if os.path.isfile(path):
            with open(path) as f:
                for run in json.load(f)["runs"]:
                    out.append((run["genome"], run["fitness"]))
    # The third edition's bests, main runs and arms, copied from their run
    # records by scripts/results_report.py.
    for folder in ("third", "arms"):
        path = os.path.join(results, folder, "runs.json")
        if os.path.isfile(path):
            with open(path) as f:
                for run in json.load(f)["runs"]:
                    out.append((run["best_genome"], run["best"]["fitness"]))
    return out


def recorded_animats():
    """(genome path, stored fitness, stored state hash) of the best and the
    phenotypes of every run record."""
    folder = os.path.join(ROOT, "docs", "results", "runs")
    out = []
    if not os.path.isdir(folder):
        return out
    for run in sorted(os.listdir(folder)):
        path = os.path.join(folder, run, "record.json")
        if not os.path.isfile(path):
            continue
        with open(path) as f:
            record = json.load(f)
        for entry in [record["best"]] + record["phenotypes"]:
            genome = os.path.join("docs", "results", "runs", run,
                                  entry["genome"] + ".json")
            out.append((genome, entry["fitness"], entry["state_hash"]))
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: bests_replay_test.py ANIMAT")
    animat = sys.argv[1]
    bests = [(g, f, None) for g, f in stored_bests()] + recorded_animats()
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
    print(f"{len(bests) - len(failures)} of {len(bests)} bests replay to "
          "their stored fitness bits")
    sys.exit(1 if failures or not bests else 0)


if __name__ == "__main__":
    main()
