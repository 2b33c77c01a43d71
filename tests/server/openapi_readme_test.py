"""The REST examples of docs/api.md against the OpenAPI document a live
server serves (ctest Python.openapi_readme): every curl line's verb and path
is a documented operation, and every JSON body it sends is valid against that
operation's request schema (JSON Schema 2020-12, python3-jsonschema); and
the server's real answers to every operation, successes and errors, are valid
against the documented answer schemas. The examples are the fenced block
between <!-- api-examples --> and <!-- /api-examples --> in docs/api.md
(tests/server/readme_examples_test.cpp runs the same block against a server).
The README shows a few of them: every line of its curl block must be a line
of that block, so that they are validated and run with it.

Usage: openapi_readme_test.py RRLAB_BINARY"""

import json
import os
import re
import shlex
import sys
import unittest
import urllib.error
import urllib.request

import jsonschema  # Debian: python3-jsonschema (required: CI installs it)

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(SOURCE_DIR, "tests", "support"))
import rrlab_serve  # noqa: E402

BINARY = None


def example_block():
    """The lines of the fenced block between the api-examples markers of docs/api.md."""
    with open(os.path.join(SOURCE_DIR, "docs", "api.md"), encoding="utf-8") as f:
        text = f.read()
    block = text[text.index("<!-- api-examples -->"):text.index("<!-- /api-examples -->")]
    block = block[block.index("```sh") + 5:block.rindex("```")]
    return block.splitlines()


def api_examples():
    return [line for line in example_block() if "curl " in line]


def readme_curl_block():
    """The code lines (not comments, not blank) of the README's fenced sh block that calls curl."""
    with open(os.path.join(SOURCE_DIR, "README.md"), encoding="utf-8") as f:
        text = f.read()
    blocks = re.findall(r"^```sh\n(.*?)^```", text, re.S | re.M)
    curl_blocks = [b for b in blocks if "curl " in b]
    if len(curl_blocks) != 1:
        raise AssertionError(f"README.md: expected one sh block with curl lines, found {len(curl_blocks)}")
    return [line for line in curl_blocks[0].splitlines() if line.strip() and not line.lstrip().startswith("#")]


def parse_curls(line):
    """[(verb, path, body or None), ...]: every curl command of a shell line."""
    words = shlex.split(line, comments=True)
    commands, current = [], None
    for word in words:
        if word == "curl" or word.endswith("$(curl"):
            current = []
            commands.append(current)
        elif word in ("|", ">", ">>", "&&", ";"):
            current = None
        elif current is not None:
            current.append(word)
    out = []
    for args in commands:
        verb, url, body = None, None, None
        i = 0
        while i < len(args):
            if args[i] == "-X":
                verb, i = args[i + 1], i + 2
            elif args[i] in ("-d", "--data"):
                body, i = args[i + 1], i + 2
            elif args[i] == "-H":
                i += 2
            elif args[i].startswith("-"):
                i += 1
            else:
                url, i = args[i], i + 1
        verb = verb or ("POST" if body is not None else "GET")
        out.append((verb, url.replace("$RRLAB", "").split("?")[0].replace("$ID", "1"), body))
    return out


def find_operation(document, verb, path):
    for template, item in document["paths"].items():
        pattern = "^" + re.sub(r"\\\{[^}]+\\\}", "[^/]+", re.escape(template)) + "$"
        if re.match(pattern, path) and verb.lower() in item:
            return template, item[verb.lower()]
    return None, None


def body_validator(document, template, verb):
    """A validator for the request body of one operation, $refs resolved in the document."""
    pointer = "/paths/" + template.replace("~", "~0").replace("/", "~1") + "/" + verb.lower() + \
              "/requestBody/content/application~1json/schema"
    schema = {"$ref": "#" + pointer, "paths": document["paths"], "components": document["components"]}
    return jsonschema.Draft202012Validator(schema)


def answer_validator(document, template, verb, status):
    """A validator for one documented answer (an error answer's $ref'd response included)."""
    operation = document["paths"][template][verb.lower()]
    answer = operation["responses"][str(status)]
    if "$ref" in answer:
        answer = document["components"]["responses"][answer["$ref"].split("/")[-1]]
    schema = dict(answer["content"]["application/json"]["schema"], components=document["components"])
    return jsonschema.Draft202012Validator(schema)


class ExamplesAgainstOpenApi(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.server = rrlab_serve.Server(BINARY)
        with urllib.request.urlopen(cls.server.url + "/api/openapi.json") as r:
            cls.document = json.load(r)
        with urllib.request.urlopen(cls.server.url + "/api/scenarios/01_planar7_obstacles") as r:
            cls.scenario = json.load(r)

    @classmethod
    def tearDownClass(cls):
        cls.server.stop()

    def test_every_schema_is_valid_json_schema(self):
        schemas = self.document["components"]["schemas"]
        for name, schema in schemas.items():
            with self.subTest(schema=name):
                jsonschema.Draft202012Validator.check_schema(schema)
        self.assertGreater(len(schemas), 40)  # 44: the API's and the scenario format's

    def test_readme_curl_lines_are_lines_of_the_examples(self):
        block = set(example_block())
        lines = readme_curl_block()
        self.assertGreaterEqual(sum("curl " in line for line in lines), 5)  # 5 when written
        for line in lines:
            with self.subTest(line=line):
                self.assertIn(line, block, "README.md: a curl block line that is not a line of docs/api.md's "
                                           "api-examples block (copy it from there, as written)")

    def test_every_example_curl_is_a_documented_operation_with_a_valid_body(self):
        lines = api_examples()
        bodies = 0
        calls = [call for line in lines for call in parse_curls(line)]
        self.assertGreaterEqual(len(calls), 20)  # 22 when written
        for verb, path, body in calls:
            with self.subTest(call=f"{verb} {path}"):
                template, operation = find_operation(self.document, verb, path)
                self.assertIsNotNone(operation, f"{verb} {path} is not in the OpenAPI document")
                if body is None:
                    self.assertFalse(operation.get("requestBody", {}).get("required", False),
                                     f"{verb} {template} needs a body")
                    continue
                self.assertIn("requestBody", operation, f"{verb} {template} takes no body")
                # `-d @-` pipes the catalogue scenario GET /api/scenarios/01_planar7_obstacles gave
                value = self.scenario if body == "@-" else json.loads(body)
                errors = [e.message for e in body_validator(self.document, template, verb).iter_errors(value)]
                self.assertEqual(errors, [], f"{verb} {template} body {body}")
                bodies += 1
        self.assertGreaterEqual(bodies, 12)  # 12 when written (one is the piped scenario)

    def call(self, verb, path, body=None):
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(self.server.url + path, data=data, method=verb,
                                         headers={"Content-Type": "application/json"} if data else {})
        try:
            with urllib.request.urlopen(request, timeout=120) as r:
                return r.status, json.load(r)
        except urllib.error.HTTPError as e:
            return e.code, json.load(e)

    def test_answers_match_the_documented_schemas(self):
        # the server's real answers, success and error, against the documented ones
        checked = []

        def check(verb, template, path=None, body=None, status=None):
            code, answer = self.call(verb, path or template, body)
            if status is not None:
                self.assertEqual(code, status, answer)
            errors = [f"{'/'.join(map(str, e.absolute_path))}: {e.message}"
                      for e in answer_validator(self.document, template, verb, code).iter_errors(answer)]
            self.assertEqual(errors, [], f"{verb} {path or template} -> {code}")
            checked.append((verb, template, code))
            return answer

        check("GET", "/api/health", status=200)
        check("GET", "/api/methods", status=200)
        check("GET", "/api/openapi.json", status=200)
        check("GET", "/api/scenarios", status=200)
        check("GET", "/api/scenarios/{name}", "/api/scenarios/01_planar7_obstacles", status=200)
        check("GET", "/api/scenarios/{name}", "/api/scenarios/nothing", status=404)
        check("POST", "/api/scenarios/validate", body=self.scenario, status=200)
        check("POST", "/api/scenarios/validate", body={"robot": {}, "task": {}}, status=422)
        check("POST", "/api/scenarios", body=dict(self.scenario, name="openapi_copy"), status=201)
        check("POST", "/api/scenarios", body=dict(self.scenario, name="openapi_copy"), status=409)
        batch = check("POST", "/api/runs", body={"scenario": "01_planar7_obstacles", "method": "dls", "mode": "batch",
                                                  "steps": 30}, status=200)
        check("POST", "/api/runs", body={"scenario": "01_planar7_obstacles", "params": {"nothing": 1}}, status=400)
        run = f"/api/runs/{batch['id']}"
        check("GET", "/api/runs/{id}", run, status=200)
        check("GET", "/api/runs", "/api/runs?limit=5", status=200)
        check("GET", "/api/runs/{id}/frames", run + "/frames?from=0&to=3", status=200)
        check("GET", "/api/runs/{id}/events", run + "/events", status=200)
        check("GET", "/api/runs/{id}/record", run + "/record", status=200)
        check("POST", "/api/runs/{id}/replay", run + "/replay", body={"mode": "resimulate"}, status=200)
        replay = check("POST", "/api/runs/{id}/replay", run + "/replay", body={"mode": "frames"}, status=201)
        check("GET", "/api/replays/{rid}", f"/api/replays/{replay['replay']}", status=200)
        check("POST", "/api/replays/{rid}/control", f"/api/replays/{replay['replay']}/control",
              body={"action": "pause"}, status=200)
        live = check("POST", "/api/runs", body={"scenario": "04_planar7_joystick", "paused": True}, status=201)
        lr = f"/api/runs/{live['id']}"
        check("GET", "/api/runs/{id}", lr, status=200)
        check("POST", "/api/runs/{id}/joystick", lr + "/joystick", body={"linear": [0.05, 0.02]}, status=200)
        check("PATCH", "/api/runs/{id}/params", lr + "/params", body={"gain": 8}, status=200)
        check("PUT", "/api/runs/{id}/obstacles/{oid}", lr + "/obstacles/box", body={"position": [1.9, 0.5]}, status=200)
        check("PUT", "/api/runs/{id}/obstacles/{oid}", lr + "/obstacles/nothing", body={"position": [1, 1]}, status=404)
        check("POST", "/api/runs/{id}/obstacles", lr + "/obstacles",
              body={"id": "ball", "shape": "sphere", "center": [1.2, 1.2], "radius": 0.1}, status=200)
        check("DELETE", "/api/runs/{id}/obstacles/{oid}", lr + "/obstacles/ball", status=200)
        check("POST", "/api/runs/{id}/method", lr + "/method", body={"name": "dls"}, status=200)
        check("POST", "/api/runs/{id}/control", lr + "/control", body={"action": "step"}, status=200)
        check("DELETE", "/api/runs/{id}", lr, status=409)
        check("POST", "/api/runs/{id}/control", lr + "/control", body={"action": "stop"}, status=200)
        check("POST", "/api/runs/{id}/joystick", lr + "/joystick", body={"linear": [0.1, 0]}, status=409)
        check("DELETE", "/api/runs/{id}", lr, status=200)
        check("GET", "/api/runs/{id}", lr, status=404)
        check("POST", "/api/compare", body={"scenario": "01_planar7_obstacles", "methods": ["pinv", "dls"], "steps": 20},
              status=200)
        check("POST", "/api/compare", body={"scenario": "01_planar7_obstacles", "methods": ["pinv", "dls"],
                                           "mode": "live", "paused": True}, status=201)
        sweep = check("POST", "/api/sweeps", body={"name": "openapi-small", "methods": ["pinv"], "steps": 20,
                                                   "scenarios": [{"generator": "planar_clutter", "count": 1, "seed": 3}],
                                                   "success": {"max_tracking_error": 0.01}}, status=202)
        check("GET", "/api/sweeps", status=200)
        self.assertTrue(rrlab_serve.wait_until(
            lambda: self.call("GET", f"/api/sweeps/{sweep['id']}")[1]["status"] != "running", timeout=120))
        check("GET", "/api/sweeps/{id}", f"/api/sweeps/{sweep['id']}", status=200)
        swept = check("GET", "/api/sweeps/{id}/runs", f"/api/sweeps/{sweep['id']}/runs", status=200)
        # a sweep run stores no frames: its re-simulation compares its summary
        check("POST", "/api/runs/{id}/replay", f"/api/runs/{swept['runs'][0]['run']}/replay", body={"mode": "resimulate"},
              status=200)
        check("POST", "/api/sweeps/validate", body={"name": "openapi-check", "methods": ["pinv"], "steps": 20,
                                                    "scenarios": ["01_planar7_obstacles"],
                                                    "success": {"max_tracking_error": 0.01}}, status=200)
        check("POST", "/api/sweeps/validate", body={"name": "x"}, status=422)
        check("POST", "/api/sweeps/{id}/control", f"/api/sweeps/{sweep['id']}/control", body={"action": "stop"},
              status=200)
        check("POST", "/api/sweeps", body={"name": "x"}, status=422)
        self.assertEqual(len({(v, t) for v, t, _ in checked}), 31)  # every documented operation at least once

    def test_the_schemas_refuse_what_the_server_refuses(self):
        # the check above would pass with empty schemas: a few bodies the server answers 400/422
        cases = [
            ("POST", "/api/runs/{id}/joystick", {"linear": [0.05]}),                      # 2 to 3 numbers
            ("POST", "/api/runs/{id}/control", {"action": "jump"}),                       # not an action
            ("POST", "/api/runs", {"method": "dls"}),                                      # no scenario
            ("POST", "/api/runs", {"scenario": "x", "mode": "fast"}),                      # not a mode
            ("POST", "/api/compare", {"scenario": "x", "methods": ["pinv"]}),              # 2 to 8 methods
            ("PUT", "/api/runs/{id}/obstacles/{oid}", {"position": [1, 2], "colour": 1}),  # unknown key
            ("POST", "/api/runs/{id}/obstacles", {"id": "b", "shape": "sphere", "center": [1, 1]}),  # no radius
            ("POST", "/api/scenarios/validate", {"robot": {"kind": "planar", "links": []},
                                                 "task": {"trajectory": {"type": "joystick"}}}),  # no link
        ]
        for verb, template, body in cases:
            with self.subTest(verb=verb, template=template, body=body):
                errors = list(body_validator(self.document, template, verb).iter_errors(body))
                self.assertGreater(len(errors), 0)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: openapi_readme_test.py RRLAB_BINARY")
    BINARY = sys.argv.pop(1)
    unittest.main(verbosity=2)
