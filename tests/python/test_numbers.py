"""Integer arguments of the Python API (python/src/whole_number.hpp): a
negative, huge or not whole value raises rrlab.ScenarioError (a ValueError)
naming the argument and its range, never pybind11's TypeError, as the
command line's options refuse them (tests/cli/integer_options_test.cpp)."""
import re

import numpy as np
import pytest

import rrlab
from conftest import scenario_path

SEEDS = "[0, 9223372036854775807]"


def refused(name, allowed):
    """pytest.raises for a ScenarioError at `name` saying the range `allowed`."""
    message = f"{name}: must be a whole number in {allowed}, got"
    return pytest.raises(rrlab.ScenarioError, match="^" + re.escape(message))


@pytest.mark.parametrize("arguments, name, allowed", [
    ({"seed": -1}, "seed", SEEDS),
    ({"seed": 2**63}, "seed", SEEDS),
    ({"seed": 2**64 - 1}, "seed", SEEDS),
    ({"seed": 1.0}, "seed", SEEDS),
    ({"seed": "1"}, "seed", SEEDS),
    ({"seed": True}, "seed", SEEDS),
    ({"count": -1}, "count", "[1, 100000]"),
    ({"count": 0}, "count", "[1, 100000]"),
    ({"count": 10**30}, "count", "[1, 100000]"),
    ({"first": -1}, "first", "[0, 1000000000]"),
    ({"first": 2**31}, "first", "[0, 1000000000]"),
    ({"first": None}, "first", "[0, 1000000000]"),
])
def test_generate_refuses_out_of_range_numbers_with_a_value_error(arguments, name, allowed):
    with refused(name, allowed) as error:
        rrlab.generate("planar_clutter", **arguments)
    assert isinstance(error.value, ValueError) and error.value.path == name


def test_generate_takes_numpy_integers_and_the_largest_seed():
    assert rrlab.generate("planar_clutter", seed=np.int64(7), count=np.uint8(1)) == rrlab.generate("planar_clutter",
                                                                                                   seed=7)
    assert rrlab.generate("planar_clutter", seed=2**63 - 1, first=10)[0]["name"] == "planar_clutter-10"


@pytest.mark.parametrize("count", [-1, 2**64, 1.5, "2"])
def test_simulator_step_refuses_counts_out_of_range(count):
    sim = rrlab.Simulator(scenario_path("01_planar7_obstacles.json"), method="pinv")
    with refused("count", "[0, 9223372036854775807]"):
        sim.step(count)
    sim.step(np.int32(2))
    assert sim.state["step"] == 2


@pytest.mark.parametrize("run", [-1, 0, 2**63, 2.0])
def test_replay_refuses_run_ids_out_of_range(tmp_path, run):
    with refused("run", "[1, 9223372036854775807]"):
        rrlab.replay(tmp_path / "none.db", run)


@pytest.mark.parametrize("jobs", [-1, 0, 2**70, 1.5])
def test_sweep_refuses_jobs_out_of_range(jobs):
    spec = {"name": "numbers", "scenarios": [{"generator": "planar_clutter", "count": 1, "seed": 7}],
            "success": {"max_tracking_error": 0.01}}
    with refused("jobs", "[1, 256]"):
        rrlab.sweep(spec, methods=["pinv"], jobs=jobs)


@pytest.mark.parametrize("steps", [-1, 2**64])
def test_run_refuses_steps_out_of_range(steps):
    with refused("steps", "[1, 10000000]"):
        rrlab.run(scenario_path("01_planar7_obstacles.json"), steps=steps)
