#!/usr/bin/env python3
"""scripts/signal_saturation.py reading run records (docs/results/runs/):
a record of a second-edition run made again measures its best exactly as
the same best kept in docs/results/bests/ measures, under the model the
record names (v2 without contacts, v3 with them).

  signal_saturation_test.py ANIMAT
"""

import glob
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
sys.path.insert(0, os.path.join(ROOT, 'scripts'))
import signal_saturation  # noqa: E402

ANIMAT = None


class ModelOfTest(unittest.TestCase):

    def test_names_the_model_by_its_contacts(self):
        self.assertEqual(
            signal_saturation.model_of('physics {\n contacts: false\n}'), 'v2')
        self.assertEqual(
            signal_saturation.model_of('physics { contact_rule: NONE }'), 'v2')
        self.assertEqual(
            signal_saturation.model_of('physics { contact_rule: ALL }'), 'v3')
        self.assertEqual(signal_saturation.model_of('model {}'), 'v3')


class RecordsTest(unittest.TestCase):

    def test_a_record_measures_as_its_kept_best(self):
        records = sorted(
            os.path.dirname(p)
            for p in glob.glob(os.path.join(ROOT, 'docs', 'results', 'runs',
                                            '*', 'record.json')))
        self.assertTrue(records, 'no run records')
        with tempfile.TemporaryDirectory() as scratch:
            out = os.path.join(scratch, 'saturation')
            command = [sys.executable,
                       os.path.join(ROOT, 'scripts', 'signal_saturation.py'),
                       '--animat', ANIMAT, '--out', out]
            for record in records:
                command += ['--db', record]
            done = subprocess.run(command, capture_output=True, text=True,
                                  check=False)
            self.assertEqual(done.returncode, 0, done.stderr)
            with open(out + '.json') as f:
                rows = {r['animat']: r for r in json.load(f)['bests']}
        compared = 0
        for record in records:
            with open(os.path.join(record, 'record.json')) as f:
                data = json.load(f)
            genome = data['best']['genome']
            self.assertIn(genome, rows)
            mine = rows[genome]
            self.assertEqual(mine['model'],
                             signal_saturation.model_of(data['config_text']))
            if not genome.startswith('v2-'):
                continue
            kept = rows.get(genome[len('v2-'):])
            if kept is None:
                continue  # The second edition kept another best.
            for key in kept:
                if key != 'animat':
                    self.assertEqual(mine[key], kept[key], genome + ' ' + key)
            compared += 1
        self.assertGreater(compared, 0, 'no record of a kept best')


if __name__ == '__main__':
    ANIMAT = sys.argv.pop(1)
    unittest.main()
