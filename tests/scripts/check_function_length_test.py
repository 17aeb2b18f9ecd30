#!/usr/bin/env python3
"""Self-test of scripts/check-function-length.py: it fails on a long function and passes on the
rest, whatever braces sit in strings, characters and comments.

Usage: check_function_length_test.py PATH/TO/check-function-length.py
"""

import pathlib
import subprocess
import sys
import tempfile


def Body(lines):
  """LINES statements, each on its own line."""
  return "".join(f"  x += {i};\n" for i in range(lines))


def Run(checker, root, *args):
  return subprocess.run([sys.executable, checker, "--root", str(root), *args], capture_output=True, text=True)


def main():
  checker = sys.argv[1]
  failures = []

  def Expect(ok, what):
    if not ok:
      failures.append(what)

  with tempfile.TemporaryDirectory() as tmp:
    root = pathlib.Path(tmp)
    (root / "src" / "long").mkdir(parents=True)
    (root / "src" / "fine").mkdir(parents=True)
    # 130 lines from signature to closing brace, braces in literals and comments that must not
    # end it early, inside a namespace and after a class.
    (root / "src" / "long" / "long.cc").write_text(
        "namespace demo {\n"
        "struct Holder { int Get() const { return 1; } };\n"
        "int LongFunction(int x,\n"
        "                 int y = int{2}) {\n"
        "  const char* s = \"}}}\"; char c = '}'; // }}\n"
        "  /* } */ auto f = [&] { return R\"(})\"; };\n"
        + Body(130 - 5) +
        "}\n"
        "}  // namespace demo\n")
    # A registration's lambda at namespace scope is a function too.
    (root / "src" / "long" / "register.cc").write_text(
        "const Registration kCommands([](App& app) {\n" + Body(130 - 2) + "});\n")
    # Exactly 120 lines, a member function with an initializer list, and a class body far
    # longer than 120 lines: none of them is over the limit.
    members = "".join(f"  int m{i} = {i};\n" for i in range(200))
    (root / "src" / "fine" / "fine.h").write_text(
        "class Big {\n"
        " public:\n"
        "  Big() : a_{1}, b_(2) {\n" + Body(120 - 2) + "  }\n"
        + members +
        "  int a_, b_;\n"
        "};\n")

    long_run = Run(checker, root, "src")
    Expect(long_run.returncode == 1, f"expected exit 1 on a 130-line function, got {long_run.returncode}")
    Expect("src/long/long.cc:3: LongFunction 130 lines" in long_run.stdout,
           f"expected the 130-line function to be named, got: {long_run.stdout!r}")
    Expect("src/long/register.cc:1: kCommands lambda 130 lines" in long_run.stdout,
           f"expected the 130-line lambda to be named, got: {long_run.stdout!r}")
    Expect("fine" not in long_run.stdout, f"a function of 120 lines or a class was listed: {long_run.stdout!r}")

    skip_run = Run(checker, root, "--skip", "src/long", "--", "src")
    Expect(skip_run.returncode == 0, f"expected exit 0 with src/long skipped, got {skip_run.returncode}: "
           f"{skip_run.stdout!r}")

    short_run = Run(checker, root, "--max", "130", "src")
    Expect(short_run.returncode == 0, f"expected exit 0 with --max 130, got {short_run.returncode}")

  for f in failures:
    print("FAIL:", f)
  return 1 if failures else 0


if __name__ == "__main__":
  sys.exit(main())
