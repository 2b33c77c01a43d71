"""README.md and docs/*.md link to nothing outside the repository (ctest
Docs.links): every Markdown link, image and autolink is a relative path to a
file or folder that exists; bare URLs name only this machine's server
(127.0.0.1, localhost, or the placeholders HOST/lab-pc). The README links to
the project's docs."""

import glob
import os
import re
import unittest

SOURCE_DIR = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LOCAL_HOSTS = ("127.0.0.1", "localhost", "[::1]", "HOST", "lab-pc", "lab.example")

INLINE = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s*\[[^\]]+\]:\s*(\S+)", re.M)
AUTOLINK = re.compile(r"<((?:[a-zA-Z][a-zA-Z0-9+.-]*):[^>\s]*)>")
HTML = re.compile(r"(?:href|src)\s*=\s*[\"']([^\"']+)[\"']", re.I)
BARE = re.compile(r"\b(?:https?|ftp)://([^/\s)\"'`>:]+)")


def documents():
    return [os.path.join(SOURCE_DIR, "README.md")] + sorted(glob.glob(os.path.join(SOURCE_DIR, "docs", "*.md")))


class Links(unittest.TestCase):
    def test_links_stay_in_the_repository(self):
        checked = 0
        for path in documents():
            with open(path, encoding="utf-8") as f:
                text = f.read()
            name = os.path.relpath(path, SOURCE_DIR)
            targets = INLINE.findall(text) + REFERENCE.findall(text) + HTML.findall(text)
            for target in targets:
                with self.subTest(document=name, link=target):
                    self.assertIsNone(re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:|^//", target),
                                      f"{name} links outside the repository: {target}")
                    file = target.split("#")[0]
                    if file:
                        resolved = os.path.normpath(os.path.join(os.path.dirname(path), file))
                        self.assertTrue(resolved.startswith(SOURCE_DIR + os.sep), f"{target} leaves the repository")
                        self.assertTrue(os.path.exists(resolved), f"{name}: {target} does not exist")
                    checked += 1
            for target in AUTOLINK.findall(text):
                with self.subTest(document=name, autolink=target):
                    self.fail(f"{name} autolinks {target}")
            for host in BARE.findall(text):
                with self.subTest(document=name, url_host=host):
                    self.assertIn(host, LOCAL_HOSTS, f"{name} names a URL outside this machine: {host}")
        self.assertGreaterEqual(checked, 3)

    def test_readme_links_the_projects_docs(self):
        with open(os.path.join(SOURCE_DIR, "README.md"), encoding="utf-8") as f:
            targets = set(INLINE.findall(f.read()))
        for doc in ("docs/architecture.md", "docs/scenario-format.md", "docs/scenario.schema.json",
                    "docs/python.md", "python/rrlab/client.py"):
            self.assertIn(doc, targets)


if __name__ == "__main__":
    unittest.main(verbosity=2)
