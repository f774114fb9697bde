#!/usr/bin/env python3
"""Tests scripts/check-doc-links.py on a small tree of Markdown pages written here, then on the
project's own README.md and docs/ (CTest: doc_links).

Run: /usr/bin/python3 tests/scripts/test_check_doc_links.py
"""

import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "check-doc-links.py")


def check(root):
    run = subprocess.run([sys.executable, SCRIPT, root], capture_output=True, text=True)
    return run.returncode, run.stdout


class CheckDocLinks(unittest.TestCase):
    def write_tree(self, root, readme):
        os.makedirs(os.path.join(root, "docs"))
        with open(os.path.join(root, "README.md"), "w", encoding="utf-8") as f:
            f.write(readme)
        with open(os.path.join(root, "docs", "guide.md"), "w", encoding="utf-8") as f:
            f.write("# Guide\n\n## The YuMi's pushes at 0.2 m/s (session 28)\n\n## Results\n\n"
                    "## Results\n\n```\n## Not a heading\n```\n")

    def test_links_to_existing_headings_pass(self):
        with tempfile.TemporaryDirectory() as root:
            self.write_tree(root, "[a](docs/guide.md#the-yumis-pushes-at-02-ms-session-28)\n"
                                  "[b](docs/guide.md#results-1) [c](https://example.org/#x)\n"
                                  "`[not a link](nowhere.md)`\n")
            code, out = check(root)
            self.assertEqual(code, 0, out)
            self.assertIn("0 broken link(s)", out)

    def test_a_missing_heading_or_file_is_named_with_its_line(self):
        with tempfile.TemporaryDirectory() as root:
            self.write_tree(root, "intro\n[a](docs/guide.md#not-a-heading-1)\n"
                                  "[b](docs/guide.md#results-2)\n[c](docs/missing.md)\n"
                                  "[d](docs/guide.md#not-a-heading)\n")
            code, out = check(root)
            self.assertEqual(code, 1, out)
            self.assertIn("README.md:2: (docs/guide.md#not-a-heading-1)", out)
            self.assertIn("README.md:3: (docs/guide.md#results-2)", out)
            self.assertIn("README.md:4: (docs/missing.md): no file", out)
            self.assertIn("README.md:5:", out)  # the heading inside a code block does not count
            self.assertIn("4 broken link(s)", out)

    def test_the_projects_pages_have_no_broken_link(self):
        code, out = check(ROOT)
        self.assertEqual(code, 0, out)


if __name__ == "__main__":
    unittest.main()
