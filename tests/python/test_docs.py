"""docs/python.md's Python blocks run as written, in order, from the source
directory (the page's examples cannot drift from the package)."""
import os
import re

from conftest import SOURCE_DIR


def test_the_python_blocks_of_the_docs_run_as_written(monkeypatch):
    with open(os.path.join(SOURCE_DIR, "docs", "python.md"), encoding="utf-8") as f:
        blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
    assert len(blocks) >= 2
    monkeypatch.chdir(SOURCE_DIR)
    namespace = {}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), namespace)
    assert namespace["res"]["method"] == "my_pinv"  # the last block's run


def test_the_readmes_engine_block_runs_as_written(monkeypatch):
    with open(os.path.join(SOURCE_DIR, "README.md"), encoding="utf-8") as f:
        text = f.read()
    start = text.index("```python", text.index("The engine itself runs in Python")) + len("```python")
    monkeypatch.chdir(SOURCE_DIR)
    namespace = {}
    exec(compile(text[start:text.index("```", start)], "README.md", "exec"), namespace)
    assert namespace["res"]["method"] == "MyPinv" and namespace["res"]["frames"]["q"].shape == (800, 7)
