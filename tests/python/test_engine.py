"""rrlab's engine from Python (python/src/module.cpp): loading scenarios, runs
with built-in methods, frames as numpy arrays equal to `rrlab run`'s CSV, the
Simulator and its live inputs."""
import json
import math
import subprocess

import numpy as np
import pytest

import rrlab
from conftest import RRLAB, scenario_path


def test_version_is_the_binarys():
    done = subprocess.run([RRLAB, "--version"], capture_output=True, text=True, check=True)
    assert done.stdout.split()[1] == rrlab.__version__


def test_methods_are_the_command_lines():
    done = subprocess.run([RRLAB, "methods"], capture_output=True, text=True, check=True)
    assert rrlab.methods() == json.loads(done.stdout)


def test_a_scenario_loads_from_a_path_a_dict_and_a_json_string():
    path = scenario_path("01_planar7_obstacles.json")
    with open(path, encoding="utf-8") as f:
        doc = json.load(f)
    for source in (path, doc, json.dumps(doc)):
        sc = rrlab.load_scenario(source)
        assert (sc.name, sc.dof, sc.task_space, sc.steps) == ("planar7_obstacles", 7, "xy", 800)


@pytest.mark.parametrize("change, path", [
    (lambda d: d["robot"]["links"][2].update(length=-1.0), "robot.links[2].length"),
    (lambda d: d.update(dt="fast"), "dt"),
    (lambda d: d["method"].update(name="no_such_method"), "method.name"),
])
def test_scenario_errors_name_the_json_path(change, path):
    with open(scenario_path("01_planar7_obstacles.json"), encoding="utf-8") as f:
        doc = json.load(f)
    change(doc)
    with pytest.raises(rrlab.ScenarioError) as error:
        rrlab.load_scenario(doc)
    assert error.value.path == path, str(error.value)
    assert path in str(error.value)


def test_a_missing_file_and_broken_json_raise_scenario_errors():
    with pytest.raises(rrlab.ScenarioError, match="no_such_file.json"):
        rrlab.load_scenario("no_such_file.json")
    with pytest.raises(rrlab.ScenarioError):
        rrlab.load_scenario('{"name": ')


def csv_value(text):
    return math.nan if text == "" else float(text)


@pytest.mark.parametrize("name", ["01_planar7_obstacles.json", "03_dh7_pose.json", "40_urdf_iiwa14_pose.json"])
def test_frames_equal_the_command_lines_csv_bit_for_bit(cli_run, name):
    summary, header, rows = cli_run(scenario_path(name))
    res = rrlab.run(scenario_path(name))
    frames = res["frames"]
    assert len(rows) == res["steps"] == summary["steps"] == len(frames["t"])
    columns = {}  # CSV column name -> (array, column index within it)
    for key, array in frames.items():
        if key == "diagnostics":
            for diag, values in array.items():
                columns[diag] = (values, None)
        elif array.ndim == 1:
            columns[key] = (array, None)
        else:
            suffixes = {3: ["_x", "_y", "_z"], 4: ["_w", "_x", "_y", "_z"]}.get(array.shape[1]) \
                if key in ("ee", "target", "ee_quat") else [str(i + 1) for i in range(array.shape[1])]
            for i, suffix in enumerate(suffixes):
                columns[key + suffix] = (array, i)
    assert set(columns) == set(header)
    for c, name_of_column in enumerate(header):
        if name_of_column == "step_us":
            continue  # wall clock
        array, index = columns[name_of_column]
        values = array if index is None else array[:, index]
        expected = np.array([csv_value(row[c]) for row in rows])
        got = values.astype(float)
        finite = np.isfinite(got)
        assert np.array_equal(finite, np.isfinite(expected)), name_of_column
        assert np.array_equal(got[finite], expected[finite]), name_of_column
    for key in ("min_distance", "max_tracking_error", "final_tracking_error", "final_q", "collided"):
        assert res[key] == summary[key], key


def test_arrays_have_the_documented_shapes_and_types():
    res = rrlab.run(scenario_path("01_planar7_obstacles.json"), method="dls", params={"lambda": 0.05}, steps=50)
    f = res["frames"]
    assert res["method"] == "dls" and res["steps"] == 50
    assert f["q"].shape == (50, 7) and f["q"].dtype == np.float64
    assert f["qdot"].shape == (50, 7)
    assert f["ee"].shape == (50, 3) and f["ee_quat"].shape == (50, 4)
    assert f["t"].shape == (50,) and f["step"].dtype == np.int64
    assert f["collided"].dtype == np.bool_ and f["min_distance_link"].dtype == np.int64
    assert list(f["diagnostics"]) == ["lambda"] or "lambda" in f["diagnostics"]
    np.testing.assert_array_equal(f["step"], np.arange(50))


def test_parameters_are_validated_by_name_and_range():
    with pytest.raises(rrlab.ScenarioError, match="lambda"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method="dls", params={"lambda": -1.0}, steps=2)
    with pytest.raises(rrlab.ScenarioError, match="no_such_param"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method="dls", params={"no_such_param": 1}, steps=2)
    with pytest.raises(rrlab.ScenarioError, match="method"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method="no_such_method", steps=2)
    with pytest.raises(rrlab.ScenarioError, match="steps"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), steps=0)


def test_the_simulator_steps_and_takes_live_inputs():
    sim = rrlab.Simulator(scenario_path("01_planar7_obstacles.json"), method="dls")
    sim.step(10)
    assert sim.state["step"] == 10 and abs(sim.state["t"] - 0.1) < 1e-12
    assert sim.frame["step"] == 9 and sim.frame["q"].shape == (7,)
    sim.set_param("lambda", 0.2)
    assert sim.params["lambda"] == 0.2
    with pytest.raises(rrlab.ScenarioError, match="lambda"):
        sim.set_param("lambda", -1.0)
    obstacle = json.load(open(scenario_path("01_planar7_obstacles.json"), encoding="utf-8"))["obstacles"][0]["id"]
    sim.move_obstacle(obstacle, position=np.array([3.0, 3.0]))
    with pytest.raises(rrlab.ScenarioError):
        sim.move_obstacle("no_such_obstacle", position=[0.0, 0.0])
    with pytest.raises(rrlab.InputStateError):
        sim.joystick([0.1, 0.0])  # not a joystick task
    sim.step(10**6)
    assert sim.done and sim.summary()["steps"] == 800
    sim.reset()
    assert sim.state["step"] == 0 and not sim.done


def test_a_joystick_run_follows_the_command():
    sim = rrlab.Simulator(scenario_path("04_planar7_joystick.json"), method="dls")
    sim.step()
    start = sim.frame["ee"].copy()
    sim.joystick([0.1, 0.0])
    sim.step(50)
    assert sim.frame["ee"][0] > start[0] + 0.02


def test_a_simulator_in_use_refuses_other_calls_instead_of_racing():
    holder = {}

    class Peeker(rrlab.Method):
        def step(self, s):
            holder["sim"].state  # the simulator is stepping: refused, not read half-way
            return np.zeros(len(s.q))

    holder["sim"] = rrlab.Simulator(scenario_path("01_planar7_obstacles.json"), method=Peeker())
    with pytest.raises(rrlab.MethodError, match="busy stepping"):
        holder["sim"].step()
    assert holder["sim"].state["step"] == 0  # usable again afterwards
