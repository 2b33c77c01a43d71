"""The package's examples run as their docstrings say (python/examples/):
my_method.py on two cases per family, its plot written."""
import os
import subprocess
import sys

import rrlab
from conftest import SOURCE_DIR


def test_my_method_runs_benchmarks_and_plots(tmp_path):
    png = tmp_path / "my_method.png"
    package_dir = os.path.dirname(os.path.dirname(os.path.abspath(rrlab.__file__)))  # this package, from elsewhere
    done = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "python", "examples", "my_method.py"),
                           "--cases", "2", "--out", str(png)], capture_output=True, text=True, timeout=300,
                          cwd=tmp_path, env=dict(os.environ, PYTHONPATH=package_dir))
    assert done.returncode == 0, done.stderr
    assert "centring_dls" in done.stdout and "sweep: 16 runs, 0 failed" in done.stdout
    assert png.stat().st_size > 10_000
    assert "Warning" not in done.stderr, done.stderr
