"""docs/methods.md against the code (ctest Docs.methods): runs `rrlab methods`
(the binary's path is the first argument) and checks that the page has a
section `## \\`NAME\\` — ...` for every method, and that the section's
parameter table (header `| parameter | unit | range | default | meaning |`)
has one row per parameter with the unit, the range and the default value
the binary prints:

    | `name` | unit or — | [min, max] or one of: `a`, `b` | default (a number, or `label`) | meaning |

It also checks that every diagnostic name a method's source file declares
literally (`declare_diagnostic("name")` in engine/methods/NAME.cpp) is named
in the section's diagnostics table (header `| diagnostic | meaning |`).
A missing or wrong row fails with the row as it should read."""

import json
import math
import os
import re
import subprocess
import sys
import unittest

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOC = os.path.join(SOURCE_DIR, "docs", "methods.md")
BINARY = None  # set from the command line

SECTION = re.compile(r"^## `([A-Za-z0-9_]+)`", re.M)
DECLARED = re.compile(r"declare_diagnostic\(\s*\"([A-Za-z0-9_]+)\"\s*\)")
RANGE = re.compile(r"^\[\s*([^,\]]+?)\s*,\s*([^\]]+?)\s*\]$")
NO_UNIT = "—"


def number(value):
    """A spec value as the doc writes it: 0.05, 200, 1e6, 1e-9."""
    value = float(value)
    if value == int(value):
        digits = str(int(abs(value)))
        if abs(value) >= 1e5 and digits.rstrip("0") == "1":
            return f"{'-' if value < 0 else ''}1e{len(digits) - 1}"  # 1e6, not 1000000
        return str(int(value))  # 200, 1048575
    text = repr(value)
    if "e" in text:
        mantissa, exponent = text.split("e")
        mantissa = mantissa[:-2] if mantissa.endswith(".0") else mantissa
        return f"{mantissa}e{int(exponent)}"
    return text


def expected_cells(spec):
    unit = spec["unit"] or NO_UNIT
    if spec.get("choices"):
        span = "one of: " + ", ".join(f"`{c}`" for c in spec["choices"])
        default = f"`{spec['choices'][int(spec['default'])]}`"
    else:
        span = f"[{number(spec['min'])}, {number(spec['max'])}]"
        default = number(spec["default"])
    return unit, span, default


def expected_row(spec):
    unit, span, default = expected_cells(spec)
    meaning = spec["help"].replace("|", "\\|")
    return f"| `{spec['name']}` | {unit} | {span} | {default} | {meaning} |"


def cells(line):
    """The cells of a Markdown table row (escaped pipes stay inside a cell)."""
    parts = re.split(r"(?<!\\)\|", line.strip())
    return [p.strip() for p in parts[1:-1]]


def tables(text):
    """Every table of a section: (header cells, [(line, cells) of its rows])."""
    found, block = [], []
    for line in text.splitlines() + [""]:
        if line.lstrip().startswith("|"):
            block.append(line)
            continue
        if len(block) >= 2:
            rows = [(row, cells(row)) for row in block[2:]]
            found.append(([c.lower() for c in cells(block[0])], rows))
        block = []
    return found


def sections(text):
    """Method name → the text of its section (up to the next `## ` heading)."""
    result = {}
    heads = list(SECTION.finditer(text))
    for head in heads:
        end = text.find("\n## ", head.end())
        result[head.group(1)] = text[head.start(): end if end >= 0 else len(text)]
    return result


def same_number(text, value):
    try:
        parsed = float(text)
    except ValueError:
        return False
    return math.isclose(parsed, float(value), rel_tol=1e-9, abs_tol=0.0)


class MethodsDoc(unittest.TestCase):
    longMessage = False  # the messages below say it all

    @classmethod
    def setUpClass(cls):
        if not BINARY:
            raise unittest.SkipTest("usage: methods_test.py PATH/TO/rrlab")
        out = subprocess.run([BINARY, "methods"], capture_output=True, text=True, timeout=60)
        if out.returncode != 0:
            raise AssertionError(f"`{BINARY} methods` exited {out.returncode}: {out.stderr}")
        cls.methods = json.loads(out.stdout)
        with open(DOC, encoding="utf-8") as f:
            cls.sections = sections(f.read())

    def test_every_method_has_a_section(self):
        self.assertEqual(len(self.methods), 14)  # 11 when written; 14 with the modern baselines (issue 40)
        names = [m["name"] for m in self.methods]
        for name in names:
            with self.subTest(method=name):
                self.assertTrue(name in self.sections,
                              f"docs/methods.md: no section for method {name} (a heading '## `{name}` — ...')")
        for name in self.sections:
            with self.subTest(section=name):
                self.assertTrue(name in names, f"docs/methods.md: section '## `{name}`' but rrlab has no method {name}")

    def parameter_table(self, name):
        found = [rows for header, rows in tables(self.sections[name]) if header and header[0] == "parameter"]
        self.assertEqual(len(found), 1,
                         f"docs/methods.md, section {name}: expected one table with the header "
                         f"'| parameter | unit | range | default | meaning |', found {len(found)}")
        return found[0]

    def test_parameter_rows_match_the_binary(self):
        checked = 0
        for method in self.methods:
            name = method["name"]
            if name not in self.sections:
                continue  # reported by test_every_method_has_a_section
            rows = {}
            for line, row in self.parameter_table(name):
                key = row[0].strip("`") if row else ""
                rows[key] = (line, row)
            specs = {spec["name"]: spec for spec in method["params"]}
            for key, (line, _) in rows.items():
                with self.subTest(method=name, row=key):
                    self.assertTrue(key in specs, f"docs/methods.md, section {name}: row for `{key}`, which "
                                              f"`rrlab methods` does not list (remove it):\n  {line.strip()}")
            for spec in method["params"]:
                with self.subTest(method=name, parameter=spec["name"]):
                    want = expected_row(spec)
                    self.assertTrue(spec["name"] in rows,
                                  f"docs/methods.md, section {name}: no row for parameter `{spec['name']}`; "
                                  f"add (meaning from its help, edit freely):\n  {want}")
                    line, row = rows[spec["name"]]
                    self.assertEqual(len(row), 5, f"docs/methods.md, section {name}: row of `{spec['name']}` "
                                                  f"has {len(row)} cells, not 5:\n  {line.strip()}\nshould read:\n  {want}")
                    unit, span, default = expected_cells(spec)
                    problems = []
                    if row[1] != unit:
                        problems.append(f"unit '{row[1]}' should be '{unit}'")
                    if spec.get("choices"):
                        if row[2] != span:
                            problems.append(f"range '{row[2]}' should be '{span}'")
                        if row[3] != default:
                            problems.append(f"default '{row[3]}' should be '{default}'")
                    else:
                        bounds = RANGE.match(row[2])
                        if not (bounds and same_number(bounds.group(1), spec["min"])
                                and same_number(bounds.group(2), spec["max"])):
                            problems.append(f"range '{row[2]}' should be '{span}'")
                        if not same_number(row[3], spec["default"]):
                            problems.append(f"default '{row[3]}' should be '{default}'")
                    self.assertFalse(problems, f"docs/methods.md, section {name}, row of `{spec['name']}`: "
                                                   f"{'; '.join(problems)}:\n  {line.strip()}\nshould read "
                                                   f"(meaning kept):\n  | `{spec['name']}` | {unit} | {span} | "
                                                   f"{default} | {row[4] if len(row) > 4 else ''} |")
                    checked += 1
        self.assertGreaterEqual(checked, 75)  # 82 parameters when written

    def test_declared_diagnostics_are_named(self):
        checked = 0
        for method in self.methods:
            name = method["name"]
            source = os.path.join(SOURCE_DIR, "engine", "methods", f"{name}.cpp")
            if name not in self.sections or not os.path.exists(source):
                continue
            with open(source, encoding="utf-8") as f:
                declared = DECLARED.findall(f.read())
            named = set()
            for header, rows in tables(self.sections[name]):
                if header and header[0] == "diagnostic":
                    for _, row in rows:
                        named.update(re.findall(r"`([A-Za-z0-9_]+)`", row[0] if row else ""))
            for diagnostic in declared:
                with self.subTest(method=name, diagnostic=diagnostic):
                    self.assertTrue(diagnostic in named,
                                  f"docs/methods.md, section {name}: the diagnostics table "
                                  f"('| diagnostic | meaning |') has no row for `{diagnostic}`, which "
                                  f"engine/methods/{name}.cpp declares; add:\n  | `{diagnostic}` | ... |")
                    checked += 1
        self.assertGreaterEqual(checked, 30)


if __name__ == "__main__":
    if len(sys.argv) > 1 and not sys.argv[1].startswith("-"):
        BINARY = sys.argv.pop(1)
    unittest.main(verbosity=2)
