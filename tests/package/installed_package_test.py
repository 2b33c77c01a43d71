#!/usr/bin/env python3
"""rrlab as a package others build on: `cmake --install` the build into a
temporary prefix, build examples/cpp against it with find_package(rrlab), and
check that rrlab::Simulator(scenario, M) run to the end gives the summary of
`rrlab run SCENARIO --method M` (final q bit for bit), and that a method of
one's own registers and runs.

usage: installed_package_test.py BUILD_DIR SOURCE_DIR RRLAB_BINARY CMAKE"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

build, source, rrlab, cmake = sys.argv[1:5]

# a planar arm among obstacles, a spatial DH arm with a pose task, a URDF arm
SCENARIOS = ["01_planar7_obstacles.json", "03_dh7_pose.json", "40_urdf_iiwa14_pose.json"]
COMPARED = ["steps", "max_tracking_error", "collided", "final_q"]


def run(cmd, **kw):
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {p.returncode}\n{p.stdout[-4000:]}\n{p.stderr[-4000:]}")
    return p.stdout


def main():
    with tempfile.TemporaryDirectory(prefix="rrlab-package-") as tmp:
        prefix = os.path.join(tmp, "prefix")
        run([cmake, "--install", build, "--prefix", prefix])
        for installed in ["include/rrlab/rrlab.hpp", "include/rrlab/sim/simulator.hpp",
                          "include/rrlab/storage/run_store.hpp", "include/rrlab/sweep/sweep_spec.hpp"]:
            assert os.path.isfile(os.path.join(prefix, installed)), f"not installed: {installed}"
        config = [d for d in ("lib", "lib64") if os.path.isfile(os.path.join(prefix, d, "cmake/rrlab/rrlabConfig.cmake"))]
        assert config, "no lib/cmake/rrlab/rrlabConfig.cmake"

        examples = os.path.join(tmp, "examples")
        configure = [cmake, "-S", os.path.join(source, "examples/cpp"), "-B", examples, "-G", "Ninja",
                     "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_PREFIX_PATH=" + prefix]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        run(configure)
        run([cmake, "--build", examples, "--parallel", "2"])

        for name in SCENARIOS:
            path = os.path.join(source, "scenarios", name)
            own = json.load(open(path))["method"]["name"]
            method = "dls" if own != "dls" else "pinv"  # another method than the scenario's: both use its defaults
            cli = json.loads(run([rrlab, "run", path, "--method", method]))
            example = json.loads(run([os.path.join(examples, "run_method"), path, method]))
            for key in COMPARED:
                assert cli[key] == example[key], f"{name} --method {method}: {key} {example[key]} != rrlab run's {cli[key]}"
            assert example["method"] == method, example["method"]
            print(f"ok {name} {method}: {cli['steps']} steps, final q equal")

        path = os.path.join(source, "scenarios", SCENARIOS[0])
        own = json.loads(run([os.path.join(examples, "own_method"), path]))
        steps = json.loads(run([rrlab, "run", path]))["steps"]
        assert own["method"] == "scaled_dls", own["method"]
        assert own["steps"] == steps, (own["steps"], steps)
        assert own["nonfinite_steps"] == 0
        assert own["max_tracking_error"] < 0.01, own["max_tracking_error"]  # its task is tracked
        print(f"ok own method: {own['steps']} steps, max tracking error {own['max_tracking_error']:.2e} m")


if __name__ == "__main__":
    main()
