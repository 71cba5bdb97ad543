#!/usr/bin/env python3
"""scripts/energy_report.py and guidance_report.py on runs of another name
(--name: the third replication's energy-holding and guidance-lead arms),
each over a tiny evolution made here: the energy report compares its arm
with the replication's d_N = 1 bests and an earlier energy report's bests,
all under the arm's cost model (each checked against `animat simulate`
under that model); the guidance report writes its files under the name.
A folder without such stores is refused.

  arm_reports_test.py ANIMAT
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
SCRIPTS = os.path.join(ROOT, "scripts")
ANIMAT = None

# Short motion and tiny populations: the reports' plumbing, not evolution.
ENERGY_ARM = """
model {
  physics { drag_normal: 1 drag_tangential: 0.005 integrator: RK4
            substeps: 1 contact_rule: NONE }
  evaluation { fitness: DISTANCE_WITHIN_ENERGY_BUDGET energy_budget: 10000
               holding_cost: 0.05 motion_steps: 600 }
}
evolution { seed: 7 population: 6 generations: 2 elite: 1 }
"""
GUIDANCE_ARM = """
model {
  guidance { enabled: true trials: 2 lead_steps: 200 }
  evaluation { motion_steps: 600 }
}
evolution { seed: 3 population: 6 generations: 2 elite: 1 }
"""


def evolve(tmp, text, db):
    config = os.path.join(tmp, "arm.txtpb")
    with open(config, "w") as f:
        f.write(text)
    os.makedirs(os.path.dirname(db), exist_ok=True)
    subprocess.run([ANIMAT, "evolve", "--config", config, "--db", db,
                    "--workers", "1"], check=True, capture_output=True)


def script(name, *args):
    return subprocess.run([sys.executable, os.path.join(SCRIPTS, name),
                           "--animat", ANIMAT, *args],
                          capture_output=True, text=True, cwd=ROOT)


def simulate(genome, config):
    out = subprocess.run([ANIMAT, "simulate", "--genome", genome, "--config",
                          config, "--json"], check=True, capture_output=True,
                         text=True, cwd=ROOT)
    return json.loads(out.stdout)


class EnergyArmTest(unittest.TestCase):
    def test_an_arm_against_its_partners_under_its_cost_model(self):
        with tempfile.TemporaryDirectory() as tmp:
            stores = os.path.join(tmp, "stores")
            evolve(tmp, ENERGY_ARM, os.path.join(stores, "holding-seed7.db"))
            dest = os.path.join(tmp, "dest")
            run = script("energy_report.py", "--name", "holding",
                         "--report", "holding-report", "--out", stores,
                         "--dest", dest, "--replication",
                         os.path.join("docs", "results", "replication.json"),
                         "--partners",
                         os.path.join("docs", "results", "energy.json"))
            self.assertEqual(run.returncode, 0, run.stderr)
            with open(os.path.join(dest, "holding-report.json")) as f:
                runs = json.load(f)["runs"]
            kinds = [r["fitness_kind"] for r in runs]
            self.assertEqual(kinds, ["energy"] + ["distance"] * 4 +
                             ["energy (energy.json)"] * 3)
            arm = runs[0]
            self.assertEqual((arm["name"], arm["seed"]), ("holding-seed7", 7))
            for name in ("holding-report.md", "holding.svg",
                         "holding-seed7-strip.svg",
                         "holding-seed7-activity.svg"):
                self.assertTrue(os.path.isfile(os.path.join(dest, name)),
                                name)
            # E = W + c_h H, split for every row: W is E without holding.
            for r in runs:
                self.assertLessEqual(r["work"], r["energy"], r["name"])
                self.assertAlmostEqual(
                    r["work"] + 0.05 * r["held_per_step"] * 600, r["energy"],
                    delta=1e-9 * r["energy"], msg=r["name"])
            with open(os.path.join(dest, "holding-report.md")) as f:
                self.assertIn("| work | held per step |", f.read())
            # Every partner as the arm's model counts it: the holding cost
            # included.
            for r in runs[1:]:
                here = simulate(r["genome"], arm["config"])
                own = simulate(r["genome"], r["genome"][:-len(".json")] +
                               ".config.txtpb")
                self.assertEqual(float.hex(r["energy_fitness"]),
                                 float.hex(here["fitness"]), r["name"])
                self.assertEqual(r["energy"], here["energy"])
                self.assertGreater(r["energy"], 0.0)
                self.assertEqual(r["fitness"], own["fitness"], r["name"])

    def test_an_arm_without_a_holding_cost_has_no_split(self):
        with tempfile.TemporaryDirectory() as tmp:
            stores = os.path.join(tmp, "stores")
            evolve(tmp, ENERGY_ARM.replace("holding_cost: 0.05",
                                           "holding_cost: 0"),
                   os.path.join(stores, "work-seed7.db"))
            dest = os.path.join(tmp, "dest")
            run = script("energy_report.py", "--name", "work", "--out",
                         stores, "--dest", dest, "--replication",
                         os.path.join("docs", "results", "replication.json"))
            self.assertEqual(run.returncode, 0, run.stderr)
            with open(os.path.join(dest, "energy.json")) as f:
                runs = json.load(f)["runs"]
            self.assertTrue(all(r["work"] is None and
                                r["held_per_step"] is None for r in runs))
            with open(os.path.join(dest, "energy.md")) as f:
                self.assertNotIn("held per step", f.read())

    def test_a_folder_without_stores_of_the_name(self):
        with tempfile.TemporaryDirectory() as tmp:
            run = script("energy_report.py", "--name", "none", "--out", tmp,
                         "--dest", tmp)
            self.assertEqual(run.returncode, 1)
            self.assertIn("no stores none-seedS.db", run.stderr)
            run = script("energy_report.py", "--name", "none", "--out",
                         os.path.join(tmp, "missing"), "--dest", tmp)
            self.assertEqual(run.returncode, 1)
            self.assertIn("no such folder", run.stderr)


    def test_a_report_to_compare_with_that_cannot_be_read(self):
        with tempfile.TemporaryDirectory() as tmp:
            stores = os.path.join(tmp, "stores")
            os.makedirs(stores)
            open(os.path.join(stores, "holding-seed1.db"), "w").close()
            # No replication.json in DEST, and none named.
            run = script("energy_report.py", "--name", "holding", "--out",
                         stores, "--dest", tmp)
            self.assertEqual(run.returncode, 1)
            self.assertIn("--replication " + os.path.join(tmp,
                          "replication.json"), run.stderr)
            self.assertNotIn("Traceback", run.stderr)
            bad = os.path.join(tmp, "bad.json")
            with open(bad, "w") as f:
                f.write("[1, 2")
            run = script("energy_report.py", "--name", "holding", "--out",
                         stores, "--dest", tmp, "--replication",
                         os.path.join("docs", "results", "replication.json"),
                         "--partners", bad)
            self.assertEqual(run.returncode, 1)
            self.assertIn("--partners " + bad, run.stderr)
            self.assertNotIn("Traceback", run.stderr)
            with open(bad, "w") as f:
                f.write("{}")
            run = script("energy_report.py", "--name", "holding", "--out",
                         stores, "--dest", tmp, "--replication", bad)
            self.assertEqual(run.returncode, 1)
            self.assertIn("no 'runs'", run.stderr)


class GuidanceArmTest(unittest.TestCase):
    def test_the_files_carry_the_runs_name(self):
        with tempfile.TemporaryDirectory() as tmp:
            stores = os.path.join(tmp, "stores")
            evolve(tmp, GUIDANCE_ARM, os.path.join(stores, "lead-seed3.db"))
            dest = os.path.join(tmp, "dest")
            run = script("guidance_report.py", "--name", "lead", "--out",
                         stores, "--dest", dest)
            self.assertEqual(run.returncode, 0, run.stderr)
            for name in ("lead.md", "lead.json", "lead-fitness.svg",
                         "lead-seed3-trials.svg", "lead-seed3.html"):
                self.assertTrue(os.path.isfile(os.path.join(dest, name)),
                                name)
            with open(os.path.join(dest, "lead.json")) as f:
                run_, = json.load(f)["runs"]
            self.assertEqual(run_["name"], "lead-seed3")
            overlap = run_["overlap"]
            self.assertEqual(overlap["bound"], 0.1)
            self.assertGreater(overlap["ok"], 0)
            self.assertLessEqual(overlap["above_bound"], overlap["ok"])
            with open(os.path.join(dest, "lead.md")) as f:
                self.assertIn("| lead-seed3 | " + f"{overlap['ok']:,} | ",
                              f.read())

    def test_a_bad_overlap_bound_is_refused_before_any_work(self):
        with tempfile.TemporaryDirectory() as tmp:
            for bad in ("nan", "-0.1", "inf"):
                run = script("guidance_report.py", "--out", tmp, "--dest",
                             tmp, "--overlap-bound", bad)
                self.assertEqual(run.returncode, 2, bad)
                self.assertIn("--overlap-bound", run.stderr)
                self.assertEqual(os.listdir(tmp), [], bad)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: arm_reports_test.py ANIMAT")
    ANIMAT = os.path.abspath(sys.argv.pop(1))
    unittest.main()
