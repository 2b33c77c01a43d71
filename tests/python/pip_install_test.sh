#!/usr/bin/env bash
# docs/python.md's install, as a user does it: a venv that sees Debian's
# packages (numpy), `pip install --no-build-isolation ./python` (offline: no
# index is asked), then `import rrlab` from another directory, its version and
# its distribution's metadata version the binary's, its stubs and py.typed
# installed beside it, and a run.
#   pip_install_test.sh PYTHON3 SOURCE_DIR BUILD_DIR RRLAB_BINARY
set -euo pipefail
python3="$1" source_dir="$2" build_dir="$3" rrlab="$4"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$python3" -m venv --system-site-packages "$work/venv"
# a copy of the package's source: pip writes its build files next to setup.py
cp -r "$source_dir/python" "$work/python"
rm -rf "$work/python/build" "$work/python/"*.egg-info
ln -s "$source_dir/CMakeLists.txt" "$work/CMakeLists.txt"
RRLAB_BUILD_DIR="$build_dir" "$work/venv/bin/pip" install --quiet --no-build-isolation --no-index "$work/python"
cd "$work"
expected="$("$rrlab" --version | cut -d' ' -f2)"
PYTHONPATH= "$work/venv/bin/python" - "$expected" "$source_dir/scenarios/01_planar7_obstacles.json" <<'PY'
import sys
import rrlab
assert rrlab.__file__.startswith(sys.prefix), rrlab.__file__  # the installed package, not a source tree
assert rrlab.__version__ == sys.argv[1], (rrlab.__version__, sys.argv[1])
import importlib.metadata
import os
meta = importlib.metadata.metadata("rrlab")
assert meta["Version"] == sys.argv[1], (meta["Version"], sys.argv[1])  # pyproject.toml's [project]
assert meta["Requires-Python"] == ">=3.9" and "numpy" in meta.get_all("Requires-Dist"), meta
here = os.path.dirname(rrlab.__file__)
for typed in ("py.typed", "_rrlab.pyi"):  # PEP 561: typed, with the engine module's stubs
    assert os.path.isfile(os.path.join(here, typed)), typed
res = rrlab.run(sys.argv[2], method="dls", steps=20)
assert res["steps"] == 20 and res["frames"]["q"].shape == (20, 7)
print("installed rrlab", rrlab.__version__, "at", rrlab.__file__)
PY
