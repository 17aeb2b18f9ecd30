#!/usr/bin/python3
"""Tests of the documentation checks on small made-up sites: check_links.py finds a missing page,
a missing anchor and a missing image, and accepts what mkdocs would link; mkdocs_build.py fails
on a link to a missing page (when an mkdocs program is given).

Usage: check_links_test.py [MKDOCS]
"""
import os
import pathlib
import subprocess
import sys
import tempfile
import unittest

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import check_links  # noqa: E402

MKDOCS = None


def write(root, name, text):
    path = pathlib.Path(root) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


class CheckLinks(unittest.TestCase):
    def site(self, root, page_b):
        write(root, "README.md", "# Title\n\nSee [B](docs/b.md#the-section) and [A](docs/a.md).\n")
        write(root, "docs/a.md", "# A\n\n## Results: `pointshell`, Fig. 10\n\n## Same\n\n## Same\n\n"
              "[b](b.md#the-section) [self](#results-pointshell-fig-10) [second](#same_1) "
              "![fig](figures/f.png) [web](https://example.org/x#y)\n\n"
              "```sh\ncat [x](missing.md)\n```\n\nInline `[x](missing.md)` is code.\n")
        write(root, "docs/figures/f.png", "")
        write(root, "docs/b.md", page_b)

    def test_links_that_resolve_pass(self):
        with tempfile.TemporaryDirectory() as root:
            self.site(root, "# B\n\n## The section\n")
            self.assertEqual(check_links.broken_links(root), [])

    def test_a_missing_anchor_is_named_with_file_line_and_the_ids_there_are(self):
        with tempfile.TemporaryDirectory() as root:
            self.site(root, "# B\n\n## Another section\n")
            problems = check_links.broken_links(root)
            self.assertEqual(len(problems), 2, problems)
            self.assertTrue(problems[0].startswith("README.md:3: link docs/b.md#the-section: docs/b.md has no heading "
                                                   "with the id 'the-section'"), problems[0])
            self.assertIn("another-section", problems[0])
            self.assertTrue(problems[1].startswith("docs/a.md:9: link b.md#the-section"), problems[1])

    def test_a_missing_page_or_image_is_named(self):
        with tempfile.TemporaryDirectory() as root:
            self.site(root, "# B\n\n## The section\n\n[gone](gone.md) ![img](images/none.png) [anchor](#nowhere)\n")
            problems = check_links.broken_links(root)
            self.assertEqual(problems, [
                "docs/b.md:5: link gone.md: gone.md does not exist",
                "docs/b.md:5: link images/none.png: images/none.png does not exist",
                "docs/b.md:5: link #nowhere: docs/b.md has no heading with the id 'nowhere' (its ids: b, the-section)",
            ])

    def test_the_command_line_exits_1_listing_each_broken_link(self):
        with tempfile.TemporaryDirectory() as root:
            self.site(root, "# B\n")
            p = subprocess.run([sys.executable, str(HERE / "check_links.py"), root], capture_output=True, text=True)
            self.assertEqual(p.returncode, 1)
            self.assertIn("2 broken link(s)", p.stderr)


@unittest.skipUnless(MKDOCS or len(sys.argv) > 1, "no mkdocs program given")
class MkdocsStrict(unittest.TestCase):
    def test_a_link_to_a_missing_page_fails_the_build(self):
        with tempfile.TemporaryDirectory() as root:
            write(root, "mkdocs.yml", "site_name: t\ntheme:\n  name: material\n  font: false\nnav:\n  - A: a.md\n")
            write(root, "docs/a.md", "# A\n\n[missing](missing.md)\n")
            p = subprocess.run([sys.executable, str(HERE / "mkdocs_build.py"), MKDOCS, root],
                               capture_output=True, text=True, timeout=120)
            self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
            self.assertIn("missing.md", p.stderr)
            write(root, "docs/a.md", "# A\n")
            p = subprocess.run([sys.executable, str(HERE / "mkdocs_build.py"), MKDOCS, root],
                               capture_output=True, text=True, timeout=120)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        MKDOCS = sys.argv.pop(1)
    unittest.main()
