"""The README's REST examples against the OpenAPI document a live server
serves (ctest Python.openapi_readme): every curl line's verb and path is a
documented operation, and every JSON body it sends is valid against that
operation's request schema (JSON Schema 2020-12, python3-jsonschema). The
examples are the fenced block between <!-- api-examples --> and
<!-- /api-examples --> in README.md (tests/server/readme_examples_test.cpp runs
the same block against a server).

Usage: openapi_readme_test.py RRLAB_BINARY"""

import json
import os
import re
import shlex
import sys
import unittest
import urllib.request

import jsonschema  # Debian: python3-jsonschema (required: CI installs it)

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(SOURCE_DIR, "tests", "support"))
import rrlab_serve  # noqa: E402

BINARY = None


def readme_examples():
    with open(os.path.join(SOURCE_DIR, "README.md"), encoding="utf-8") as f:
        text = f.read()
    block = text[text.index("<!-- api-examples -->"):text.index("<!-- /api-examples -->")]
    block = block[block.index("```sh") + 5:block.rindex("```")]
    return [line for line in block.splitlines() if "curl " in line]


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


class ReadmeAgainstOpenApi(unittest.TestCase):
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

    def test_every_readme_curl_is_a_documented_operation_with_a_valid_body(self):
        lines = readme_examples()
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
