#!/usr/bin/env python3
"""scripts/check-layers on the tree (no upward include), and on a small tree
made up here that has one of each kind (so the check is seen to catch them).

usage: layers_test.py SOURCE_DIR"""
import os
import subprocess
import sys
import tempfile

source = sys.argv[1]
script = os.path.join(source, "scripts", "check-layers")

tree = subprocess.run([sys.executable, script, source], capture_output=True, text=True)
print(tree.stdout)
assert tree.returncode == 0, "upward includes in the tree:\n" + tree.stdout

UPWARD = {
    "engine/methods/m.cpp": "#include <rrlab/scenario/scenario.hpp>",   # methods never know scenarios
    "engine/scenario/s.cpp": "#include <rrlab/sim/simulator.hpp>",      # the parser does not run the simulator
    "engine/collision/c.hpp": "#include <rrlab/task/task.hpp>",         # one line of the order: not each other
    "engine/model/x.cpp": "#include <rrlab/storage/run_store.hpp>",     # the engine knows no storage
    "storage/y.cpp": "#include <rrlab/sweep/sweep_spec.hpp>",
    "server/app/a.cpp": "#include <rrlab/server/routes/router.hpp>",    # the app layer knows no HTTP routes
}
ALLOWED = {
    "engine/sim/ok.cpp": "#include <rrlab/scenario/scenario.hpp>",
    "engine/scenario/ok.cpp": "#include <rrlab/methods/registry.hpp>",  # the parser may know the registry
    "server/routes/ok.cpp": "#include <rrlab/server/app/run_manager.hpp>",
    "sweep/ok.cpp": "#include <rrlab/storage/run_store.hpp>",
}
with tempfile.TemporaryDirectory() as tmp:
    for name, line in {**UPWARD, **ALLOWED}.items():
        os.makedirs(os.path.join(tmp, os.path.dirname(name)), exist_ok=True)
        with open(os.path.join(tmp, name), "w") as f:
            f.write(line + "\n")
    made = subprocess.run([sys.executable, script, tmp], capture_output=True, text=True)
    print(made.stdout)
    assert made.returncode == 1
    for name in UPWARD:
        assert f"{name}:1:" in made.stdout, f"not caught: {name}"
    for name in ALLOWED:
        assert name not in made.stdout, f"refused, though allowed: {name}"
print("ok")
