"""rrlab.client: a Python client for the REST and WebSocket API of `rrlab serve`.

REST uses the standard library only (urllib); streaming frames uses the
`websockets` package (Debian: python3-websockets), imported only when
`Client.stream` is called. `Client.frames` returns numpy arrays when numpy is
installed, lists otherwise.

    from rrlab.client import Client
    c = Client("http://127.0.0.1:8080")
    result = c.run("01_planar7_obstacles", "dls", {"lambda": 0.02})   # batch: waits, returns the summary
    frames = c.frames(result["id"])                                    # frames["t"], frames["q"], ...
    live = c.run("04_planar7_joystick", mode="live")
    for frame in c.stream(live["id"]):
        c.joystick(live["id"], [0.05, 0.0])
        ...

Every request says `Content-Type: application/json` when it has a body (the
server refuses other bodies with 415), names the server in `Host` (urllib does)
and sends no `Origin` (the server refuses foreign ones). `token` is sent as
`Authorization: Bearer TOKEN` when given (servers that check no token ignore it).
An error answer is raised as `ApiError` (rrlab.ApiError, a rrlab.Error; the
name `RrlabError` still works) with the server's status, code, message and
JSON path; a wait that runs out raises `Timeout` (a TimeoutError too). The
routes and their bodies: GET /api/openapi.json.
"""
from __future__ import annotations

import importlib
import json
import time
import urllib.error
import urllib.parse
import urllib.request
from typing import Any, Dict, Iterable, Iterator, Mapping, Sequence, Union

from .errors import ApiError, ArgumentError, Error, Timeout

__all__ = ["ApiError", "Client", "Error", "RrlabError", "Timeout"]

_np: Any  # optional: frames as arrays
try:
    import numpy as _np
except ImportError:  # pragma: no cover - depends on the machine
    _np = None

_ENDED = ("completed", "stopped", "failed", "interrupted")


# the client's errors are rrlab's (rrlab.errors): an error answer is an
# ApiError, a wait that ran out a Timeout (a TimeoutError too), both rrlab.Error
RrlabError = ApiError  # the earlier name of ApiError

# A JSON value as the server answers it (json.loads): dicts, lists, numbers, strings
JSON = Any
# A run or sweep id as the server gives it (an int; a string of one is accepted)
RunId = Union[int, str]
# a method as a run or a comparison names it: a name, or {"name", "params"}
MethodConfig = Union[str, Mapping[str, Any]]
# frames as columns (Client.frames): numpy arrays, or lists; "diagnostics" a dict of them
Columns = Dict[str, Any]


class Client:
    """A connection to one rrlab server.

    url: the server's address, e.g. "http://127.0.0.1:8080".
    token: sent as `Authorization: Bearer TOKEN` on every request when given.
    timeout: seconds for one HTTP request (a batch run answers when it has
    ended, so keep it generous).
    """

    def __init__(self, url: str = "http://127.0.0.1:8080", token: str | None = None, timeout: float = 300.0) -> None:
        parsed = urllib.parse.urlsplit(url)
        if parsed.scheme not in ("http", "https") or not parsed.netloc:
            raise ArgumentError(f"url must be http://HOST:PORT, got {url!r}")
        self.url = f"{parsed.scheme}://{parsed.netloc}"
        self.token = token
        self.timeout = timeout

    # ---- plumbing ----

    def _headers(self) -> dict[str, str]:
        headers = {"Accept": "application/json"}
        if self.token:
            headers["Authorization"] = f"Bearer {self.token}"
        return headers

    def request(self, verb: str, path: str, body: JSON = None, query: Mapping[str, Any] | None = None,
                accept: str | None = None) -> JSON:
        """One REST request; returns the parsed JSON answer (text for CSV).

        verb: GET, POST, PUT, PATCH or DELETE; path: "/api/..."; body: a JSON
        value (sent with Content-Type: application/json); query: a dict.
        """
        url = self.url + path
        if query:
            url += "?" + urllib.parse.urlencode({k: v for k, v in query.items() if v is not None})
        headers = self._headers()
        if accept:
            headers["Accept"] = accept
        data: bytes | None = None
        if body is not None:
            data = json.dumps(body).encode("utf-8")
            headers["Content-Type"] = "application/json"
        req = urllib.request.Request(url, data=data, headers=headers, method=verb)
        try:
            with urllib.request.urlopen(req, timeout=self.timeout) as response:
                text = response.read().decode("utf-8")
                kind = response.headers.get("Content-Type", "")
        except urllib.error.HTTPError as e:
            text = e.read().decode("utf-8", "replace")
            try:
                error = json.loads(text)["error"]
            except (ValueError, KeyError, TypeError):
                raise ApiError(e.code, "http", text.strip() or e.reason) from None
            raise ApiError(e.code, error.get("code", ""), error.get("message", ""), error.get("path", ""), text) from None
        if kind.startswith("application/json"):
            return json.loads(text)
        return text

    # ---- catalogue ----

    def health(self) -> JSON:
        """{status, version, api_version, uptime_s, websockets, building}"""
        return self.request("GET", "/api/health")

    def openapi(self) -> JSON:
        """The server's OpenAPI 3.1 document."""
        return self.request("GET", "/api/openapi.json")

    def methods(self) -> JSON:
        """Every method with its parameter specs (default, min, max, unit, choices)."""
        return self.request("GET", "/api/methods")

    def scenarios(self) -> list[JSON]:
        """The whole catalogue as summaries: [{name, title, description (at most
        200 characters), source, builtin, kind, dof, obstacles, bytes}, ...],
        fetched a page at a time (scenario_page)."""
        out: list[JSON] = []
        while True:
            page = self.scenario_page(limit=1000, offset=len(out))
            out.extend(page["scenarios"])
            if not page["scenarios"] or len(out) >= page["total"]:
                return out

    def scenario_page(self, limit: int = 100, offset: int = 0) -> JSON:
        """One page of the catalogue: {scenarios: [summary, ...], total, offset, limit}."""
        return self.request("GET", "/api/scenarios?limit=%d&offset=%d" % (limit, offset))

    def scenario(self, name: str) -> JSON:
        """One scenario's JSON."""
        return self.request("GET", "/api/scenarios/" + urllib.parse.quote(name, safe=""))

    def validate_scenario(self, scenario: Mapping[str, Any]) -> JSON:
        """Checks a scenario object as a run would (ApiError 422 naming the path); stores nothing."""
        return self.request("POST", "/api/scenarios/validate", scenario)

    def add_scenario(self, scenario: Mapping[str, Any]) -> JSON:
        """Stores a scenario object with a new `name` in the server's database."""
        return self.request("POST", "/api/scenarios", scenario)

    # ---- runs ----

    def run(self, scenario: str | Mapping[str, Any], method: str | None = None,
            params: Mapping[str, Any] | None = None, mode: str = "batch", **options: Any) -> JSON:
        """Starts a run. scenario: a catalogue name or a scenario dict.

        mode "batch" (default here): waits until the run has ended and returns
        its status with `summary` (pass wait=False to return at once).
        mode "live": returns at once {id, status, ws, ...}; steer it with
        set_params, move_obstacle, joystick, control, and watch it with stream.
        options: rate, paused, steps, wait, display_hz (see POST /api/runs).
        """
        body: dict[str, Any] = {"scenario": scenario, "mode": mode}
        if method is not None:
            body["method"] = method
        if params:
            body["params"] = params
        body.update(options)
        return self.request("POST", "/api/runs", body)

    def compare(self, scenario: str | Mapping[str, Any], methods: Iterable[MethodConfig], mode: str = "batch",
                **options: Any) -> JSON:
        """Runs 2 to 8 methods on one scenario in lockstep.

        methods: names or {"name", "params"} dicts. batch (default): waits and
        returns {group, runs, comparison}; live: returns {group, runs} at once.
        options: steps, wait, rate, paused.
        """
        body: dict[str, Any] = {"scenario": scenario, "methods": list(methods), "mode": mode}
        body.update(options)
        return self.request("POST", "/api/compare", body)

    def runs(self, scenario: str | None = None, method: str | None = None, status: str | None = None,
             limit: int | None = None, offset: int | None = None) -> JSON:
        """Stored runs, newest first."""
        return self.request("GET", "/api/runs", query={"scenario": scenario, "method": method, "status": status,
                                                       "limit": limit, "offset": offset})

    def get_run(self, run_id: RunId) -> JSON:
        """One stored run (with `live` status while it runs)."""
        return self.request("GET", f"/api/runs/{int(run_id)}")

    def delete_run(self, run_id: RunId) -> JSON:
        """Deletes a stored run with its frames and events (ApiError 409 while it is live)."""
        return self.request("DELETE", f"/api/runs/{int(run_id)}")

    def events(self, run_id: RunId) -> JSON:
        """The input events the run received, in order."""
        return self.request("GET", f"/api/runs/{int(run_id)}/events")

    def record(self, run_id: RunId) -> JSON:
        """The run as a record `rrlab run FILE` runs again."""
        return self.request("GET", f"/api/runs/{int(run_id)}/record")

    def wait(self, run_id: RunId, timeout: float | None = None, poll: float = 0.1) -> JSON:
        """Waits until a run has ended; returns the stored run."""
        deadline = None if timeout is None else time.monotonic() + timeout
        while True:
            run = self.get_run(run_id)
            if run["status"] in _ENDED:
                return run
            if deadline is not None and time.monotonic() > deadline:
                raise Timeout(f"run {run_id} is still {run['status']} after {timeout} s")
            time.sleep(poll)

    def frames(self, run_id: RunId, start: int = 0, stop: int | None = None, stride: int = 1,
               arrays: bool | None = None) -> Columns:
        """A run's stored frames, exact values, as columns.

        Returns a dict: "seq", "step", "t", "task_error", ... one entry per
        frame; "q", "qdot", "ee", "target", ... one row per frame;
        "diagnostics": {name: column}. Columns are numpy arrays when numpy is
        installed (arrays=None) or arrays=True, lists with arrays=False.
        Pages through the server's 20,000-frame limit. stop is inclusive.
        """
        if arrays is None:
            arrays = _np is not None
        if arrays and _np is None:
            raise RuntimeError("arrays=True needs numpy (Debian: python3-numpy)")
        rows: list[dict[str, Any]] = []
        names: list[str] = []
        first = int(start)
        while True:
            page = self.request("GET", f"/api/runs/{int(run_id)}/frames",
                                query={"from": first, "to": stop, "stride": stride})
            names = page["diagnostic_names"]
            rows.extend(page["frames"])
            if not page["frames"]:
                break
            last = page["frames"][-1]["seq"]
            if (stop is not None and last + stride > stop) or len(page["frames"]) < 20000:
                break
            first = last + stride
        # a frame is {seq, step, t, q, ..., metrics: {...}, diagnostics: [...]}
        # (docs/api.md, Frames): the metrics become columns of their own
        columns: Columns = {}
        first_row = rows[0] if rows else {}
        for key in first_row:
            if key == "metrics":
                for metric in first_row["metrics"]:
                    columns[metric] = [row["metrics"].get(metric) for row in rows]
            elif key != "diagnostics":
                columns[key] = [row.get(key) for row in rows]
        columns["diagnostics"] = {name: [row["diagnostics"][i] for row in rows] for i, name in enumerate(names)}
        if arrays:
            def to_array(values: list[Any]) -> Any:  # null (a non-finite number) becomes nan
                if values and isinstance(values[0], list):
                    return _np.array([[_np.nan if x is None else x for x in v] for v in values], dtype=float)
                return _np.array([_np.nan if v is None else v for v in values], dtype=float)
            for key, values in list(columns.items()):
                if key == "diagnostics":
                    columns[key] = {n: to_array(v) for n, v in values.items()}
                elif key == "collided":
                    columns[key] = _np.array(values, dtype=bool)
                elif key in ("seq", "step", "min_distance_link"):
                    columns[key] = _np.array(values, dtype=_np.int64)
                else:
                    columns[key] = to_array(values)
        return columns

    # ---- live runs ----

    def control(self, run_id: RunId, action: str | None = None, rate: float | None = None) -> JSON:
        """action: start, pause, step, reset or stop; rate: real-time factor (0: as fast as possible)."""
        body: dict[str, Any] = {}
        if action is not None:
            body["action"] = action
        if rate is not None:
            body["rate"] = rate
        return self.request("POST", f"/api/runs/{int(run_id)}/control", body)

    def pause(self, run_id: RunId) -> JSON:
        """Pauses a live run."""
        return self.control(run_id, "pause")

    def resume(self, run_id: RunId) -> JSON:
        """Starts or resumes a live run."""
        return self.control(run_id, "start")

    def step(self, run_id: RunId) -> JSON:
        """Advances a paused live run by one step."""
        return self.control(run_id, "step")

    def stop(self, run_id: RunId) -> JSON:
        """Stops a run; answers once it has ended and its frames are stored."""
        return self.control(run_id, "stop")

    def set_params(self, run_id: RunId, params: Mapping[str, Any] | None = None, **named: Any) -> JSON:
        """Sets method parameters of a live run: set_params(id, {"gain": 8}) or set_params(id, gain=8)."""
        body = dict(params or {})
        body.update(named)
        return self.request("PATCH", f"/api/runs/{int(run_id)}/params", body)

    def move_obstacle(self, run_id: RunId, obstacle_id: str, position: Sequence[float] | None = None,
                      velocity: Sequence[float] | None = None, **fields: Any) -> JSON:
        """Moves (position, now) or reshapes (size, radius, points, normal, z) an obstacle of a live run."""
        body = dict(fields)
        if position is not None:
            body["position"] = list(position)
        if velocity is not None:
            body["velocity"] = list(velocity)
        return self.request("PUT", f"/api/runs/{int(run_id)}/obstacles/" + urllib.parse.quote(obstacle_id, safe=""),
                            body)

    def add_obstacle(self, run_id: RunId, obstacle: Mapping[str, Any]) -> JSON:
        """Adds an obstacle in scenario syntax (with a new `id`) to a live run."""
        return self.request("POST", f"/api/runs/{int(run_id)}/obstacles", obstacle)

    def remove_obstacle(self, run_id: RunId, obstacle_id: str) -> JSON:
        """Removes an obstacle from a live run."""
        return self.request("DELETE", f"/api/runs/{int(run_id)}/obstacles/" + urllib.parse.quote(obstacle_id, safe=""))

    def joystick(self, run_id: RunId, linear: Sequence[float], angular: Sequence[float] | None = None) -> JSON:
        """Velocity command to a live joystick run: linear [vx, vy(, vz)] m/s, angular rad/s; held until the next."""
        body: dict[str, Any] = {"linear": list(linear)}
        if angular is not None:
            body["angular"] = list(angular)
        return self.request("POST", f"/api/runs/{int(run_id)}/joystick", body)

    def switch_method(self, run_id: RunId, name: str, params: Mapping[str, Any] | None = None) -> JSON:
        """Switches a live run to method `name` (with `params`) from its next step."""
        body: dict[str, Any] = {"name": name}
        if params:
            body["params"] = params
        return self.request("POST", f"/api/runs/{int(run_id)}/method", body)

    def replay(self, run_id: RunId, mode: str = "resimulate", **options: Any) -> JSON:
        """resimulate: re-runs it and compares every frame ({identical, ...}); frames: starts a replay."""
        return self.request("POST", f"/api/runs/{int(run_id)}/replay", dict(options, mode=mode))

    def stream(self, run_id: RunId, replay: bool = False, snapshots: bool = False, max_frames: int | None = None,
               timeout: float = 30.0) -> Iterator[dict[str, Any]]:
        """A generator of the frames a live run (or, with replay=True, a replay) streams.

        Frames come at the display rate, latest wins (a slow reader skips
        frames; exact values: Client.frames). Ends when the run has ended
        (the frame whose status is completed, stopped or failed is the last),
        after max_frames frames, or when the server closes the socket; raises
        TimeoutError when nothing arrives for `timeout` seconds. snapshots=True
        also yields the snapshot messages (type "snapshot": geometry, limits,
        obstacles, parameters), which come first and after each change.
        Needs the `websockets` package (Debian: python3-websockets).
        """
        import asyncio
        try:
            websockets: Any = importlib.import_module("websockets")  # dynamic: its API moved between versions
        except ImportError as e:
            raise RuntimeError("Client.stream needs the websockets package (Debian: python3-websockets)") from e
        scheme = "wss" if self.url.startswith("https") else "ws"
        path = f"/ws/replays/{int(run_id)}" if replay else f"/ws/runs/{int(run_id)}"
        url = scheme + self.url[self.url.index("://"):] + path
        headers = {"Authorization": f"Bearer {self.token}"} if self.token else {}
        loop = asyncio.new_event_loop()
        socket: Any = None
        try:
            async def connect() -> Any:  # created inside the loop: websockets binds to the running loop
                try:
                    return await websockets.connect(url, extra_headers=headers, max_size=2 ** 24)
                except TypeError:  # websockets >= 14 renamed extra_headers
                    return await websockets.connect(url, additional_headers=headers, max_size=2 ** 24)

            socket = loop.run_until_complete(connect())
            count = 0
            while max_frames is None or count < max_frames:
                try:
                    text = loop.run_until_complete(asyncio.wait_for(socket.recv(), timeout))
                except asyncio.TimeoutError:
                    raise Timeout(f"no message from {path} for {timeout} s") from None
                except websockets.ConnectionClosed:
                    return
                message: dict[str, Any] = json.loads(text)
                kind = message.get("type")
                if kind == "snapshot" and snapshots:
                    yield message
                elif kind == "frame":
                    count += 1
                    yield message
                    if not replay and message.get("status") in _ENDED:
                        return
        finally:
            if socket is not None:
                loop.run_until_complete(socket.close())
            loop.close()

    # ---- sweeps ----

    def sweep(self, spec: Mapping[str, Any], jobs: int = 1, wait: bool = True, poll: float = 0.5,
              timeout: float | None = None) -> JSON:
        """Starts a sweep (a spec dict, as `rrlab sweep` takes; scenarios by
        catalogue name or generator). wait=True: polls until it has ended and
        returns its status with the report; wait=False: returns {id, ...} at once."""
        status = self.request("POST", "/api/sweeps", spec, query={"jobs": jobs})
        if not wait:
            return status
        deadline = None if timeout is None else time.monotonic() + timeout
        while status["status"] == "running":
            if deadline is not None and time.monotonic() > deadline:
                raise Timeout(f"sweep {status['id']} still running after {timeout} s")
            time.sleep(poll)
            status = self.request("GET", f"/api/sweeps/{int(status['id'])}")
        return status

    def stop_sweep(self, sweep_id: RunId) -> JSON:
        """Stops a running sweep (the runs already stored stay)."""
        return self.request("POST", f"/api/sweeps/{int(sweep_id)}/control", {"action": "stop"})
