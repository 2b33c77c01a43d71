"""The exceptions rrlab raises (the engine's errors, translated)."""


class ScenarioError(ValueError):
    """A scenario, a run input or an argument that rrlab rejects; `path` is the
    JSON path of the offending value (e.g. "robot.links[2].length")."""

    def __init__(self, message, path=""):
        super().__init__(message)
        self.path = path


class ParamError(ValueError):
    """A method parameter that is unknown or out of its range; `param` names it."""

    def __init__(self, message, param=""):
        super().__init__(message)
        self.param = param


class MethodError(RuntimeError):
    """A Python method that failed at a step: it raised, or returned a wrong
    shape or a non-finite value. The message names the method and the step."""


class InputStateError(RuntimeError):
    """A valid live input that the run's state does not allow (e.g. a joystick
    command on a run whose task is not a joystick)."""


def jsonable(value):
    """json.dumps' fallback for numpy arrays and scalars."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not JSON serializable")
