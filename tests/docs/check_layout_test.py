#!/usr/bin/python3
"""Tests of check_layout.py on small made-up trees: it passes when docs/layout.md names every
folder, fails naming a folder the page leaves out (added, or moved to a new place), in a git
checkout and in a plain folder alike, and ignores what it should (hidden, build and git-ignored
folders, folders deeper than it requires, folders the page names that do not exist).

Usage: check_layout_test.py
"""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import check_layout  # noqa: E402

GIT = shutil.which("git")

PAGE = """# Source layout

Some text, and a block that is not the tree:

```yaml
nowhere/
```

```text
CMakeLists.txt  one build
src/          the library
  util/       errors, parameter tables
              continued/ here, which names no folder
  view/       the viewer
    web/      the page's files
  future/     a folder being made
docs/         this documentation
tests/        the tests
  util/       tests of util
```
"""


def write(root, name, text=""):
    path = pathlib.Path(root) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def make_tree(root):
    write(root, "CMakeLists.txt")
    write(root, "docs/layout.md", PAGE)
    write(root, "src/util/error.h")
    write(root, "src/view/web/viewer.js")
    write(root, "src/view/web/deeper/part.js")      # three levels below src/: not required
    write(root, "tests/util/error_test.cc")
    write(root, ".ci/run")                          # hidden: not required
    write(root, "build-asan/CMakeCache.txt")        # a build folder: not required
    write(root, "results/run-1/cycles.csv")         # ignored by .gitignore: not required
    write(root, ".gitignore", "/build*/\n/results/*\n!/results/README.md\n")


def git(root, *args):
    subprocess.run(["git", "-C", str(root), *args], check=True, capture_output=True,
                   env=dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@t", GIT_COMMITTER_NAME="t",
                            GIT_COMMITTER_EMAIL="t@t"))


def run(root):
    return subprocess.run([sys.executable, str(HERE / "check_layout.py"), str(root)], capture_output=True, text=True)


class NamedFolders(unittest.TestCase):
    def test_the_tree_block_names_folders_by_indentation(self):
        self.assertEqual(check_layout.named_folders(PAGE), {
            "src", "src/util", "src/view", "src/view/web", "src/future", "docs", "tests", "tests/util"})

    def test_a_folder_indented_deeper_than_one_level_is_description_text(self):
        page = "```\nsrc/  a\n      util/  b\n  view/  c\n```\n"
        self.assertEqual(check_layout.named_folders(page), {"src", "src/view"})


class Layout(unittest.TestCase):
    def check_tree(self, use_git):
        with tempfile.TemporaryDirectory(prefix="contactlab-layout-") as root:
            root = pathlib.Path(root)
            make_tree(root)
            if use_git:
                git(root, "init", "-q")
                git(root, "add", "-A")
                git(root, "commit", "-q", "-m", "tree")
            p = run(root)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            self.assertIn("names all 7 folders", p.stdout)

            # A new folder (untracked in git) and a folder one level below a top-level one.
            write(root, "src/newstage/new_stage.h")
            write(root, "docs/images/shot.png")
            p = run(root)
            self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
            self.assertIn("docs/layout.md: the folder docs/images/ is not named", p.stderr)
            self.assertIn("docs/layout.md: the folder src/newstage/ is not named", p.stderr)
            self.assertIn("2 of 9 folders are not named", p.stderr)

            # Named, they pass again.
            page = PAGE.replace("docs/         this documentation\n",
                                "docs/         this documentation\n  images/     screenshots\n")
            page = page.replace("  future/", "  newstage/  a new stage\n  future/")
            write(root, "docs/layout.md", page)
            p = run(root)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)

            # A folder moved under src/view/ is required at its new place.
            (root / "src/view/web").rename(root / "src/view/page")
            if use_git:
                git(root, "add", "-A")
            p = run(root)
            self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
            self.assertIn("the folder src/view/page/ is not named", p.stderr)

    @unittest.skipUnless(GIT, "git is not installed")
    def test_in_a_git_checkout_an_unnamed_folder_fails(self):
        self.check_tree(use_git=True)

    def test_in_a_plain_folder_an_unnamed_folder_fails(self):
        self.check_tree(use_git=False)

    def test_a_missing_page_fails(self):
        with tempfile.TemporaryDirectory(prefix="contactlab-layout-") as root:
            write(root, "src/util/error.h")
            p = run(root)
            self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
            self.assertIn("does not exist", p.stderr)


if __name__ == "__main__":
    unittest.main()
