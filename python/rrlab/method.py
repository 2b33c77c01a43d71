"""Redundancy-resolution methods written in Python.

Subclass Method, give it a `name` (no built-in method's) and a
`step(self, state)` that returns the joint velocity (a sequence of n
numbers); rrlab.run and rrlab.Simulator then run it like a built-in method:
the same integration, limit and collision checks, metrics and frames.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Union

if TYPE_CHECKING:  # the engine module imports this one: no import of it at run time
    import numpy
    import numpy.typing as npt

    from ._rrlab import StepState

# What step() returns: n joint velocities, as a numpy array or a sequence of numbers
JointVelocity = Union["npt.NDArray[numpy.floating[Any]]", Sequence[float]]


@dataclass
class Param:
    """A parameter of a Python method: validated like a built-in method's
    (range), settable with params={...}, Simulator.set_param and sweeps."""

    name: str
    default: float = 0.0
    min: float = -math.inf
    max: float = math.inf
    step: float = 0.0
    label: str = ""
    unit: str = ""
    help: str = ""


class Method:
    """Base class of a method written in Python.

    name:    the method's name in summaries and frames (default: the class name)
    params:  a list of Param (optional)
    start(self, context):  optional; called when a run (re)starts, with a dict
             of dof, task_rows, obstacles and seed
    step(self, state):     the joint velocity for this step; `state` is an
             rrlab.StepState (q, qdot, t, dt, J, xdot, error, limits,
             per-link distances, points, normals and distance Jacobians)
    """

    name: Optional[str] = None
    params: List[Param] = []
    param_values: Dict[str, float] = {}  # set by the engine, per object

    def param(self, name: str) -> float:
        """The current value of parameter `name` (set by the engine)."""
        return self.param_values[name]

    def step(self, state: StepState) -> JointVelocity:
        """The joint velocity (n numbers) to apply over [t, t + dt]."""
        raise NotImplementedError("a rrlab.Method needs a step(self, state) that returns the joint velocity")
