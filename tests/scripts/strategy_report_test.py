#!/usr/bin/env python3
"""scripts/strategy_report.py's tables on hand-made phenotypes and a
hand-made store: label counts and Wilson intervals, per-run counts,
Fisher and Kruskal-Wallis between conditions, the overlap query."""

import os
import sqlite3
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..',
                                'scripts'))
import stats  # noqa: E402
import strategy_report as sr  # noqa: E402


def phenotype(run, label, synchrony, stable=False):
    return {"run": run, "id": 1, "label": label, "margin": 0.5,
            "stable": stable, "fitness": 1.0,
            "features": {"synchrony": synchrony, "fb_lag": 0.0,
                         "elongation": None, "period_steps": 100.0,
                         "amplitude_mean": 0.3}}


class StrategyReportTest(unittest.TestCase):
    def setUp(self):
        # Condition A: two runs, 3 turtles of 4; B: one run, no turtle.
        self.a = [phenotype("r1", "turtle", 0.9, stable=True),
                  phenotype("r1", "other", 0.1),
                  phenotype("r2", "turtle", 0.8),
                  phenotype("r2", "turtle", 0.7)]
        self.b = [phenotype("r3", "other", 0.2),
                  phenotype("r3", "jellyfish", 0.3)]

    def test_summary_counts_phenotypes_and_runs(self):
        runs = [{"best_label": "turtle", "phenotypes": self.a[:2]},
                {"best_label": "turtle", "phenotypes": self.a[2:]}]
        s = sr.summarise("A", runs, self.a)
        self.assertEqual((s["runs"], s["phenotypes"]), (2, 4))
        turtle = s["labels"]["turtle"]
        self.assertEqual((turtle["k"], turtle["runs_best"],
                          turtle["runs_any"], turtle["stable"]),
                         (3, 2, 2, 1))
        self.assertEqual(turtle["wilson95"], list(stats.wilson(3, 4)))
        other = s["labels"]["other"]
        self.assertEqual((other["k"], other["runs_best"], other["runs_any"]),
                         (1, 0, 1))
        self.assertEqual(s["labels"]["shark"]["k"], 0)

    def test_comparison(self):
        c = sr.compare(["A", "B"], {"A": self.a, "B": self.b})
        turtle, = c["fisher"]["turtle"]
        self.assertEqual(turtle["table"], [[3, 1], [0, 2]])
        self.assertAlmostEqual(turtle["p"],
                               stats.fisher_exact([[3, 1], [0, 2]]))
        self.assertEqual(turtle["p_holm"], turtle["p"])  # One pair.
        k = c["kruskal_wallis"]["synchrony"]
        self.assertEqual(k["n"], [4, 2])
        self.assertEqual(k["medians"], [0.75, 0.25])
        h, p = stats.kruskal_wallis([0.9, 0.1, 0.8, 0.7], [0.2, 0.3])
        self.assertAlmostEqual(k["h"], h)
        # A feature no phenotype has is not tested.
        self.assertIsNone(c["kruskal_wallis"]["elongation"])

    def test_comparison_over_runs_counts_each_run_once(self):
        runs = {"A": [{"best_label": "turtle"}, {"best_label": "turtle"}],
                "B": [{"best_label": "other"}]}
        c = sr.compare(["A", "B"], {"A": self.a, "B": self.b}, runs)
        turtle, = c["fisher_runs"]["turtle"]
        self.assertEqual(turtle["table"], [[2, 0], [0, 1]])
        self.assertAlmostEqual(turtle["p"],
                               stats.fisher_exact([[2, 0], [0, 1]]))
        # Over phenotypes as before.
        self.assertEqual(c["fisher"]["turtle"][0]["table"], [[3, 1], [0, 2]])
        self.assertIsNone(sr.compare(["A", "B"],
                                     {"A": self.a, "B": self.b})["fisher_runs"])
        text = sr.markdown({"conditions": [], "summaries": [],
                            "comparisons": [c]}, 0.1)
        self.assertIn("| comparison (runs, by their best's label) |", text)
        self.assertIn("| A vs B | turtle | A / B | 2, 0 / 0, 1 |", text)
        self.assertIn("| A vs B | turtle | A / B | 3, 1 / 0, 2 |", text)

    def test_three_conditions_are_holm_adjusted_per_label(self):
        c = sr.compare(["A", "B", "C"],
                       {"A": self.a, "B": self.b, "C": self.b})
        tests = c["fisher"]["turtle"]
        self.assertEqual([(t["a"], t["b"]) for t in tests],
                         [("A", "B"), ("A", "C"), ("B", "C")])
        self.assertEqual([t["p_holm"] for t in tests],
                         stats.holm([t["p"] for t in tests]))

    def test_overlap_query(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "run.db")
            db = sqlite3.connect(path)
            db.executescript("""
              CREATE TABLE runs (run_id INTEGER);
              CREATE TABLE generation_statistics (run_id INTEGER,
                generation INTEGER, best_fitness REAL, completed_at TEXT);
              CREATE TABLE individuals (run_id INTEGER, status TEXT,
                max_overlap REAL);
              INSERT INTO runs VALUES (1), (2);
              INSERT INTO generation_statistics VALUES
                (2, 0, 1.5, 'x'), (2, 1, 2.5, 'x'), (2, 2, 9.0, NULL),
                (1, 5, 99.0, 'x');
              INSERT INTO individuals VALUES
                (2, 'ok', 0.05), (2, 'ok', 0.2), (2, 'ok', 0.1),
                (2, 'failed', NULL), (1, 'ok', 0.9);
            """)
            db.commit()
            db.close()
            o = sr.store_overlap(path, 0.1)
        # The latest run only; the bound itself is not above it.
        self.assertEqual(o, {"generations": 2, "best_fitness": 2.5, "ok": 3,
                             "deepest_overlap": 0.2, "above_bound": 1})

    def test_markdown_names_every_condition(self):
        runs = [{"run": "r3", "best_label": "other", "phenotypes": self.b,
                 "overlap": {"generations": 2, "best_fitness": 2.5, "ok": 3,
                             "deepest_overlap": 0.2, "above_bound": 1}}]
        report = {"conditions": [{"name": "B", "runs": runs}],
                  "summaries": [sr.summarise("B", runs, self.b)],
                  "comparisons": []}
        text = sr.markdown(report, 0.1)
        self.assertIn("| B | 1 | 2 |", text)
        self.assertIn("| B: r3 | 2 | 2.50 | 3 | 0.200 | 1 (33.3%) |", text)
        self.assertIn("| B | r3 | other (0.50); jellyfish (0.50) |", text)


if __name__ == '__main__':
    unittest.main()
