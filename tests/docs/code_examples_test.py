#!/usr/bin/env python3
"""The C++ in the docs is the code: every ```cpp block of docs/*.md is either
compiled (a translation unit against the engine's headers) or an excerpt whose
every line is in the file it names. The marker on the line before a block
says which:

  <!-- compiled -->                                   the block is a translation unit
  <!-- compiled with the block above, as: TEXT -->    TEXT with BLOCK replaced by the block,
                                                      appended to the block above's unit
  <!-- excerpt of PATH -->                            each line (stripped) is a line of PATH

A block without a marker fails the test.

usage: code_examples_test.py SOURCE_DIR BUILD_DIR CXX"""
import glob
import os
import re
import subprocess
import sys
import tempfile

source, build, cxx = sys.argv[1:4]
MARKER = re.compile(r"<!--\s*(compiled|compiled with the block above, as:(.*)|excerpt of (\S+))\s*-->")
flags = ["-std=c++20", "-fsyntax-only", "-I", os.path.join(build, "include", "rrlab_engine"),
         "-I", "/usr/include/eigen3"]


def blocks(path):
    """(marker or None, code, line) of every ```cpp block."""
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].strip() == "```cpp":
            indent = lines[i][: len(lines[i]) - len(lines[i].lstrip())]
            j = i + 1
            while lines[j].strip() != "```":
                j += 1
            code = "\n".join(l[len(indent):] if l.startswith(indent) else l.lstrip() for l in lines[i + 1:j])
            k = i - 1
            while k >= 0 and not lines[k].strip():
                k -= 1
            m = MARKER.search(lines[k]) if k >= 0 else None
            yield m, code, i + 1
            i = j
        i += 1


def compile_unit(code, where):
    with tempfile.NamedTemporaryFile("w", suffix=".cpp", delete=False) as f:
        f.write(code)
    try:
        p = subprocess.run([cxx, *flags, f.name], capture_output=True, text=True)
    finally:
        os.unlink(f.name)
    if p.returncode != 0:
        return f"{where}: does not compile:\n{p.stderr[-3000:]}"
    return None


def main():
    problems, compiled, excerpts = [], 0, 0
    for path in sorted(glob.glob(os.path.join(source, "docs", "*.md"))):
        name = os.path.relpath(path, source)
        unit = None
        for m, code, line in blocks(path):
            where = f"{name}:{line}"
            if m is None:
                problems.append(f"{where}: a ```cpp block without a marker (compiled or excerpt)")
            elif m.group(3):
                target = os.path.join(source, m.group(3))
                have = {l.strip() for l in open(target, encoding="utf-8")}
                for l in code.split("\n"):
                    if l.strip() and l.strip() not in have:
                        problems.append(f"{where}: not in {m.group(3)}: {l.strip()}")
                excerpts += 1
            elif m.group(2) is not None:
                if unit is None:
                    problems.append(f"{where}: 'with the block above' but no compiled block above")
                    continue
                unit += "\n" + m.group(2).strip().replace("\\n", "\n").replace("BLOCK", code) + "\n"
                problem = compile_unit(unit, where)
                compiled += 1
                if problem:
                    problems.append(problem)
            else:
                unit = code
                problem = compile_unit(unit, where)
                compiled += 1
                if problem:
                    problems.append(problem)
    print(f"{compiled} blocks compiled, {excerpts} excerpts checked")
    for p in problems:
        print("FAIL", p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
