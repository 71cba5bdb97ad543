#!/usr/bin/env python3
"""scripts/run_record.py on a hand-made store: the top distinct phenotypes
(fitness descending, then id; each state hash once, its members counted;
the last completed generation's ok members only), the overlap count, the
statuses of generation 0 and of the offspring; and scripts/
strategy_report.py reading the record in place of the store."""

import argparse
import json
import os
import sqlite3
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), '..', '..',
                                'scripts'))
import run_record  # noqa: E402
import strategy_report as sr  # noqa: E402

STORE = """
  CREATE TABLE runs (run_id INTEGER, seed INTEGER, config_text TEXT,
    build_id TEXT, state TEXT);
  CREATE TABLE generation_statistics (run_id INTEGER, generation INTEGER,
    size INTEGER, evaluated INTEGER, failed INTEGER, best_id INTEGER,
    best_fitness REAL, mean_fitness REAL, median_fitness REAL,
    completed_at TEXT);
  CREATE TABLE members (run_id INTEGER, generation INTEGER, id INTEGER);
  CREATE TABLE evaluations (run_id INTEGER, id INTEGER, status TEXT,
    fitness REAL, state_hash TEXT);
  CREATE TABLE births (run_id INTEGER, id INTEGER, generation INTEGER);
  CREATE VIEW individuals AS SELECT b.run_id, b.id, b.generation, e.status,
    e.fitness, e.state_hash, 32 AS cells, 70 AS springs, 40 AS chambers,
    18 AS skin_edges, CASE WHEN e.status = 'ok' THEN b.id / 100.0 END
    AS max_overlap
    FROM births b LEFT JOIN evaluations e ON e.run_id = b.run_id
    AND e.id = b.id;
  INSERT INTO runs VALUES (1, 9, 'old', 'b0', 'finished'),
    (2, 7, 'model {\n  physics {\n    drag_normal: 0.1\n  }\n}\n', 'b1',
     'running');
  INSERT INTO generation_statistics VALUES
    (2, 0, 4, 4, 1, 3, 3.0, 2.0, 2.0, 'x'),
    (2, 1, 6, 6, 1, 14, 5.0, 3.0, 3.0, 'x'),
    (2, 2, 6, 2, 0, 20, 9.0, 9.0, 9.0, NULL),
    (1, 0, 1, 1, 0, 99, 99.0, 99.0, 99.0, 'x');
  INSERT INTO births VALUES (2, 1, 0), (2, 2, 0), (2, 3, 0), (2, 4, 0),
    (2, 11, 1), (2, 12, 1), (2, 13, 1), (2, 14, 1), (2, 15, 1), (2, 16, 1),
    (2, 20, 2), (1, 99, 0);
  INSERT INTO evaluations VALUES (2, 1, 'ok', 1.0, 'a'),
    (2, 2, 'ok', 2.0, 'b'), (2, 3, 'ok', 3.0, 'c'),
    (2, 4, 'non_viable', NULL, ''),
    (2, 11, 'ok', 4.0, 'h1'), (2, 12, 'ok', 5.0, 'h2'),
    (2, 13, 'ok', 4.0, 'h3'), (2, 14, 'ok', 5.0, 'h1'),
    (2, 15, 'too_few_cells', NULL, ''), (2, 16, 'ok', 4.0, 'h1'),
    (2, 20, 'ok', 9.0, 'h9'), (1, 99, 'ok', 99.0, 'z');
  INSERT INTO members VALUES (2, 1, 3), (2, 1, 11), (2, 1, 12), (2, 1, 13),
    (2, 1, 14), (2, 1, 15), (2, 1, 16), (2, 2, 20);
"""


class RunRecordTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "run.db")
        db = sqlite3.connect(self.path)
        db.executescript(STORE)
        db.commit()
        db.close()

    def tearDown(self):
        self.tmp.cleanup()

    def test_top_phenotypes_follow_the_cluster_rule(self):
        r = run_record.read_store(self.path, 3, 0.1)
        # Generation 1 is the last completed; 12 and 14 tie at 5.0 (id
        # decides); 11 and 16 share 14's hash; 13 comes next; 15 failed.
        self.assertEqual([(p["id"], p["members"]) for p in r["phenotypes"]],
                         [(12, 1), (14, 3), (13, 1)])
        self.assertEqual(r["generations"], 2)
        self.assertEqual(r["best"]["id"], 14)
        self.assertEqual((r["seed"], r["build_id"]), (7, "b1"))
        self.assertEqual(len(r["statistics"]), 2)

    def test_overlap_and_statuses(self):
        r = run_record.read_store(self.path, 5, 0.1)
        # ok individuals of run 2: ids 1, 2, 3, 11-14, 16, 20 (overlap
        # id / 100): above 0.1 are 11-14, 16 and 20.
        self.assertEqual(r["overlap"], {"bound": 0.1, "ok": 9,
                                        "deepest": 0.2, "above_bound": 6})
        self.assertEqual(r["statuses"]["initial"],
                         {"non_viable": 1, "ok": 3})
        self.assertEqual(r["statuses"]["offspring"],
                         {"ok": 6, "too_few_cells": 1})

    def test_overlap_counts_at_another_bound(self):
        db = sqlite3.connect(self.path)
        try:
            # Above 0.13: 14, 16 and 20; run 1's individual is not counted.
            self.assertEqual(run_record.overlap_counts(db, 2, 0.13),
                             {"bound": 0.13, "ok": 9, "deepest": 0.2,
                              "above_bound": 3})
            self.assertEqual(run_record.overlap_counts(db, 3, 0.1),
                             {"bound": 0.1, "ok": 0, "deepest": None,
                              "above_bound": 0})
        finally:
            db.close()

    def test_the_bound_must_be_a_finite_fraction(self):
        self.assertEqual(run_record.overlap_bound("0.1"), 0.1)
        self.assertEqual(run_record.overlap_bound("0"), 0.0)
        for bad in ("nan", "-0.1", "inf", "", "tenth"):
            with self.assertRaises(argparse.ArgumentTypeError, msg=bad):
                run_record.overlap_bound(bad)

    def test_strategy_report_reads_a_record(self):
        record = run_record.read_store(self.path, 5, 0.1)
        record.update(run="dn0.1-seed7", top=5)
        folder = os.path.join(self.tmp.name, "dn0.1-seed7")
        os.makedirs(folder)
        with open(os.path.join(folder, "record.json"), "w") as f:
            json.dump(record, f)
        self.assertTrue(sr.is_record(folder))
        self.assertFalse(sr.is_record(self.path))
        self.assertEqual(sr.stem_of(folder), "dn0.1-seed7")
        self.assertEqual(sr.stem_of(self.path), "run")
        from_record = sr.store_overlap(folder, 0.1)
        self.assertEqual(from_record, {"generations": 2, "best_fitness": 5.0,
                                       "ok": 9, "deepest_overlap": 0.2,
                                       "above_bound": 6})
        with self.assertRaises(SystemExit):
            sr.store_overlap(folder, 0.2)  # Counted at another bound.

    def test_a_store_without_a_completed_generation_is_refused(self):
        db = sqlite3.connect(self.path)
        db.execute("DELETE FROM generation_statistics WHERE run_id = 2")
        db.commit()
        db.close()
        with self.assertRaises(ValueError):
            run_record.read_store(self.path, 5, 0.1)


if __name__ == '__main__':
    unittest.main()
