"""rrlab.sweep: a sweep spec (docs/cli.md, "sweep") run in this process, with
methods written in Python beside the built-in ones."""
from __future__ import annotations

import copy
import csv
import io
import json
import os
import tempfile
from types import ModuleType
from typing import Any, Iterable, Mapping, Union

from .method import Method

# a "methods" entry of a sweep: a name, a {"name", "params"} configuration
# (its name may be a Python method), or a Python method
MethodEntry = Union[str, Mapping[str, Any], Method]


def _method_entry(entry: MethodEntry, engine: ModuleType) -> str | dict[str, Any]:
    """A spec "methods" entry with Python methods registered and named."""
    if isinstance(entry, str):
        return entry
    if isinstance(entry, Mapping):
        config = dict(entry)
        if not isinstance(config.get("name"), str):
            config["name"] = engine.register_method(config["name"])
        return config
    name: str = engine.register_method(entry)
    return name


def _typed(value: str) -> int | float | str | None:
    """A per-run CSV cell as a number where it is one ("" is None)."""
    if value == "":
        return None
    try:
        return int(value)
    except ValueError:
        pass
    try:
        return float(value)
    except ValueError:
        return value


def sweep(spec: Mapping[str, Any] | str | os.PathLike[str], methods: Iterable[MethodEntry] | None = None,
          jobs: int = 2, db: str | os.PathLike[str] | None = None,
          scenarios_dir: str | os.PathLike[str] | None = None, frames: bool = False) -> dict[str, Any]:
    """Runs a sweep spec (a dict or a JSON file) in this process.

    methods: replaces the spec's "methods": names, {"name", "params"} configs
    (value lists span grids) and Python methods (rrlab.Method objects, also as
    a config's "name"), which are registered by their names (register_method).
    jobs: worker threads; the engine steps without the GIL, Python methods
    take it for their own steps. db: a SQLite file that keeps the runs (a
    second call resumes; `rrlab serve --db` shows them, and replays a Python
    method's runs only from frames stored with frames=True); None: a
    temporary one. scenarios_dir: where scenario names of the spec are found
    (default ./scenarios when it exists, else the spec's directory).

    Returns {"report": the report as `rrlab report --format json` gives it,
    "runs": the per-run table (one dict per run, the columns of
    `rrlab sweep --out`), "sweep", "runs_total", "stored",
    "already_stored", "failures": ["KEY: message", ...]}.
    """
    from . import _rrlab as engine

    if isinstance(spec, (str, os.PathLike)):
        path = os.fspath(spec)
        with open(path, encoding="utf-8") as f:
            doc: dict[str, Any] = json.load(f)
        spec_dir = os.path.dirname(os.path.abspath(path))
    else:
        doc = copy.deepcopy(dict(spec))
        spec_dir = os.getcwd()
    if methods is not None:
        doc["methods"] = list(methods)
    doc["methods"] = [_method_entry(entry, engine) for entry in doc.get("methods", [])]
    if scenarios_dir is None:
        scenarios_dir = "scenarios" if os.path.isdir("scenarios") else spec_dir
    with tempfile.TemporaryDirectory(prefix="rrlab-sweep-") as scratch:
        database = os.fspath(db) if db is not None else os.path.join(scratch, "sweep.db")
        report, table, done = engine._run_sweep(json.dumps(doc), spec_dir, os.path.abspath(scenarios_dir), jobs,
                                                database, bool(frames))
    runs = [{key: _typed(value) for key, value in row.items()} for row in csv.DictReader(io.StringIO(table))]
    return {"report": json.loads(report), "runs": runs, "sweep": done["sweep"], "runs_total": done["runs"],
            "stored": done["stored"], "already_stored": done["already_stored"], "failures": done["failures"]}
