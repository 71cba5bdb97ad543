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


def best(name, capped, shares, kernel=5.0, steps=60):
    return {'animat': name, 'capped_share': capped,
            'morphogen_shares': shares, 'kernel_sum_mean': kernel,
            'crossing_steps': steps}


class SummaryTest(unittest.TestCase):

    def test_groups_the_bests_by_name(self):
        rows = [best('v3-dn1-seed1-7', 0.5, [1.0, 0.0], 6.0, 80),
                best('v3-dn1-seed2-9', 0.1, [0.2, 0.96], 4.0, 50),
                best('v3-dn1-seed3-4', 0.3, [0.97], 5.0, 70),
                best('v3-dn10-seed1-3', 0.9, [0.5], 7.0, 90)]
        [one, ten] = signal_saturation.summary(
            rows, [('d_N 1', r'-dn1-'), ('d_N 10', r'-dn10-')])
        self.assertEqual(one['bests'], 3)
        self.assertEqual(one['capped_share_median'], 0.3)
        self.assertEqual(one['capped_share_min'], 0.1)
        self.assertEqual(one['capped_share_max'], 0.5)
        self.assertEqual(one['with_hot_morphogen'], 2)  # 1.0 and 0.97
        self.assertEqual(one['kernel_sum_mean_min'], 4.0)
        self.assertEqual(one['crossing_steps_max'], 80)
        self.assertEqual(ten['bests'], 1)
        self.assertEqual(ten['with_hot_morphogen'], 0)
        self.assertIn('| d_N 1 | 3 | 30% (10–50%) | 2 of 3 | 4.0–6.0 | 50–80 |',
                      signal_saturation.summary_markdown([one, ten]))

    def test_an_even_count_takes_the_middle_pair(self):
        rows = [best('a', 0.2, []), best('b', 0.4, [])]
        [g] = signal_saturation.summary(rows, [('all', '.')])
        self.assertAlmostEqual(g['capped_share_median'], 0.3)

    def test_a_group_without_bests_is_an_error(self):
        with self.assertRaises(ValueError):
            signal_saturation.summary([best('a', 0.2, [])], [('x', 'zzz')])


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
