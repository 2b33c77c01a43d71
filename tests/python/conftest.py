"""Shared fixtures of the Python package's tests (ctest PythonPackage.*): the
package comes from PYTHONPATH (the build's python/ directory), the rrlab
binary and the source tree from RRLAB_BINARY and RRLAB_SOURCE_DIR."""
import csv
import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("RRLAB_SOURCE_DIR",
                            os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
RRLAB = os.environ.get("RRLAB_BINARY", os.path.join(SOURCE_DIR, "build", "cli", "rrlab"))


def scenario_path(name):
    return os.path.join(SOURCE_DIR, "scenarios", name)


@pytest.fixture
def cli_run(tmp_path):
    """`rrlab run FILE --out CSV [ARGS]`: its summary (JSON) and its CSV rows (header, rows of strings)."""
    import json

    def run(file, *args):
        out = tmp_path / "frames.csv"
        done = subprocess.run([RRLAB, "run", file, "--out", str(out), *args], capture_output=True, text=True,
                              timeout=300)
        assert done.returncode == 0, done.stderr
        with open(out, newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
        return json.loads(done.stdout), rows[0], rows[1:]

    return run

# client_test.py is a script of its own (ctest Python.rrlab_client, against the
# sanitized server, without the engine module): not collected here
collect_ignore = ["client_test.py"]
