"""One hierarchy: every exception rrlab raises is an rrlab.Error (rrlab.errors),
the engine's translated ones included, and each is still the built-in
exception it was (ValueError, RuntimeError)."""
import inspect

import numpy as np
import pytest

import rrlab
import rrlab.client
from conftest import scenario_path

SCENARIO = scenario_path("01_planar7_obstacles.json")


def test_every_exception_class_of_rrlab_derives_from_rrlab_error():
    classes = [value for _, value in inspect.getmembers(rrlab.errors, inspect.isclass)
               if issubclass(value, BaseException) and value.__module__ == "rrlab.errors"]
    assert len(classes) >= 9
    for cls in classes:
        assert issubclass(cls, rrlab.Error), cls
        assert getattr(rrlab, cls.__name__) is cls  # all exported by rrlab
    assert rrlab.client.RrlabError is rrlab.ApiError  # the client's error, under its earlier name too
    assert issubclass(rrlab.Timeout, TimeoutError)


class Stale(rrlab.Method):
    def step(self, s):
        self.kept = s
        return np.zeros(len(s.q))


class Raises(rrlab.Method):
    def step(self, s):
        raise ZeroDivisionError("boom")


def _stale_state():
    method = Stale()
    rrlab.run(SCENARIO, method=method, steps=1)
    return method.kept.q


@pytest.mark.parametrize("call, error, builtin", [
    (lambda: rrlab.load_scenario({"robot": {}}), rrlab.ScenarioError, ValueError),
    (lambda: rrlab.run(SCENARIO, method="dls", params={"lambda": -1.0}), rrlab.ScenarioError, ValueError),
    (lambda: rrlab.run(SCENARIO, method=Stale(), params={"nope": 1.0}), rrlab.ParamError, ValueError),
    (lambda: rrlab.run(SCENARIO, method=Stale), rrlab.ArgumentError, ValueError),
    (lambda: rrlab.run(SCENARIO, method=Raises(), steps=2), rrlab.MethodError, RuntimeError),
    (lambda: rrlab.Simulator(SCENARIO).joystick([0.1, 0.0]), rrlab.InputStateError, RuntimeError),
    (_stale_state, rrlab.EngineError, RuntimeError),
    (lambda: rrlab.client.Client("localhost"), rrlab.ArgumentError, ValueError),
])
def test_except_rrlab_error_catches_what_rrlab_raises(call, error, builtin):
    with pytest.raises(rrlab.Error) as caught:
        call()
    assert type(caught.value) is error, caught.value
    assert isinstance(caught.value, builtin)
