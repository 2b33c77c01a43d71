"""The committed benchmark is what the code gives (ctest Benchmark.committed_runs):
2 cases of every family of benchmarks/default.json, with every configuration,
re-run by the rrlab binary, match their rows of the committed per-run CSV
(benchmarks/default-runs.csv, which the README and docs/results.md quote) in
every column but the run id and the step times (wall clock), and in every
column the CSV predates when it is empty now; the smoothness columns (rms_qddot,
max_qddot, rms_jerk, max_jerk) and the steps past limits after integration
(position_limit_steps, velocity_limit_steps), measures of the motion that no
success criterion reads, are checked once a committed file is re-run and has them. Likewise the first case of
every committed reproduction sweep (benchmarks/reproductions/NAME.json with its
NAME-runs.csv) against its CSV, and the marks table of docs/results.md, the
README's tallies and the Papers panel's data against scripts/reproduction-table.

Runs against the Release build only (the Makefile's RELEASE_TESTS): that build
wrote the committed file, and other compilers may round differently.

    committed_benchmark_test.py RRLAB_BINARY
"""
import csv
import json
import lzma
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RRLAB = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(SOURCE_DIR, "build", "cli", "rrlab")
CASES_PER_FAMILY = 2
CASES_PER_REPRODUCTION = 1  # some are minutes of multi_preview per case
# newer than some committed files: smoothness, and the steps past limits after integration
NEWER_COLUMNS = {"rms_qddot", "max_qddot", "rms_jerk", "max_jerk", "position_limit_steps", "velocity_limit_steps"}


def deterministic_rows(path, keys=None):
    """The rows of a per-run CSV (.csv or .csv.xz) by run key, without the run id and the step times;
    only the given keys' rows when keys is a set (a 100,000-row file is not held whole)."""
    opener = lzma.open if path.endswith(".xz") else open
    with opener(path, "rt", newline="", encoding="utf-8") as f:
        return {row["key"]: {k: v for k, v in row.items() if k != "run" and not k.startswith("step_us")}
                for row in csv.DictReader(f) if keys is None or row["key"] in keys}


class CommittedBenchmark(unittest.TestCase):
    def check_slice(self, spec_path, committed_csv, cases_per_entry):
        """Re-runs the first cases of every entry of the spec and compares their rows."""
        with open(spec_path, encoding="utf-8") as f:
            spec = json.load(f)
        for entry in spec["scenarios"]:
            if isinstance(entry, dict):
                entry["count"] = min(entry.get("count", 1), cases_per_entry)
        with tempfile.TemporaryDirectory() as tmp:
            spec_file = os.path.join(tmp, "slice.json")
            with open(spec_file, "w", encoding="utf-8") as f:
                json.dump(spec, f)
            out = os.path.join(tmp, "slice.csv")
            done = subprocess.run([RRLAB, "sweep", spec_file, "--db", os.path.join(tmp, "slice.db"), "--jobs", "2",
                                   "--out", out, "--scenarios", os.path.join(SOURCE_DIR, "scenarios")],
                                  capture_output=True, text=True, timeout=360)
            self.assertEqual(done.returncode, 0, done.stderr)
            now = deterministic_rows(out)
        committed = deterministic_rows(committed_csv, set(now))
        cases = sum(e.get("count", 1) if isinstance(e, dict) else 1 for e in spec["scenarios"])
        configs = len({row["config"] for row in now.values()})  # value lists expanded
        self.assertEqual(len(now), cases * configs)
        name = os.path.relpath(committed_csv, SOURCE_DIR)
        for key, row in now.items():
            self.assertIn(key, committed, f"{key} is not in {name}")
            for column, value in row.items():
                if column not in committed[key] and (value == "" or column in NEWER_COLUMNS):
                    continue  # a column added since the CSV was written, empty on these runs: nothing drifted
                self.assertEqual(committed[key].get(column), value,
                                 f"{key} {column}: {name} no longer matches the code; "
                                 "re-run it (docs/results.md)")

    def test_a_slice_of_the_default_suite_matches_the_committed_runs(self):
        self.check_slice(os.path.join(SOURCE_DIR, "benchmarks", "default.json"),
                         os.path.join(SOURCE_DIR, "benchmarks", "default-runs.csv"), CASES_PER_FAMILY)

    def test_a_slice_of_the_full_suite_matches_its_committed_runs(self):
        self.check_slice(os.path.join(SOURCE_DIR, "benchmarks", "full.json"),
                         os.path.join(SOURCE_DIR, "benchmarks", "full-runs.csv.xz"), CASES_PER_FAMILY)

    def test_a_slice_of_every_reproduction_sweep_matches_its_committed_runs(self):
        folder = os.path.join(SOURCE_DIR, "benchmarks", "reproductions")
        specs = sorted(f for f in os.listdir(folder)
                       if f.endswith(".json") and os.path.exists(os.path.join(folder, f[:-5] + "-runs.csv")))
        self.assertTrue(specs)
        for spec in specs:
            with self.subTest(spec=spec):
                self.check_slice(os.path.join(folder, spec), os.path.join(folder, spec[:-5] + "-runs.csv"),
                                 CASES_PER_REPRODUCTION)

    def test_the_marks_table_in_the_docs_is_what_the_committed_sweeps_give(self):
        """docs/results.md holds scripts/reproduction-table's output as printed (rates and marks by the rule)."""
        done = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "scripts", "reproduction-table"), "--check",
                               os.path.join(SOURCE_DIR, "docs", "results.md")], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr + " (re-run scripts/reproduction-table into docs/results.md)")

    def test_the_readmes_tallies_count_the_marks_table_row_for_row(self):
        """Each paper's README line reads "N ✓, M ◐, L ✗ of K; R of them (rrlab)" as scripts/reproduction-table counts
        the rows of paper-rows.json, the rows the Papers panel shows."""
        done = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "scripts", "reproduction-table"), "--check-tallies",
                               os.path.join(SOURCE_DIR, "README.md")], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0, done.stderr + " (copy scripts/reproduction-table --tallies into README.md)")

    def test_the_dashboards_papers_panel_shows_the_same_marks(self):
        """web/data/papers.json (the Papers panel) is what scripts/reproduction-table --papers-json prints."""
        done = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "scripts", "reproduction-table"), "--check-papers-json",
                               os.path.join(SOURCE_DIR, "web", "data", "papers.json")], capture_output=True, text=True)
        self.assertEqual(done.returncode, 0,
                         done.stderr + " (re-run scripts/reproduction-table --papers-json > web/data/papers.json)")


if __name__ == "__main__":
    unittest.main(verbosity=2)
