"""The exceptions rrlab raises: one hierarchy rooted at rrlab.Error.

    Error                                   everything rrlab raises (except rrlab.Error: catches them all)
    +-- ScenarioError(Error, ValueError)    a scenario, run input or argument rrlab rejects; .path
    +-- ParamError(Error, ValueError)       a method parameter unknown or out of range; .param
    +-- ArgumentError(Error, ValueError)    another bad argument (e.g. a Python method object without step)
    +-- MethodError(Error, RuntimeError)    a Python method that failed at a step, or re-entered the engine
    +-- InputStateError(Error, RuntimeError)  a live input the run's state does not allow
    +-- EngineError(Error, RuntimeError)    any other failure inside the engine (a database, a stale StepState)
    +-- ApiError(Error)                     an error answer of `rrlab serve` (rrlab.client); .status, .code
    +-- Timeout(Error, TimeoutError)        rrlab.client waited too long for a run, a sweep or a message

The engine's C++ exceptions are translated into these by the engine module
(python/src/module.cpp); each also derives from the built-in exception it
was before (ValueError, RuntimeError), so code that catches those still
does.
"""
from __future__ import annotations

from typing import Any

__all__ = ["ApiError", "ArgumentError", "EngineError", "Error", "InputStateError", "MethodError", "ParamError",
           "ScenarioError", "Timeout", "jsonable"]


class Error(Exception):
    """The base of every exception rrlab raises: `except rrlab.Error` catches
    the engine's errors, a Python method's failures and the client's."""


class ScenarioError(Error, ValueError):
    """A scenario, a run input or an argument that rrlab rejects; `path` is the
    JSON path of the offending value (e.g. "robot.links[2].length")."""

    def __init__(self, message: str, path: str = "") -> None:
        super().__init__(message)
        self.path = path


class ParamError(Error, ValueError):
    """A method parameter that is unknown or out of its range; `param` names it."""

    def __init__(self, message: str, param: str = "") -> None:
        super().__init__(message)
        self.param = param


class ArgumentError(Error, ValueError):
    """An argument the engine rejects that is not part of a scenario, e.g. a
    Python method given as a class, without step(), or with a built-in
    method's name; the message says what is wrong."""


class MethodError(Error, RuntimeError):
    """A Python method that failed at a step: it raised, or returned a wrong
    shape or a non-finite value; or a method's own code that tried to run or
    step a simulation. The message names the method and the step."""


class InputStateError(Error, RuntimeError):
    """A valid live input that the run's state does not allow (e.g. a joystick
    command on a run whose task is not a joystick)."""


class EngineError(Error, RuntimeError):
    """Any other failure inside the engine: a database that cannot be opened,
    a StepState read after its step, a Simulator used from two threads."""


class ApiError(Error):
    """An error answer of `rrlab serve` to rrlab.client: {"error": {"code",
    "message", "path"}} with its HTTP status (rrlab.client.RrlabError is
    this class, its earlier name)."""

    def __init__(self, status: int, code: str, message: str, path: str = "", body: str | None = None) -> None:
        super().__init__(f"{status} {code}: {message}" + (f" (at {path})" if path else ""))
        self.status = status
        self.code = code
        self.message = message
        self.path = path
        self.body = body


class Timeout(Error, TimeoutError):
    """rrlab.client waited longer than its timeout for a run or a sweep to end,
    or for a streamed message (also a built-in TimeoutError)."""


def jsonable(value: Any) -> Any:
    """json.dumps' fallback for numpy arrays and scalars."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON serializable")
