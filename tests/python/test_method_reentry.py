"""A Python method whose own code runs or steps a simulation
(python/src/method_reentry.hpp): refused with rrlab.MethodError naming the
re-entry, and the interpreter goes on. Re-entering rrlab.run from a step used
to nest one run in another until the C++ stack overflowed (SIGSEGV at about
450 levels)."""
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import rrlab
from conftest import scenario_path

SCENARIO = scenario_path("01_planar7_obstacles.json")


class Reentrant(rrlab.Method):
    """Runs its own scenario again from its step: a recursion without end, were it let in."""

    def step(self, s):
        rrlab.run(SCENARIO, method=self, steps=1)
        return np.zeros(len(s.q))


def test_recursion_through_rrlab_run_is_refused_and_the_interpreter_survives():
    # in a child interpreter with Python's recursion limit far above the old
    # crash: a crash shows as a signal there instead of ending this session
    script = textwrap.dedent(f"""
        import sys
        import numpy as np
        import rrlab
        sys.setrecursionlimit(100000)

        class Reentrant(rrlab.Method):
            def step(self, s):
                rrlab.run({SCENARIO!r}, method=self, steps=1)
                return np.zeros(len(s.q))

        try:
            rrlab.run({SCENARIO!r}, method=Reentrant(), steps=1)
        except rrlab.MethodError as e:
            print(e)
        print("after:", rrlab.run({SCENARIO!r}, method="pinv", steps=2)["steps"])
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300,
                          env=dict(os.environ))
    assert done.returncode == 0, f"exit {done.returncode}: {done.stderr}"
    assert done.stdout.startswith("Reentrant at step 0 (t = 0 s): MethodError: rrlab.run re-entered from the "
                                  "Python method Reentrant"), done.stdout
    assert "re-entry is refused" in done.stdout
    assert done.stdout.rstrip().endswith("after: 2")


def test_rrlab_run_from_a_step_raises_a_method_error_and_the_engine_goes_on():
    with pytest.raises(rrlab.MethodError, match=r"rrlab\.run re-entered from the Python method Reentrant") as error:
        rrlab.run(SCENARIO, method=Reentrant(), steps=3)
    assert str(error.value).startswith("Reentrant at step 0")
    assert rrlab.run(SCENARIO, method="pinv", steps=3)["steps"] == 3


def test_every_entry_point_that_steps_is_refused_from_a_methods_code(tmp_path):
    other = rrlab.Simulator(SCENARIO, method="pinv")
    calls = {
        "Simulator.step": lambda: other.step(),
        "rrlab.run": lambda: rrlab.run(SCENARIO, method="pinv", steps=1),
        "rrlab.sweep": lambda: rrlab.sweep({"name": "inner", "scenarios": [SCENARIO]}, methods=["pinv"], jobs=1),
        "rrlab.replay": lambda: rrlab.replay(tmp_path / "none.db", 1),
    }
    for call, make in calls.items():
        for where in ("start", "step"):
            class Caller(rrlab.Method):
                def start(self, context):
                    if where == "start":
                        make()

                def step(self, s):
                    make()
                    return np.zeros(len(s.q))

            with pytest.raises(rrlab.MethodError, match=rf"{call} re-entered from the Python method Caller"):
                rrlab.run(SCENARIO, method=Caller(), steps=1)
    assert other.state["step"] == 0  # never stepped from inside


def test_a_method_that_catches_the_refusal_runs_to_its_end():
    class Tries(rrlab.Method):
        refusals = 0

        def step(self, s):
            try:
                rrlab.run(SCENARIO, method="pinv", steps=1)
            except rrlab.MethodError:
                self.refusals += 1
            return np.zeros(len(s.q))

    method = Tries()
    assert rrlab.run(SCENARIO, method=method, steps=5)["steps"] == 5
    assert method.refusals == 5


def test_in_a_sweep_the_reentrant_method_fails_its_runs_not_the_sweep():
    spec = {"name": "reentrant", "scenarios": [{"generator": "planar_clutter", "count": 2, "seed": 7}],
            "success": {"max_tracking_error": 0.01}}
    out = rrlab.sweep(spec, methods=[Reentrant(), "pinv"], jobs=2)
    assert out["stored"] == 2 and len(out["failures"]) == 2  # the pinv runs; the failed ones are not stored
    assert all("rrlab.run re-entered from the Python method Reentrant" in failure for failure in out["failures"])
