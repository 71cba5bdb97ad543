#!/usr/bin/env python3
"""Every best kept in docs/results/bests/ still gives its stored fitness, to
the last bit, when simulated with its own configuration by this build: runs
made under an earlier model (v2: no contacts, its stored `contacts: false`)
replay unchanged (docs/model.md §7.10, §12).

The stored fitness of each best is the one its report recorded from the
run's lineage store: docs/results/replication.json, energy.json and
guidance.json.

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
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: bests_replay_test.py ANIMAT")
    animat = sys.argv[1]
    bests = stored_bests()
    failures = []
    for genome, fitness in bests:
        path = os.path.join(ROOT, genome)
        config = path[:-len(".json")] + ".config.txtpb"
        run = subprocess.run(
            [animat, "simulate", "--genome", path, "--config", config,
             "--json"], capture_output=True, text=True, check=False)
        if run.returncode != 0:
            failures.append(f"{genome}: exit {run.returncode}: "
                            f"{run.stderr.strip()}")
            continue
        again = json.loads(run.stdout).get("fitness")
        if again is None or float.hex(again) != float.hex(fitness):
            failures.append(f"{genome}: stored fitness {fitness!r}, "
                            f"simulated again {again!r}")
    for failure in failures:
        print(failure, file=sys.stderr)
    print(f"{len(bests) - len(failures)} of {len(bests)} bests replay to "
          "their stored fitness bits")
    sys.exit(1 if failures or not bests else 0)


if __name__ == "__main__":
    main()
