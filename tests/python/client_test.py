"""python/rrlab/client.py against a real `rrlab serve` (ctest
Python.rrlab_client): batch run and frames, a live run steered while it
streams, compare, a small sweep, errors, the two examples, and the Python
block of docs/api.md as written (the README's Python lines are lines of it).

Usage: client_test.py RRLAB_BINARY. websockets (Debian
python3-websockets) is required: its absence fails the test."""

import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(os.path.dirname(HERE))
# python/ from the source tree: rrlab.client needs no engine module (this test runs in the sanitized part)
sys.path.insert(0, os.path.join(SOURCE_DIR, "python"))
sys.path.insert(0, os.path.join(SOURCE_DIR, "tests", "support"))

import rrlab_serve  # noqa: E402
import rrlab  # noqa: E402
from rrlab.client import ApiError, Client, RrlabError  # noqa: E402

BINARY = None
HAVE_NUMPY = importlib.util.find_spec("numpy") is not None
HAVE_MATPLOTLIB = importlib.util.find_spec("matplotlib") is not None


class ClientTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.server = rrlab_serve.Server(BINARY)
        cls.client = Client(cls.server.url, token="not-checked-yet")

    @classmethod
    def tearDownClass(cls):
        status = cls.server.stop()
        if status != 0:
            raise AssertionError(f"rrlab serve exited with {status} after SIGTERM")

    def test_catalogue(self):
        self.assertEqual(self.client.health()["status"], "ok")
        names = [s["name"] for s in self.client.scenarios()]
        self.assertIn("01_planar7_obstacles", names)
        self.assertIn("04_planar7_joystick", names)
        # scenarios() pages through every summary; scenario_page is one page
        page = self.client.scenario_page(limit=2, offset=1)
        self.assertEqual(page["total"], len(names))
        self.assertEqual([s["name"] for s in page["scenarios"]], names[1:3])
        planar = next(s for s in self.client.scenarios() if s["name"] == "01_planar7_obstacles")
        self.assertEqual((planar["kind"], planar["dof"]), ("planar", 7))
        methods = {m["name"]: m for m in self.client.methods()}
        self.assertIn("dls", methods)
        self.assertIn("lambda", [p["name"] for p in methods["dls"]["params"]])
        self.assertEqual(self.client.scenario("01_planar7_obstacles")["robot"]["kind"], "planar")
        self.assertEqual(self.client.openapi()["openapi"], "3.1.0")

    def test_batch_run_and_frames(self):
        result = self.client.run("01_planar7_obstacles", "dls", {"lambda": 0.02}, steps=120)
        self.assertEqual(result["status"], "completed")
        self.assertEqual(result["frames"], 120)
        self.assertEqual(result["params"]["lambda"], 0.02)
        self.assertLess(result["summary"]["max_tracking_error"], 0.01)  # 0.00297 (the start's error)
        frames = self.client.frames(result["id"], arrays=False)
        self.assertEqual(len(frames["seq"]), 120)
        self.assertEqual(frames["seq"][:3], [0, 1, 2])
        self.assertEqual(len(frames["q"][0]), 7)
        self.assertEqual(list(frames["diagnostics"]), ["lambda"])
        self.assertAlmostEqual(frames["t"][10], 0.1, delta=1e-12)
        # exact values: the summary's final_q is the last frame's q + dt * qdot (dt 0.01 s), to the bit
        final = [q + 0.01 * qd for q, qd in zip(frames["q"][-1], frames["qdot"][-1])]
        self.assertLess(max(abs(a - b) for a, b in zip(final, result["summary"]["final_q"])), 1e-12)  # 0.0
        page = self.client.frames(result["id"], start=10, stop=30, stride=10, arrays=False)
        self.assertEqual(page["seq"], [10, 20, 30])
        if HAVE_NUMPY:
            arrays = self.client.frames(result["id"])
            self.assertEqual(arrays["q"].shape, (120, 7))
            self.assertEqual(arrays["t"].shape, (120,))
            self.assertEqual(arrays["collided"].dtype.name, "bool")
            self.assertEqual(arrays["q"].tolist(), frames["q"])
        else:
            with self.assertRaises(RuntimeError):
                self.client.frames(result["id"], arrays=True)

    def test_live_run_stream_and_inputs(self):
        run = self.client.run("04_planar7_joystick", mode="live", rate=1)
        run_id = run["id"]
        self.assertEqual(run["status"], "running")
        snapshots, frames = 0, []
        for message in self.client.stream(run_id, snapshots=True, timeout=20):
            if message["type"] == "snapshot":
                snapshots += 1
                continue
            frames.append(message)
            if len(frames) == 3:
                self.assertEqual(self.client.joystick(run_id, [0.05, 0.02])["status"], "running")
                self.assertEqual(self.client.set_params(run_id, gain=8)["params"]["gain"], 8)
                self.client.move_obstacle(run_id, "box", position=[1.9, 0.5])
                self.client.add_obstacle(run_id, {"id": "ball", "shape": "sphere", "center": [1.2, 1.2], "radius": 0.1})
            if len(frames) == 12:
                stopped = self.client.stop(run_id)
                self.assertEqual(stopped["status"], "stopped")
        self.assertGreaterEqual(snapshots, 2)  # the first, and one after each scene/parameter change
        self.assertEqual(frames[-1]["status"], "stopped")  # the stream ends with the run
        seqs = [f["seq"] for f in frames]
        self.assertEqual(seqs, sorted(seqs))
        kinds = [e["kind"] for e in self.client.events(run_id)]
        self.assertEqual(kinds, ["joystick", "params", "obstacle", "obstacle_add"])
        stored = self.client.get_run(run_id)
        self.assertEqual(stored["status"], "stopped")
        self.assertGreater(stored["frames"], 0)
        verdict = self.client.replay(run_id)
        self.assertIs(verdict["identical"], True)

    def test_compare(self):
        result = self.client.compare("01_planar7_obstacles", ["pinv", {"name": "dls", "params": {"lambda": 0.05}}],
                                     steps=60)
        self.assertEqual([r["method"] for r in result["comparison"]], ["pinv", "dls"])
        self.assertEqual(len(result["runs"]), 2)
        for row in result["comparison"]:
            self.assertEqual(self.client.get_run(row["run"])["frames"], 60)

    def test_sweep(self):
        spec = {"name": "py-client-small", "scenarios": [{"generator": "planar_clutter", "count": 2, "seed": 7}],
                "methods": ["pinv", "dls"], "success": {"max_tracking_error": 0.01}, "steps": 100}
        status = self.client.sweep(spec, jobs=1, timeout=240)
        self.assertEqual(status["status"], "completed")
        self.assertEqual(status["total"], 4)
        self.assertEqual(status["done"], 4)
        self.assertEqual(status["failed"], 0)
        self.assertIn("ranking", status["report"])

    def test_errors(self):
        # an error answer is an rrlab.ApiError, an rrlab.Error like every exception rrlab raises
        self.assertIs(RrlabError, ApiError)  # the earlier name
        self.assertIs(ApiError, rrlab.ApiError)
        with self.assertRaises(rrlab.Error) as caught:
            self.client.run("01_planar7_obstacles", "dls", {"lambda": -1})
        self.assertIsInstance(caught.exception, ApiError)
        self.assertEqual(caught.exception.status, 400)
        self.assertEqual(caught.exception.path, "params.lambda")
        with self.assertRaises(ApiError) as caught:
            self.client.run("no_such_scenario")
        self.assertEqual(caught.exception.status, 404)
        with self.assertRaises(RrlabError) as caught:
            self.client.validate_scenario({"robot": {"kind": "planar", "links": [{"length": -1}]},
                                           "task": {"trajectory": {"type": "joystick"}}})
        self.assertEqual((caught.exception.status, caught.exception.path), (422, "robot.links[0].length"))
        with self.assertRaises(rrlab.ArgumentError):  # a ValueError too
            Client("127.0.0.1:8080")
        with self.assertRaises(ValueError):
            Client("127.0.0.1:8080")
        live = self.client.run("01_planar7_obstacles", mode="live", paused=True)
        try:
            with self.assertRaises(rrlab.Timeout):  # a TimeoutError too
                self.client.wait(live["id"], timeout=0)
        finally:
            self.client.stop(live["id"])

    @staticmethod
    def python_block(path, after):
        """The first ```python block of the file at `path` (from the source dir) after the text `after`."""
        with open(os.path.join(SOURCE_DIR, path), encoding="utf-8") as f:
            text = f.read()
        start = text.index("```python", text.index(after)) + len("```python")
        return text[start:text.index("```", start)]

    def test_docs_snippet_runs(self):
        # the Python block of docs/api.md (Clients, "Python client"), as written, on this server
        code = self.python_block(os.path.join("docs", "api.md"), "**Python client.**")
        code = code.replace("http://127.0.0.1:8080", self.server.url) + "\nprint(len(table), sorted(report))\n"
        done = subprocess.run([sys.executable, "-c", code], cwd=SOURCE_DIR, capture_output=True, text=True,
                              timeout=300)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertIn("3 ['comparisons', 'fallbacks', 'groups', 'pairs', 'ranking', 'rules', 'sweeps', 'verdicts']", done.stdout)

    def test_readme_lines_are_the_docs_snippets_first_lines(self):
        # the README's Python lines are not run on their own: they are lines of the docs/api.md block
        # above, in its order, so that test_docs_snippet_runs runs them
        docs = [line for line in self.python_block(os.path.join("docs", "api.md"), "**Python client.**").splitlines()
                if line.strip()]
        readme = [line for line in self.python_block("README.md", "## ").splitlines() if line.strip()]
        self.assertGreaterEqual(len(readme), 5)  # 5 when written
        positions = []
        for line in readme:
            self.assertIn(line, docs, "README.md: a Python line that is not a line of docs/api.md's Python client "
                                      "block (copy it from there, as written)")
            positions.append(docs.index(line))
        self.assertEqual(positions, sorted(positions), "README.md: the Python lines are not in docs/api.md's order")

    def run_example(self, name, *args, env=None):
        command = [sys.executable, os.path.join(SOURCE_DIR, "python", "examples", name),
                   "--url", self.server.url, *args]
        done = subprocess.run(command, capture_output=True, text=True, timeout=300, env=env)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        return done.stdout

    def test_example_compare_methods(self):
        with tempfile.TemporaryDirectory() as tmp:
            png = os.path.join(tmp, "compare.png")
            out = self.run_example("compare_methods.py", "--steps", "100", "--out", png)
            self.assertIn("closest_point", out)
            if HAVE_MATPLOTLIB:
                self.assertIn("plot written to", out)
                with open(png, "rb") as f:
                    data = f.read()
                self.assertEqual(data[:8], b"\x89PNG\r\n\x1a\n")
                self.assertGreater(len(data), 10000)  # 800x600 with three curves: ~45 KB
            else:
                self.assertIn("matplotlib is not installed", out)
                self.assertFalse(os.path.exists(png))

    def test_example_compare_methods_without_matplotlib(self):
        # a matplotlib package that fails to import stands in for a machine without it
        with tempfile.TemporaryDirectory() as tmp:
            os.makedirs(os.path.join(tmp, "matplotlib"))
            with open(os.path.join(tmp, "matplotlib", "__init__.py"), "w") as f:
                f.write("raise ImportError('hidden by the test')\n")
            png = os.path.join(tmp, "compare.png")
            env = dict(os.environ, PYTHONPATH=tmp)
            out = self.run_example("compare_methods.py", "--steps", "50", "--out", png, env=env)
            self.assertIn("matplotlib is not installed: no plot written", out)
            self.assertIn("dls", out)  # the table is printed all the same
            self.assertFalse(os.path.exists(png))

    def test_example_joystick(self):
        out = self.run_example("joystick.py", "--seconds", "2")
        self.assertIn("moving obstacle 'box'", out)
        self.assertRegex(out, r"run \d+ stopped after \d+ steps")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: client_test.py RRLAB_BINARY")
    BINARY = sys.argv.pop(1)
    unittest.main(verbosity=2)
