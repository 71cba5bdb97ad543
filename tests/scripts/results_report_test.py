#!/usr/bin/env python3
"""scripts/results_report.py: the choice of each label's panel, and a whole
report over one kept run record (its best copied and simulated again, its
fitness curves, the panel of its label), then the same record with its
best's fitness altered, which the report must refuse.

  results_report_test.py ANIMAT
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import results_report as rr  # noqa: E402

RECORD = os.path.join(ROOT, "docs", "results", "runs", "v3-dn10-seed2")
ANIMAT = None


def phenotype(run, label, stable, margin, fitness):
    return {"run": run, "id": int(fitness), "label": label,
            "stable": stable, "margin": margin, "fitness": fitness,
            "features": {"period_steps": 100.0, "amplitude_mean": 0.3}}


class TradeTest(unittest.TestCase):
    def test_rank_correlation_of_amplitude_and_frequency(self):
        # Amplitude rising as the period shortens: rho = +1; a phenotype
        # without a period is left out.
        points = [{"period_steps": p, "amplitude_mean": a}
                  for p, a in ((100, 0.1), (50, 0.2), (25, 0.3), (None, 1))]
        self.assertEqual(rr.trade(points), (1.0, 3))
        self.assertEqual(rr.trade(points[:2]), (None, 2))
        self.assertEqual(rr.rho_text(None, 2), "—")

    def test_one_period_for_all_is_undefined_not_nan(self):
        # Five relatives with one period: no ranks to correlate.
        points = [{"period_steps": 80, "amplitude_mean": a}
                  for a in (0.1, 0.2, 0.3, 0.4, 0.5)]
        self.assertEqual(rr.trade(points), (None, 5))
        self.assertEqual(rr.rho_text(None, 5), "undefined")
        self.assertEqual(rr.rho_text(-0.5, 5), "-0.50")


class ChoiceTest(unittest.TestCase):
    def test_stable_then_margin_then_fitness(self):
        chosen = rr.clearest([
            phenotype("a", "turtle", False, 0.9, 50.0),
            phenotype("b", "turtle", True, 0.3, 10.0),
            phenotype("c", "turtle", True, 0.3, 20.0),
            phenotype("d", "other", False, 0.1, 5.0),
            phenotype("e", "other", False, 0.2, 1.0),
        ])
        self.assertEqual(chosen["turtle"]["run"], "c")
        self.assertEqual(chosen["other"]["run"], "e")
        self.assertEqual(sorted(chosen), ["other", "turtle"])


class ReportTest(unittest.TestCase):
    def report(self, records, tmp):
        strategies = os.path.join(tmp, "strategies.json")
        with open(os.path.join(RECORD, "record.json")) as f:
            record = json.load(f)
        best = record["best"]
        with open(strategies, "w") as f:
            json.dump({"conditions": [{"name": "c", "runs": [{
                "run": record["run"], "best_label": "turtle",
                "phenotypes": [phenotype(record["run"], "turtle", True,
                                         0.5, best["fitness"]) |
                               {"id": best["id"]}]}]}]}, f)
        dest = os.path.join(tmp, "dest")
        run = subprocess.run(
            [sys.executable, os.path.join(ROOT, "scripts",
                                          "results_report.py"),
             "--animat", ANIMAT, "--condition", f"c={records}",
             "--strategies", strategies, "--dest", dest,
             "--bests", os.path.join(tmp, "bests")],
            capture_output=True, text=True, cwd=tmp)
        return run, dest, record

    def test_a_kept_record(self):
        with tempfile.TemporaryDirectory() as tmp:
            run, dest, record = self.report(RECORD, tmp)
            self.assertEqual(run.returncode, 0, run.stderr)
            with open(os.path.join(dest, "runs.json")) as f:
                out = json.load(f)
            row, = out["runs"]
            self.assertTrue(row["replays"])
            self.assertEqual(row["best_label"], "turtle")
            self.assertEqual(row["generations"], record["generations"])
            stem = record["best"]["genome"]
            for ext in (".json", ".config.txtpb"):
                self.assertTrue(os.path.isfile(
                    os.path.join(tmp, "bests", stem + ext)))
            self.assertTrue(os.path.isfile(os.path.join(dest,
                                                        "fitness-c.svg")))
            panel = out["panels"]["turtle"]
            self.assertTrue(panel["drawn"])
            for kind in rr.PANELS:
                self.assertTrue(os.path.isfile(os.path.join(
                    dest, f"{panel['stem']}-{kind}.svg")))
            with open(os.path.join(dest, "runs.md")) as f:
                self.assertIn("same bits", f.read())
            claims = row["claims"]
            self.assertEqual(claims["best_over_generation_0"],
                             record["best"]["fitness"] /
                             record["statistics"][0]["best_fitness"])
            self.assertEqual(len(claims["phenotype_cells"]),
                             len(record["phenotypes"]))
            self.assertTrue(all(c == 32 for c in claims["phenotype_cells"]))
            self.assertGreaterEqual(claims["glide"]["quiet_share"], 0.0)
            # One phenotype's features: too few for a rank correlation.
            self.assertIsNone(claims["spearman_amplitude_frequency"])
            self.assertEqual(claims["spearman_points"], 1)

    def test_a_best_that_does_not_replay_fails_the_report(self):
        with tempfile.TemporaryDirectory() as tmp:
            copy = os.path.join(tmp, "records", "v3-dn10-seed2")
            shutil.copytree(RECORD, copy)
            path = os.path.join(copy, "record.json")
            with open(path) as f:
                record = json.load(f)
            record["best"]["fitness"] += 1e-9
            with open(path, "w") as f:
                json.dump(record, f)
            run, dest, _ = self.report(copy, tmp)
            self.assertEqual(run.returncode, 1)
            self.assertIn("simulated again", run.stderr)
            with open(os.path.join(dest, "runs.json")) as f:
                self.assertFalse(json.load(f)["runs"][0]["replays"])

    def test_a_malformed_record_or_strategies_file_is_named(self):
        with tempfile.TemporaryDirectory() as tmp:
            copy = os.path.join(tmp, "records", "v3-dn10-seed2")
            shutil.copytree(RECORD, copy)
            path = os.path.join(copy, "record.json")
            for text, why in (('{"run": "x", ', "Expecting"),
                              ('{"run": "x"}', "no 'best'"),
                              ("[]", "not a JSON object")):
                with open(path, "w") as f:
                    f.write(text)
                run, _, _ = self.report(copy, tmp)
                self.assertEqual(run.returncode, 1, text)
                self.assertIn(path, run.stderr)
                self.assertIn(why, run.stderr)
                self.assertNotIn("Traceback", run.stderr)
            run = subprocess.run(
                [sys.executable, os.path.join(ROOT, "scripts",
                                              "results_report.py"),
                 "--animat", ANIMAT, "--condition", f"c={RECORD}",
                 "--strategies", os.path.join(tmp, "missing.json"),
                 "--dest", os.path.join(tmp, "dest"),
                 "--bests", os.path.join(tmp, "bests")],
                capture_output=True, text=True, cwd=tmp)
            self.assertEqual(run.returncode, 1)
            self.assertIn("missing.json", run.stderr)
            self.assertNotIn("Traceback", run.stderr)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: results_report_test.py ANIMAT")
    ANIMAT = os.path.abspath(sys.argv.pop(1))
    unittest.main()
