#!/usr/bin/python3
"""Tests of run_commands.py on made-up pages: it runs sh, console and python blocks from the
page's own folder, lists the blocks marked not run with their reasons, and fails on a failing
command, a missing --out, a write into the checkout, a python block neither runnable nor marked
and a marker without a reason.
"""
import pathlib
import subprocess
import sys
import tempfile
import unittest

HERE = pathlib.Path(__file__).resolve().parent


def write(root, name, text):
    path = pathlib.Path(root) / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)


def run(root):
    for d in ("bin", "python", "cache"):
        (pathlib.Path(root) / "fake-build" / d).mkdir(parents=True, exist_ok=True)
    return subprocess.run([sys.executable, str(HERE / "run_commands.py"), root, f"{root}/fake-build/bin",
                           f"{root}/fake-build/python", f"{root}/fake-build/cache"],
                          capture_output=True, text=True, timeout=60)


GOOD = """# A

```sh
cat data/input.txt > copy.txt   # reads through the link to the checkout's data/
test -s copy.txt
```

```console
$ echo hello > out.txt
hello is not run: output
$ cat out.txt
hello
```

```python
# PYTHONPATH=build/python python3
import os
path = "/tmp/contactlab-x.txt"
assert path.startswith(os.getcwd() + "/"), path   # moved into the page's folder
open(path, "w").write("x")
```

<!-- not run: needs a haptic device -->
```sh
contactlab session scene.yaml --device spacenav
```

```yaml
not: run
```
"""


class RunCommands(unittest.TestCase):
    def test_runnable_pages_pass_and_list_what_is_not_run(self):
        with tempfile.TemporaryDirectory() as root:
            write(root, "README.md", "# R\n")
            write(root, "data/input.txt", "x\n")
            write(root, "docs/a.md", GOOD)
            p = run(root)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            self.assertIn("not run  docs/a.md:24: needs a haptic device", p.stdout)
            self.assertIn("ok", p.stdout)
            self.assertIn("echo hello > out.txt", p.stdout)
            self.assertNotIn("hello is not run", p.stdout)

    def test_each_problem_fails_naming_file_and_line(self):
        cases = {
            "```sh\nfalse\n```\n": "docs/a.md:1: `false` failed (exit 1)",
            "```sh\ntrue --out missing.html\n```\n": "docs/a.md:1: `true --out missing.html` did not write its --out missing.html",
            "```sh\necho x > data/new.txt\n```\n": "the commands wrote into the checkout: data/new.txt",
            "```python\nprint(1)\n```\n": "docs/a.md:1: a python block that is neither a program",
            "<!-- not run: -->\n```sh\ntrue\n```\n": "docs/a.md:2: a 'not run' marker without a reason",
        }
        for page, message in cases.items():
            with self.subTest(page=page), tempfile.TemporaryDirectory() as root:
                write(root, "README.md", "# R\n")
                write(root, "data/input.txt", "x\n")
                write(root, "docs/a.md", page)
                p = run(root)
                self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
                self.assertIn(message, p.stderr)


if __name__ == "__main__":
    unittest.main()
