"""The package is typed: `mypy --strict` passes over python/rrlab (the
pure-Python modules and the engine module's stubs, _rrlab.pyi), and code
that uses rrlab is checked against those types: a well-typed user of the
engine, the methods and the client passes, calls with a wrong argument name
or type fail. mypy is Debian's python3-mypy (scripts/install-deps); its
absence fails the test."""
import os
import subprocess
import sys
import textwrap

import pytest

from conftest import SOURCE_DIR

PACKAGE_DIR = os.path.join(SOURCE_DIR, "python")


@pytest.fixture(scope="module")
def mypy(tmp_path_factory):
    cache = tmp_path_factory.mktemp("mypy-cache")

    def run(*args, cwd=PACKAGE_DIR):
        # python/pyproject.toml's [tool.mypy] (strict), read from python/
        done = subprocess.run([sys.executable, "-m", "mypy", "--config-file", os.path.join(PACKAGE_DIR, "pyproject.toml"),
                               "--cache-dir", str(cache), "--no-error-summary", "--hide-error-context", *args],
                              cwd=cwd, capture_output=True, text=True, timeout=300,
                              env=dict(os.environ, MYPYPATH=PACKAGE_DIR))
        assert "No module named mypy" not in done.stderr, \
            "mypy is missing: scripts/install-deps installs Debian's python3-mypy"
        return done

    return run


def test_mypy_strict_passes_over_the_package_and_its_stubs(mypy):
    done = mypy("--strict", "-p", "rrlab")
    assert done.returncode == 0, done.stdout + done.stderr


USER = '''
    from typing import Any

    import numpy as np
    import numpy.typing as npt

    import rrlab
    from rrlab.client import Client


    class Damped(rrlab.Method):
        name = "damped"
        params = [rrlab.Param("lam", default=0.05, min=0.0, max=1.0)]

        def step(self, s: rrlab.StepState) -> npt.NDArray[np.float64]:
            J = s.J
            out: npt.NDArray[np.float64] = J.T @ np.linalg.solve(J @ J.T + self.param("lam") ** 2 * np.eye(len(J)),
                                                                   s.xdot)
            return out


    def use_engine() -> float:
        sc: rrlab.Scenario = rrlab.load_scenario("scenarios/01_planar7_obstacles.json")
        res: dict[str, Any] = rrlab.run(sc, method=Damped(), params={"lam": 0.1}, steps=sc.steps)
        sim = rrlab.Simulator(sc, method="dls")
        sim.step(10)
        sim.set_param("lambda", 0.02)
        sim.move_obstacle("box", position=[1.2, 0.4])
        q: npt.NDArray[np.float64] = sim.state["q"]
        cases = rrlab.generate("planar_limits", seed=1, count=2)
        out = rrlab.sweep({"name": "x", "scenarios": cases}, methods=[Damped(), "dls"], jobs=1)
        try:
            rrlab.replay("runs.db", 1)
        except rrlab.Error as e:
            print(e)
        return float(res["min_distance"]) + float(q[0]) + len(out["runs"]) + sc.dt


    def use_client() -> None:
        c = Client("http://127.0.0.1:8080", token=None, timeout=10.0)
        try:
            run = c.run("01_planar7_obstacles", "dls", {"lambda": 0.02})
            frames = c.frames(run["id"], stride=2)
            print(frames["q"])
        except rrlab.ApiError as e:
            print(e.status, e.code, e.path)
'''

WRONG = '''
    import rrlab
    from rrlab.client import Client

    sc = rrlab.load_scenario("scenarios/01_planar7_obstacles.json")
    rrlab.run(sc, stepz=10)
    sim = rrlab.Simulator(sc)
    sim.step("ten")
    sim.joystick(linear_velocity=[0.1, 0.0])
    sc.dof = 3
    Client(url=8080)
    rrlab.Error("x").status
'''


def test_code_that_uses_rrlab_is_checked_against_its_types(mypy, tmp_path):
    (tmp_path / "user.py").write_text(textwrap.dedent(USER))
    done = mypy("--strict", "user.py", cwd=tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr

    (tmp_path / "wrong.py").write_text(textwrap.dedent(WRONG))
    done = mypy("--strict", "wrong.py", cwd=tmp_path)
    lines = [line for line in done.stdout.splitlines() if ": error:" in line]
    wrong = {int(line.split(":")[1]) for line in lines}
    assert wrong == {6, 8, 9, 10, 11, 12}, done.stdout  # one error per wrong line, each of them found
