"""The committed benchmark is what the code gives (ctest Benchmark.committed_runs):
2 cases of every family of benchmarks/default.json, with every configuration,
re-run by the rrlab binary, match their rows of the committed per-run CSV
(benchmarks/default-runs.csv, which the README and docs/results.md quote) in
every column but the run id and the step times (wall clock).

Runs against the Release build only (the Makefile's RELEASE_TESTS): that build
wrote the committed file, and other compilers may round differently.

    committed_benchmark_test.py RRLAB_BINARY
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RRLAB = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(SOURCE_DIR, "build", "cli", "rrlab")
CASES_PER_FAMILY = 2


def deterministic_rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return {row["key"]: {k: v for k, v in row.items() if k != "run" and not k.startswith("step_us")}
                for row in csv.DictReader(f)}


class CommittedBenchmark(unittest.TestCase):
    def test_a_slice_of_the_default_suite_matches_the_committed_runs(self):
        with open(os.path.join(SOURCE_DIR, "benchmarks", "default.json"), encoding="utf-8") as f:
            spec = json.load(f)
        for entry in spec["scenarios"]:
            entry["count"] = CASES_PER_FAMILY
        with tempfile.TemporaryDirectory() as tmp:
            spec_file = os.path.join(tmp, "slice.json")
            with open(spec_file, "w", encoding="utf-8") as f:
                json.dump(spec, f)
            out = os.path.join(tmp, "slice.csv")
            done = subprocess.run([RRLAB, "sweep", spec_file, "--db", os.path.join(tmp, "slice.db"), "--jobs", "2",
                                   "--out", out], capture_output=True, text=True, timeout=360)
            self.assertEqual(done.returncode, 0, done.stderr)
            now = deterministic_rows(out)
        committed = deterministic_rows(os.path.join(SOURCE_DIR, "benchmarks", "default-runs.csv"))
        expected_runs = CASES_PER_FAMILY * len(spec["scenarios"]) * len(spec["methods"])
        self.assertEqual(len(now), expected_runs)
        for key, row in now.items():
            self.assertIn(key, committed, f"{key} is not in benchmarks/default-runs.csv")
            for column, value in row.items():
                self.assertEqual(committed[key][column], value,
                                 f"{key} {column}: the committed benchmark no longer matches the code; "
                                 "re-run it (docs/results.md, Benchmark)")


if __name__ == "__main__":
    unittest.main(verbosity=2)
