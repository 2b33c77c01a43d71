"""Sweeps and generated cases from Python (python/src/sweeps.cpp,
python/rrlab/_sweep.py): Python and built-in methods in one sweep, the
report and per-run table the command line gives, stored runs that replay."""
import json
import os
import subprocess

import numpy as np
import pytest

import rrlab
from conftest import RRLAB


class NumpyDls(rrlab.Method):
    """Damped least squares with numpy."""
    name = "numpy_dls"
    params = [rrlab.Param("damping", default=0.05, min=0.0, max=1.0)]

    def step(self, s):
        j = s.J
        return j.T @ np.linalg.solve(j @ j.T + self.param("damping") ** 2 * np.eye(len(j)), s.xdot)


SPEC = {"name": "mixed", "scenarios": [{"generator": "planar_clutter", "count": 3, "seed": 7}],
        "success": {"max_tracking_error": 0.01}}


def test_generated_cases_are_the_command_lines(tmp_path):
    cases = rrlab.generate("planar_clutter", seed=7, count=2, options={"obstacles": 3})
    subprocess.run([RRLAB, "generate", "planar_clutter", "--seed", "7", "--count", "2", "--option", "obstacles=3",
                    "--out", str(tmp_path)], check=True, capture_output=True)
    for case in cases:
        with open(tmp_path / (case["name"] + ".json"), encoding="utf-8") as f:
            assert json.load(f) == case
        assert "witness" in case
    with pytest.raises(rrlab.ScenarioError, match="generator"):
        rrlab.generate("no_such_family")


def test_a_sweep_mixes_python_and_builtin_methods(tmp_path):
    db = tmp_path / "mixed.db"
    out = rrlab.sweep(SPEC, methods=[NumpyDls(), "dls", {"name": NumpyDls(), "params": {"damping": [0.25, 0.5]}}],
                      jobs=2, db=db)
    assert out["failures"] == [] and out["runs_total"] == out["stored"] == 12
    configs = sorted({run["config"] for run in out["runs"]})
    assert configs == ["dls", "numpy_dls", "numpy_dls{damping=0.25}", "numpy_dls{damping=0.5}"]
    by_key = {run["key"]: run for run in out["runs"]}
    # numpy's damped least squares with the built-in's damping lands where the built-in does
    for case in range(3):
        mine = by_key[f"mixed/gen:planar_clutter:7:{case}/numpy_dls/own"]
        builtin = by_key[f"mixed/gen:planar_clutter:7:{case}/dls/own"]
        assert mine["success"] == builtin["success"] and mine["failure_mode"] == builtin["failure_mode"]
        assert abs(mine["min_distance"] - builtin["min_distance"]) < 1e-9
    assert {g["config"] for g in out["report"]["groups"]} == set(configs)
    # the command line reads the same database: its per-run table is the same
    table = tmp_path / "runs.csv"
    spec_file = tmp_path / "spec.json"
    spec_file.write_text(json.dumps(dict(SPEC, methods=["dls"])))
    again = rrlab.sweep(spec_file, jobs=1, db=db)  # resumes: nothing to run
    assert again["stored"] == 0 and again["already_stored"] == 3
    done = subprocess.run([RRLAB, "report", str(db), "--sweep", "mixed", "--format", "csv", "--out", str(table)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def test_a_stored_python_run_replays_only_with_its_method_registered(tmp_path):
    db = tmp_path / "stored.db"
    out = rrlab.sweep(dict(SPEC, scenarios=[{"generator": "planar_clutter", "count": 1, "seed": 7}]),
                      methods=[NumpyDls()], jobs=1, db=db, frames=True)
    run = out["runs"][0]["run"]
    assert rrlab.replay(db, run)["identical"] is True  # registered in this process by the sweep
    done = subprocess.run([RRLAB, "replay", str(run), "--db", str(db)], capture_output=True, text=True)
    assert done.returncode == 2
    assert '"numpy_dls" is a method written in Python' in done.stderr


def test_a_failing_python_method_fails_its_runs_not_the_sweep():
    class Broken(rrlab.Method):
        name = "broken"

        def step(self, s):
            raise RuntimeError("not yet")

    out = rrlab.sweep(SPEC, methods=[Broken(), "pinv"], jobs=2)
    assert out["stored"] == 3 and len(out["failures"]) == 3
    assert all("broken at step 0" in failure and "not yet" in failure for failure in out["failures"])


def test_registered_names_and_bad_specs():
    assert rrlab.register_method(NumpyDls()) == "numpy_dls"
    scenario = rrlab.generate("planar_clutter", seed=7)[0]
    scenario["method"] = {"name": "numpy_dls", "params": {"damping": 0.2}}
    assert rrlab.run(scenario, steps=5)["method"] == "numpy_dls"  # found by name once registered
    with pytest.raises(rrlab.ScenarioError, match="methods"):
        rrlab.sweep(dict(SPEC, name="bad"), methods=["no_such_method"])
    with pytest.raises(rrlab.ScenarioError, match="jobs"):
        rrlab.sweep(SPEC, methods=["pinv"], jobs=0)
    assert os.path.basename(rrlab.__file__) == "__init__.py"


def test_ctrl_c_stops_a_sweep_and_a_second_call_resumes(tmp_path):
    import signal
    import threading

    handled = threading.Event()

    def on_sigint(signum, frame):
        handled.set()
        raise KeyboardInterrupt

    class Interrupting(rrlab.Method):
        """Presses Ctrl-C at its first step, then waits until Python has handled it."""
        name = "interrupting"

        def step(self, s):
            if s.step == 0 and not handled.is_set():
                signal.raise_signal(signal.SIGINT)
                assert handled.wait(timeout=120)
            return np.zeros(len(s.q))

    previous = signal.signal(signal.SIGINT, on_sigint)
    db = tmp_path / "stopped.db"
    try:
        with pytest.raises(KeyboardInterrupt):
            rrlab.sweep(SPEC, methods=[Interrupting()], jobs=1, db=db)
    finally:
        signal.signal(signal.SIGINT, previous)
    resumed = rrlab.sweep(SPEC, methods=[Interrupting()], jobs=1, db=db)
    assert resumed["already_stored"] + resumed["stored"] == 3 and resumed["stored"] >= 1
