"""rrlab: redundancy-resolution lab, in Python.

    import rrlab
    sc = rrlab.load_scenario("scenarios/01_planar7_obstacles.json")
    res = rrlab.run(sc, method="dls", params={"lambda": 0.05})
    res["min_distance"], res["frames"]["q"]

The engine runs in this process (the GIL is released while it steps); a
method may be written in Python (rrlab.Method); rrlab.client talks to a
running `rrlab serve`. Every exception rrlab raises is an rrlab.Error
(rrlab.errors). docs/python.md has the rest.
"""
from typing import NoReturn

from . import errors
from .errors import (ApiError, ArgumentError, EngineError, Error, InputStateError, MethodError, ParamError,
                     ScenarioError, Timeout)
from ._sweep import sweep
from .method import Method, Param

try:
    import numpy as _numpy  # noqa: F401  the engine's arrays (Debian: python3-numpy, for /usr/bin/python3)

    from ._rrlab import (Scenario, Simulator, StepState, __version__, generate, load_scenario, methods,
                         register_method, replay, run)
except ImportError as _missing:  # no engine module (a source tree) or no numpy: rrlab.client still works
    _engine_error = _missing

    def __getattr__(name: str) -> NoReturn:
        raise ImportError(f"rrlab.{name} needs rrlab's engine module, which did not load ({_engine_error}); "
                          "install the package as docs/python.md says") from _engine_error

__all__ = [
    "ApiError", "ArgumentError", "EngineError", "Error", "InputStateError", "Method", "MethodError", "Param",
    "ParamError", "Scenario", "ScenarioError", "Simulator", "StepState", "Timeout", "__version__", "errors",
    "generate", "load_scenario", "methods", "register_method", "replay", "run", "sweep",
]
