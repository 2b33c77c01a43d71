"""docs/scenario.schema.json (ctest Docs.scenario_schema): a valid JSON Schema
2020-12 that every scenario file of scenarios/ satisfies, and that refuses
what the parser (engine/scenario/scenario.cpp) refuses in a few typical
mistakes. Needs python3-jsonschema (its absence fails the test)."""

import copy
import glob
import json
import os
import unittest

import jsonschema

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def load(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


class ScenarioSchema(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.schema = load(os.path.join(SOURCE_DIR, "docs", "scenario.schema.json"))
        jsonschema.Draft202012Validator.check_schema(cls.schema)
        cls.validator = jsonschema.Draft202012Validator(cls.schema)

    def errors(self, doc):
        return [f"{'.'.join(map(str, e.absolute_path))}: {e.message}" for e in self.validator.iter_errors(doc)]

    def test_every_scenario_file_is_valid(self):
        files = sorted(glob.glob(os.path.join(SOURCE_DIR, "scenarios", "*.json")))
        self.assertGreaterEqual(len(files), 20)  # 22 when written
        for path in files:
            with self.subTest(scenario=os.path.basename(path)):
                self.assertEqual(self.errors(load(path)), [])

    def test_typical_mistakes_are_refused(self):
        base = load(os.path.join(SOURCE_DIR, "scenarios", "01_planar7_obstacles.json"))
        self.assertEqual(self.errors(base), [])

        def broken(edit):
            doc = copy.deepcopy(base)
            edit(doc)
            return doc

        mistakes = {
            "unknown top-level key": lambda d: d.update(colour="red"),
            "no robot": lambda d: d.pop("robot"),
            "no task": lambda d: d.pop("task"),
            "dt over 1 s": lambda d: d.update(dt=2),
            "angle unit": lambda d: d.update(angle_unit="grad"),
            "negative seed": lambda d: d.update(seed=-1),
            "robot kind": lambda d: d["robot"].update(kind="scara"),
            "no links": lambda d: d["robot"].update(links=[]),
            "negative link length": lambda d: d["robot"]["links"][0].update(length=-0.4),
            "dh key on a planar link": lambda d: d["robot"]["links"][0].update(alpha=90),
            "base_rpy on a planar robot": lambda d: d["robot"].update(base_rpy=[0, 0, 0]),
            "3D base on a planar robot": lambda d: d["robot"].update(base=[0, 0, 0]),
            "zero velocity limit": lambda d: d["robot"]["limits"]["velocity"].__setitem__(0, 0),
            "obstacle shape": lambda d: d["obstacles"][0].update(shape="cone"),
            "sphere without radius": lambda d: d["obstacles"][1].pop("radius"),
            "polygon of two points": lambda d: d["obstacles"][0].update(points=[[0, 0], [1, 1]]),
            "box key on a sphere": lambda d: d["obstacles"][1].update(size=[1, 1]),
            "mesh obstacle on a planar robot": lambda d: d["obstacles"].append(
                {"shape": "mesh", "file": "meshes/torus.obj", "center": [1, 1, 0]}),
            "task space": lambda d: d["task"].update(space="uv"),
            "trajectory type": lambda d: d["task"]["trajectory"].update(type="spiral"),
            "circle without radius": lambda d: d["task"]["trajectory"].pop("radius"),
            "circle direction": lambda d: d["task"]["trajectory"].update(direction="left"),
            "method without name": lambda d: d["method"].pop("name"),
            "parameter as a list": lambda d: d["method"]["params"].update(gain=[1, 2]),
        }
        for what, edit in mistakes.items():
            with self.subTest(mistake=what):
                self.assertGreater(len(self.errors(broken(edit))), 0)

    def test_dh_robots_take_dh_links_and_a_3d_base(self):
        doc = load(os.path.join(SOURCE_DIR, "scenarios", "03_dh7_pose.json"))
        self.assertEqual(self.errors(doc), [])
        doc["robot"]["links"][0]["joint"] = "prismatic"
        doc["robot"]["base_rpy"] = [0, 0, 90]
        self.assertEqual(self.errors(doc), [])
        doc["robot"]["links"][0]["length"] = 0.3  # a planar key
        self.assertGreater(len(self.errors(doc)), 0)

    def test_mesh_obstacles_on_spatial_robots(self):
        doc = load(os.path.join(SOURCE_DIR, "scenarios", "43_urdf_iiwa14_mesh_obstacle.json"))
        self.assertEqual(self.errors(doc), [])
        hoop = doc["obstacles"][0]
        for scale in ([1, 2, 3], 0.5):
            hoop["scale"] = scale
            self.assertEqual(self.errors(doc), [], scale)
        for bad in (0, -1, [1, 0, 1], [1, 2], "big"):
            hoop["scale"] = bad
            self.assertGreater(len(self.errors(doc)), 0, bad)
        hoop["scale"] = 1
        for key, value in (("size", [1, 1, 1]), ("center", [1, 2])):
            broken = copy.deepcopy(doc)
            broken["obstacles"][0][key] = value
            self.assertGreater(len(self.errors(broken)), 0, key)
        broken = copy.deepcopy(doc)
        broken["obstacles"][0].pop("file")
        self.assertGreater(len(self.errors(broken)), 0)


if __name__ == "__main__":
    unittest.main(verbosity=2)
