#!/usr/bin/env python3
"""Strategies with statistics (docs/results.md, third edition): the labels
of the top distinct phenotypes of every run's last generation, their
proportions per condition with 95% Wilson intervals, Fisher's exact tests
and Kruskal-Wallis tests between conditions, and how deeply unjoined
cells overlap in every store.

  scripts/strategy_report.py --animat build/bin/animat \\
      --condition 'v3-dn0.1=/work/runs/v3rep/dn0.1-seed*.db' ... \\
      --compare v3-dn0.1,v3-dn1,v3-dn10 --compare v2-dn1,v3-dn1 ... \\
      [--pool v3=v3-dn0.1+v3-dn1+v3-dn10] [--top 5] [--overlap-bound 0.1] \\
      [--out docs/results/strategies]

- A condition is a name and a glob of lineage stores (one run each), or of
  run records (folders written by scripts/run_record.py, for runs whose
  store is not kept). The phenotypes are `animat cluster --top N`'s: each
  store's last completed generation, ok members by fitness, each state
  hash once (equal hashes are identical simulations); a record holds the
  same phenotypes' genomes and models. Each is labelled by `animat analyze`'s
  classifier, which also gives its period and amplitude.
- A pool is a condition made of others (e.g. every drag of one model).
- A comparison names two or more conditions. For each label, Fisher's
  exact test of every pair (label against the rest), Holm-adjusted over
  the pairs of that comparison and label; for each continuous feature,
  one Kruskal-Wallis test over all its conditions.
- The phenotypes of one run are relatives, not independent draws: the
  tables also count, per condition, the runs whose best carries each
  label, and the runs with at least one phenotype of it; and each
  comparison's Fisher tests are made again over runs, each run counted
  once by its best's label.
- Overlap: per store, by SQL, the ok individuals and how many have a
  deepest unjoined overlap (docs/model.md §8.6) above --overlap-bound.

Writes OUT.json (every number) and OUT.md (the tables). Exit 0 when every
store was read and every phenotype analysed, 1 otherwise, 2 on a usage
error. Standard library only.
"""

import argparse
import glob
import json
import os
import re
import sqlite3
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import stats  # noqa: E402

LABELS = ("turtle", "shark", "worm", "jellyfish", "other")
# The continuous features compared between conditions: four of the
# classifier's (docs/analysis.md, "Definitions") and the period and
# amplitude of the analysis.
FEATURES = ("synchrony", "fb_lag", "elongation", "period_steps",
            "amplitude_mean")
PHENOTYPE = re.compile(r"^(.*) #([0-9]+)$")


def natural_key(text):
    """Sorts seed2 before seed10."""
    return [int(t) if t.isdigit() else t for t in re.split(r"([0-9]+)", text)]


def parse_pairs(values, flag):
    """NAME=VALUE arguments as an ordered list of (name, value)."""
    pairs = []
    for v in values:
        name, sep, rest = v.partition("=")
        if not sep or not name or not rest:
            sys.exit(f"strategy_report.py: {flag} wants NAME=VALUE, got {v!r}")
        pairs.append((name, rest))
    return pairs


def store_overlap(path, bound):
    """The latest run of store (or record) PATH: its generations, best
    fitness and the deepest unjoined overlap of its ok individuals."""
    if is_record(path):
        record = read_record(path)
        o = record["overlap"]
        if o["bound"] != bound:
            sys.exit(f"strategy_report.py: {path} counts overlaps above "
                     f"{o['bound']:g}, not {bound:g}")
        return {"generations": record["generations"],
                "best_fitness": record["statistics"][-1]["best_fitness"],
                "ok": o["ok"], "deepest_overlap": o["deepest"],
                "above_bound": o["above_bound"]}
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    try:
        run_id, = db.execute(
            "SELECT MAX(run_id) FROM runs").fetchone()
        generations, best = db.execute(
            "SELECT MAX(generation) + 1, MAX(best_fitness) FROM "
            "generation_statistics WHERE run_id = ? AND completed_at IS NOT "
            "NULL", (run_id,)).fetchone()
        ok, deepest, above = db.execute(
            "SELECT COUNT(*), MAX(max_overlap), "
            "COALESCE(SUM(max_overlap > ?), 0) FROM individuals "
            "WHERE run_id = ? AND status = 'ok'", (bound, run_id)).fetchone()
    finally:
        db.close()
    return {"generations": generations, "best_fitness": best, "ok": ok,
            "deepest_overlap": deepest, "above_bound": above}


def run_tool(cmd):
    """Runs a command; returns its standard output, or None (the command
    and its error on standard error)."""
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        print(f"failed ({result.returncode}): {' '.join(cmd)}\n"
              f"{result.stderr.strip()}", file=sys.stderr)
        return None
    return result.stdout


def is_record(source):
    """True for a run record's folder (scripts/run_record.py), false for a
    lineage store."""
    return os.path.isfile(os.path.join(source, "record.json"))


def read_record(folder):
    """FOLDER/record.json (scripts/run_record.py); exits saying why when it
    cannot be read or is not a run record."""
    return read_json_object(os.path.join(folder, "record.json"),
                            ("run", "best", "statistics"))


def read_json_object(path, keys, flag=None):
    """The JSON object in PATH, which must hold KEYS; exits naming the file
    (after FLAG, the option that named it, if given) when it cannot be
    read, is not JSON, or lacks one of them."""
    where = f"{flag} {path}" if flag else path
    try:
        with open(path) as f:
            value = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"{where}: {e}")
    if not isinstance(value, dict):
        sys.exit(f"{where}: not a JSON object")
    for key in keys:
        if key not in value:
            sys.exit(f"{where}: no {key!r}")
    return value


def stem_of(source):
    """The run's name: a store's file name without .db, a record's run."""
    if is_record(source):
        return read_record(source)["run"]
    return os.path.basename(source)[:-3]


def record_files(folder, genome):
    stem = os.path.join(folder, genome)
    return stem + ".json", stem + ".config.txtpb"


def cluster(animat, sources, top):
    """`animat cluster`'s animats for the stores and records given: each
    (run, individual id, the analyse command's source arguments, entry)."""
    stores = [s for s in sources if not is_record(s)]
    records = [s for s in sources if is_record(s)]
    calls = []
    if stores:
        cmd = ["--top", str(top)]
        for s in stores:
            cmd += ["--db", s]
        calls.append(cmd)
    files = {}
    if records:
        cmd = []
        for folder in records:
            record = read_record(folder)
            if record["top"] < top:
                print(f"{folder}: the record holds the top "
                      f"{record['top']} phenotypes, not {top}",
                      file=sys.stderr)
                return None
            for p in record["phenotypes"][:top]:
                genome, config = record_files(folder, p["genome"])
                files[p["genome"]] = (record["run"], p["id"], genome, config)
                cmd += ["--genome", genome, "--config", config]
        calls.append(cmd)
    by_stem = {os.path.basename(s)[:-3]: s for s in stores}
    found = []
    for call in calls:
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "clusters.json")
            if run_tool([animat, "cluster", "-o", out] + call) is None:
                return None
            with open(out) as f:
                clustered = json.load(f)
        for a in clustered.get("animat", []):
            m = PHENOTYPE.match(a["name"])
            if m and m.group(1) in by_stem:
                found.append((m.group(1), int(m.group(2)),
                              ["--db", by_stem[m.group(1)], "--individual",
                               m.group(2)], a))
            elif a["name"] in files:
                run, ident, genome, config = files[a["name"]]
                found.append((run, ident, ["--genome", genome, "--config",
                                           config], a))
            else:
                found.append((None, None, None, a))
    return found


def phenotypes(animat, sources, top):
    """The top distinct phenotypes of each store or record (`animat
    cluster`), each analysed (`animat analyze`). Returns (phenotypes,
    problems)."""
    clustered = cluster(animat, sources, top)
    if clustered is None:
        return [], 1
    found, problems = [], 0
    for run, ident, source, a in clustered:
        if run is None:
            print(f"unexpected animat name {a['name']!r}", file=sys.stderr)
            problems += 1
            continue
        text = run_tool([animat, "analyze"] + source + ["-o", "-"])
        if text is None:
            problems += 1
            continue
        analysis = json.loads(text)
        label = a["label"].lower()
        again = analysis.get("strategy", {}).get("label", "OTHER").lower()
        if again != label:
            print(f"{a['name']}: cluster says {label}, analyze {again}",
                  file=sys.stderr)
            problems += 1
        values = dict(a.get("features", {}))
        for key in ("period_steps", "amplitude_mean"):
            camel = re.sub(r"_([a-z])", lambda x: x.group(1).upper(), key)
            values[key] = analysis.get(key, analysis.get(camel))
        found.append({"run": run, "id": ident, "label": label,
                      "margin": a.get("margin", 0.0),
                      "stable": bool(a.get("stable", False)),
                      "fitness": a.get("fitness"), "features": values})
    return found, problems


def summarise(name, runs, members):
    """Label counts with Wilson intervals, over phenotypes and over runs."""
    n = len(members)
    labels = {}
    for label in LABELS:
        k = sum(1 for p in members if p["label"] == label)
        lo, hi = stats.wilson(k, n)
        best_runs = sum(1 for r in runs if r["best_label"] == label)
        any_runs = sum(1 for r in runs
                       if any(p["label"] == label for p in r["phenotypes"]))
        labels[label] = {"k": k, "share": k / n if n else None,
                         "wilson95": [lo, hi], "runs_best": best_runs,
                         "runs_any": any_runs,
                         "stable": sum(1 for p in members
                                       if p["label"] == label and p["stable"])}
    return {"name": name, "runs": len(runs), "phenotypes": n,
            "labels": labels}


def fisher_pairs(names, labels_of):
    """Per label, Fisher's exact test of every pair of conditions (label
    against the rest of `labels_of[condition]`), Holm-adjusted within the
    label."""
    pairs = [(a, b) for i, a in enumerate(names) for b in names[i + 1:]]
    fisher = {}
    for label in LABELS:
        tests = []
        for a, b in pairs:
            ka = sum(1 for x in labels_of[a] if x == label)
            kb = sum(1 for x in labels_of[b] if x == label)
            table = [[ka, len(labels_of[a]) - ka],
                     [kb, len(labels_of[b]) - kb]]
            tests.append({"a": a, "b": b, "table": table,
                          "p": stats.fisher_exact(table)})
        for t, adjusted in zip(tests, stats.holm([t["p"] for t in tests])):
            t["p_holm"] = adjusted
        fisher[label] = tests
    return fisher


def compare(names, members_of, runs_of=None):
    """Fisher per label over every pair (Holm within the label) over
    phenotypes and, with `runs_of`, over runs by their best's label (a
    run's phenotypes are relatives: the runs are the independent units);
    and Kruskal-Wallis per feature over all the named conditions."""
    fisher = fisher_pairs(names, {c: [p["label"] for p in members_of[c]]
                                  for c in names})
    fisher_runs = None
    if runs_of is not None:
        fisher_runs = fisher_pairs(
            names, {c: [r["best_label"] for r in runs_of[c]] for c in names})
    kruskal = {}
    for feature in FEATURES:
        groups = [[p["features"][feature] for p in members_of[c]
                   if p["features"].get(feature) is not None] for c in names]
        if all(len(g) > 0 for g in groups):
            h, p = stats.kruskal_wallis(*groups)
            kruskal[feature] = {"h": h, "p": p,
                                "n": [len(g) for g in groups],
                                "medians": [median(g) for g in groups]}
        else:
            kruskal[feature] = None
    return {"conditions": names, "fisher": fisher, "fisher_runs": fisher_runs,
            "kruskal_wallis": kruskal}


def median(values):
    v = sorted(values)
    mid = len(v) // 2
    return v[mid] if len(v) % 2 else (v[mid - 1] + v[mid]) / 2


def p_text(p):
    return "<0.001" if p < 0.001 else f"{p:.3f}"


def markdown(report, bound):
    """The report's tables as Markdown."""
    out = ["| condition | runs | phenotypes | " +
           " | ".join(LABELS) + " |",
           "|---|---:|---:|" + "---|" * len(LABELS)]
    for s in report["summaries"]:
        cells = []
        for label in LABELS:
            x = s["labels"][label]
            lo, hi = x["wilson95"]
            cells.append(f"{x['k']} ({lo:.2f}–{hi:.2f}); best of "
                         f"{x['runs_best']}, any in {x['runs_any']}")
        out.append(f"| {s['name']} | {s['runs']} | {s['phenotypes']} | " +
                   " | ".join(cells) + " |")
    out.append("")
    for key, units in (("fisher", "phenotypes"),
                       ("fisher_runs", "runs, by their best's label")):
        comparisons = [c for c in report["comparisons"] if c.get(key)]
        if not comparisons:
            continue
        out.append(f"| comparison ({units}) | label | pair | counts (label, "
                   "rest) | Fisher p | Holm p |")
        out.append("|---|---|---|---|---:|---:|")
        for c in comparisons:
            title = " vs ".join(c["conditions"])
            for label in LABELS:
                for t in c[key][label]:
                    (ka, ra), (kb, rb) = t["table"]
                    if ka + kb == 0:
                        continue  # Neither has the label: nothing to test.
                    out.append(f"| {title} | {label} | {t['a']} / {t['b']} | "
                               f"{ka}, {ra} / {kb}, {rb} | {p_text(t['p'])} "
                               f"| {p_text(t['p_holm'])} |")
        out.append("")
    out.append("| comparison | feature | medians | H | p |")
    out.append("|---|---|---|---:|---:|")
    for c in report["comparisons"]:
        title = " vs ".join(c["conditions"])
        for feature in FEATURES:
            k = c["kruskal_wallis"][feature]
            if k is None:
                out.append(f"| {title} | {feature} | — | — | — |")
                continue
            medians = ", ".join(f"{m:.3g}" for m in k["medians"])
            out.append(f"| {title} | {feature.replace('_', ' ')} | {medians} "
                       f"| {k['h']:.2f} | {p_text(k['p'])} |")
    out.append("")
    out.append(f"| store | generations | best | ok individuals | deepest "
               f"unjoined overlap | ok above {bound:g} |")
    out.append("|---|---:|---:|---:|---:|---:|")
    for c in report["conditions"]:
        for r in c["runs"]:
            o = r["overlap"]
            out.append(f"| {c['name']}: {r['run']} | {o['generations']} | "
                       f"{o['best_fitness']:.2f} | {o['ok']:,} | "
                       f"{o['deepest_overlap']:.3f} | {o['above_bound']:,} "
                       f"({o['above_bound'] / o['ok']:.1%}) |")
    out.append("")
    out.append("| condition | run | labels of its top phenotypes, by "
               "fitness (margin; * stable under ±20%) |")
    out.append("|---|---|---|")
    for c in report["conditions"]:
        for r in c["runs"]:
            text = "; ".join(
                f"{p['label']} ({p['margin']:.2f}{'*' if p['stable'] else ''})"
                for p in r["phenotypes"])
            out.append(f"| {c['name']} | {r['run']} | {text} |")
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--animat", default="build/bin/animat")
    parser.add_argument("--condition", action="append", default=[],
                        help="NAME=GLOB of lineage stores or run records")
    parser.add_argument("--pool", action="append", default=[],
                        help="NAME=A+B+... of conditions pooled")
    parser.add_argument("--compare", action="append", default=[],
                        help="A,B[,...]: conditions (or pools) compared")
    parser.add_argument("--top", type=int, default=5)
    parser.add_argument("--overlap-bound", type=float, default=0.1)
    parser.add_argument("--out", default="docs/results/strategies")
    args = parser.parse_args()
    if args.top < 1 or not args.condition:
        parser.error("give --condition (one or more) and --top >= 1")

    conditions, members_of, problems = [], {}, 0
    for name, pattern in parse_pairs(args.condition, "--condition"):
        stores = sorted(glob.glob(pattern), key=natural_key)
        if not stores:
            sys.exit(f"strategy_report.py: no store matches {pattern!r}")
        found, bad = phenotypes(args.animat, stores, args.top)
        problems += bad
        runs = []
        for s in stores:
            stem = stem_of(s)
            mine = [p for p in found if p["run"] == stem]
            runs.append({"run": stem, "store": s, "phenotypes": mine,
                         "best_label": mine[0]["label"] if mine else None,
                         "overlap": store_overlap(s, args.overlap_bound)})
        conditions.append({"name": name, "runs": runs})
        members_of[name] = found
        print(f"{name}: {len(stores)} stores, {len(found)} phenotypes",
              file=sys.stderr)
    runs_of = {c["name"]: c["runs"] for c in conditions}
    for name, parts in parse_pairs(args.pool, "--pool"):
        names = parts.split("+")
        unknown = [n for n in names if n not in members_of]
        if unknown:
            sys.exit(f"strategy_report.py: --pool {name}: unknown {unknown}")
        members_of[name] = [p for n in names for p in members_of[n]]
        runs_of[name] = [r for n in names for r in runs_of[n]]
    comparisons = []
    for spec in args.compare:
        names = spec.split(",")
        unknown = [n for n in names if n not in members_of]
        if len(names) < 2 or unknown:
            sys.exit(f"strategy_report.py: --compare {spec!r}: two or more "
                     f"known conditions wanted (unknown: {unknown})")
        comparisons.append(compare(names, members_of, runs_of))
    report = {
        "top": args.top,
        "overlap_bound": args.overlap_bound,
        "conditions": conditions,
        "summaries": [summarise(n, runs_of[n], members_of[n])
                      for n in members_of],
        "comparisons": comparisons,
    }
    for c in conditions:
        for r in c["runs"]:
            r.pop("store")
    os.makedirs(os.path.dirname(args.out) or ".", exist_ok=True)
    with open(args.out + ".json", "w") as f:
        json.dump(report, f, indent=1, sort_keys=True)
    with open(args.out + ".md", "w") as f:
        f.write(markdown(report, args.overlap_bound))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
