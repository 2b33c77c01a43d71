"""Methods written in Python (python/src/python_method.cpp): they run like a
built-in method, see the state the built-in methods see, and fail with a
MethodError that names the step."""
import numpy as np
import pytest

import rrlab
from conftest import scenario_path


class PythonPinv(rrlab.Method):
    name = "python_pinv"

    def step(self, s):
        return np.linalg.pinv(s.J) @ s.xdot


@pytest.mark.parametrize("name", ["01_planar7_obstacles.json", "02_spatial_xz_reach.json", "03_dh7_pose.json"])
def test_a_python_pinv_ends_where_the_builtin_pinv_ends(name):
    mine = rrlab.run(scenario_path(name), method=PythonPinv())
    builtin = rrlab.run(scenario_path(name), method="pinv")
    assert mine["method"] == "python_pinv" and mine["steps"] == builtin["steps"]
    np.testing.assert_allclose(mine["final_q"], builtin["final_q"], rtol=0, atol=1e-9)
    np.testing.assert_allclose(mine["frames"]["q"], builtin["frames"]["q"], rtol=0, atol=1e-9)


class Recorder(rrlab.Method):
    """Keeps copies of what it was shown, and holds still."""
    name = "recorder"
    params = [rrlab.Param("gain", default=1.0, min=0.0, max=10.0)]

    def start(self, context):
        self.context = context
        self.seen = []

    def step(self, s):
        self.seen.append(dict(t=s.t, q=s.q, J=s.J, xdot=s.xdot, error=s.error, distances=s.distances,
                              jac=s.distance_jacobians, normals=s.normals, lower=s.q_lower, speed=s.qdot_max,
                              gain=self.param("gain"), dt=s.dt))
        return np.zeros(len(s.q))


def test_the_state_is_what_the_builtin_methods_see():
    method = Recorder()
    res = rrlab.run(scenario_path("01_planar7_obstacles.json"), method=method, params={"gain": 2.5}, steps=3)
    assert method.context == {"dof": 7, "task_rows": 2, "obstacles": method.context["obstacles"], "seed": 1}
    first = method.seen[0]
    assert first["gain"] == 2.5 and first["dt"] == 0.01 and first["t"] == 0.0
    assert first["J"].shape == (2, 7) and first["xdot"].shape == (2,) and first["q"].shape == (7,)
    assert first["jac"].shape == (7, 3, 7) and first["normals"].shape == (7, 3)
    np.testing.assert_array_equal(first["q"], res["frames"]["q"][0])
    # the nearest distance of the frame is the smallest of the links' distances
    assert abs(first["distances"].min() - res["frames"]["min_distance"][0]) < 1e-12


def test_the_distance_jacobians_predict_how_the_distances_change():
    seen = []
    delta = 1e-6 * np.arange(1, 8)

    class Jump(rrlab.Method):
        """Moves by `delta` in the first step, then holds."""

        def step(self, s):
            seen.append((s.distances, s.normals, s.distance_jacobians))
            return delta / s.dt if s.step == 0 else np.zeros(len(s.q))

    rrlab.run(scenario_path("01_planar7_obstacles.json"), method=Jump(), steps=2)
    (before, normals, jacobians), (after, _, _) = seen
    for link in range(len(before)):  # first order: the error is |delta|^2
        predicted = before[link] + normals[link] @ jacobians[link] @ delta
        assert abs(after[link] - predicted) < 1e-9, link


def test_python_parameters_are_validated():
    with pytest.raises(rrlab.ParamError, match="gain"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method=Recorder(), params={"gain": 20.0}, steps=1)
    with pytest.raises(rrlab.ParamError, match="nope"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method=Recorder(), params={"nope": 1.0}, steps=1)
    sim = rrlab.Simulator(scenario_path("01_planar7_obstacles.json"), method=Recorder())
    sim.set_param("gain", 3.0)
    assert sim.params == {"gain": 3.0}


class Failing(rrlab.Method):
    def __init__(self, how):
        self.how = how

    def step(self, s):
        if s.step < 4:
            return np.zeros(len(s.q))
        if self.how == "nan":
            return np.full(len(s.q), np.nan)
        if self.how == "shape":
            return np.zeros(len(s.q) + 1)
        if self.how == "type":
            return "fast"
        raise ZeroDivisionError("my bug")


@pytest.mark.parametrize("how, message", [
    ("nan", "returned NaN for joint 1"),
    ("shape", r"returned shape \(8,\), expected \(7,\)"),
    ("type", "returned str, not an array of 7 joint velocities"),
    ("raise", "ZeroDivisionError: my bug"),
])
def test_a_failing_method_gets_an_error_naming_the_step(how, message):
    with pytest.raises(rrlab.MethodError, match=message) as error:
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method=Failing(how))
    assert str(error.value).startswith("Failing at step 4 (t = 0.04 s)")


def test_a_builtin_name_is_refused_and_the_state_does_not_outlive_its_step():
    class Impostor(rrlab.Method):
        name = "pinv"

        def step(self, s):
            return np.zeros(len(s.q))

    with pytest.raises(ValueError, match="built-in"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method=Impostor())

    class Keeper(rrlab.Method):
        def step(self, s):
            self.kept = s
            return np.zeros(len(s.q))

    keeper = Keeper()
    rrlab.run(scenario_path("01_planar7_obstacles.json"), method=keeper, steps=1)
    with pytest.raises(RuntimeError, match="step that has ended"):
        keeper.kept.q


def test_a_state_kept_from_an_earlier_step_raises_instead_of_showing_the_current_one():
    class Keeper(rrlab.Method):
        def step(self, s):
            if s.step == 0:
                self.first = s
            else:
                with pytest.raises(RuntimeError, match="step that has ended"):
                    self.first.q
                self.checked = True
            return np.zeros(len(s.q))

    keeper = Keeper()
    rrlab.run(scenario_path("01_planar7_obstacles.json"), method=keeper, steps=2)
    assert keeper.checked


def test_start_sees_the_runs_parameters_and_simulators_of_one_object_keep_theirs():
    class Gains(rrlab.Method):
        params = [rrlab.Param("k", default=1.0, min=0.0, max=10.0)]

        def start(self, context):
            self.started_with = self.param("k")

        def step(self, s):
            self.seen = self.param("k")
            return np.zeros(len(s.q))

    method = Gains()
    rrlab.run(scenario_path("01_planar7_obstacles.json"), method=method, params={"k": 5}, steps=1)
    assert method.started_with == 5.0
    a = rrlab.Simulator(scenario_path("01_planar7_obstacles.json"), method=method, params={"k": 2})
    b = rrlab.Simulator(scenario_path("01_planar7_obstacles.json"), method=method, params={"k": np.int64(7)})
    a.step()
    assert method.seen == 2.0
    b.step()
    assert method.seen == 7.0
    a.step()
    assert method.seen == 2.0 and a.params == {"k": 2.0}


def test_live_inputs_reach_a_python_method_and_a_switch_comes_back_to_it():
    class Scaled(rrlab.Method):
        name = "scaled_zero"
        params = [rrlab.Param("k", default=1.0, min=0.0, max=10.0)]

        def step(self, s):
            return np.zeros(len(s.q))

    sim = rrlab.Simulator(scenario_path("01_planar7_obstacles.json"), method=Scaled())
    sim.apply("params", {"k": 3.0})
    assert sim.params == {"k": 3.0}
    sim.apply("method", {"name": "dls", "params": {"lambda": 0.1}})
    sim.step()
    assert sim.method == "dls"
    sim.apply("method", {"name": "scaled_zero", "params": {"k": 4.0}})
    sim.step()
    assert sim.method == "scaled_zero" and sim.params == {"k": 4.0}
    with pytest.raises(rrlab.ParamError, match="k"):
        sim.apply("params", {"k": 11.0})


def test_an_object_named_like_a_registered_method_keeps_its_own_parameters():
    class First(rrlab.Method):
        name = "same_name"
        params = [rrlab.Param("a", default=1.0, min=0.0, max=2.0)]

        def step(self, s):
            return np.zeros(len(s.q))

    class Second(First):
        params = [rrlab.Param("b", default=1.0, min=0.0, max=2.0)]

    rrlab.register_method(First())
    res = rrlab.run(scenario_path("01_planar7_obstacles.json"), method=Second(), params={"b": 0.5}, steps=1)
    assert res["method"] == "same_name"


@pytest.mark.parametrize("make, error, message", [
    (lambda: type("P", (rrlab.Method,), {"params": [rrlab.Param("k", default="x")],
                                          "step": lambda self, s: np.zeros(7)})(), ValueError, "params.k.default"),
    (lambda: type("N", (rrlab.Method,), {"name": 5, "step": lambda self, s: np.zeros(7)})(), ValueError,
     "must be a string"),
    (lambda: type("L", (rrlab.Method,), {"params": {"k": 1}, "step": lambda self, s: np.zeros(7)})(), ValueError,
     "list of rrlab.Param"),
    (lambda: PythonPinv, ValueError, r"PythonPinv\(\), not the class"),
])
def test_a_badly_made_method_is_refused_with_what_is_wrong(make, error, message):
    with pytest.raises(error, match=message):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method=make(), steps=1)


@pytest.mark.parametrize("steps", [1.5, 10**30, True, "10"])
def test_steps_must_be_a_whole_number_in_range(steps):
    with pytest.raises(rrlab.ScenarioError, match="whole number"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), steps=steps)


def test_ctrl_c_in_a_python_methods_step_stays_a_keyboard_interrupt():
    class Interrupted(rrlab.Method):
        def step(self, s):
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), method=Interrupted())
