#!/usr/bin/python3
"""Runs every command the documentation shows (README.md, docs/**/*.md), so that none goes stale.

Convention (also in docs/index.md, "Commands in these pages"):
- A fenced block tagged sh, bash or shell holds commands: every line that is not blank or a
  comment (a line ending in a backslash continues on the next). A block tagged console holds a
  transcript: the lines starting with "$ " are the commands, the rest is output.
- A block tagged python whose first line is "# PYTHONPATH=build/python python3" is a program,
  run as one.
- Any other block (no tag, text, yaml, cpp, cmake, ...) is output or a file's content, not run.
- A block that must not run here says why on the line right before it:
  <!-- not run: REASON -->  (needs a haptic device, a cluster, installs outside the build, ...).
  Every such block is listed with its reason; a marker without a reason, or a python block that
  is neither a program nor marked, is an error.

Each page's blocks run in order, each command through bash, in a fresh folder per page that
holds links to the checkout's data/, experiments/, scripts/ and examples/ and a build/ with the
build's bin/ and python/, so the commands run as written from the project's root and what they
write stays in that folder. Long runs are shortened, printed beside the command: `contactlab
run` (without --slurm) runs 0.2 s of trajectory, `contactlab session` 0.5 s of
session, and /tmp/contactlab-* folders move into the page's folder. A command fails the test
when it exits non-zero, an `--out PATH` it names is not there afterwards, or it wrote into the
checkout's data/, experiments/, scripts/ or examples/.

Usage: run_commands.py ROOT BIN_DIR PYTHON_DIR CACHE_DIR [--list]
"""
import os
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile
import time

RUN_TAGS = {"sh", "bash", "shell", "console"}
PYTHON_HEADER = "# PYTHONPATH=build/python python3"
NOT_RUN = re.compile(r"^<!--\s*not run:(.*?)-->\s*$")
FENCE = re.compile(r"^```\s*([\w+-]*)\s*$")
LINKED = ["data", "experiments", "scripts", "examples"]
TIMEOUT = 150


class Block:
    def __init__(self, path, line, tag, text, skip_reason):
        self.path, self.line, self.tag, self.text, self.skip_reason = path, line, tag, text, skip_reason

    def where(self, root):
        return f"{self.path.relative_to(root)}:{self.line}"


def blocks_of(path):
    """The fenced blocks of a Markdown file, each with the reason of a not-run marker before it."""
    lines = path.read_text(encoding="utf-8").split("\n")
    out, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        start, tag = i, m.group(1).lower()
        j = i + 1
        while j < len(lines) and not lines[j].startswith("```"):
            j += 1
        reason = None
        if start > 0:
            mm = NOT_RUN.match(lines[start - 1].strip())
            if mm:
                reason = mm.group(1).strip()
        out.append(Block(path, start + 1, tag, "\n".join(lines[start + 1:j]), reason))
        i = j + 1
    return out


def commands_of(block):
    """The commands of a sh/bash/console block, continuation lines joined."""
    cmds, current = [], None
    for raw in block.text.split("\n"):
        line = raw.rstrip()
        if current is not None:
            current += "\n" + line
        elif block.tag == "console":
            if not line.startswith("$ "):
                continue
            current = line[2:]
        else:
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            current = line
        if not current.endswith("\\"):
            cmds.append(current)
            current = None
    if current is not None:
        cmds.append(current)
    return cmds


def shortened(cmd, workdir):
    """The command as run, with the quick settings of long runs; and what was changed."""
    notes = []
    try:
        words = shlex.split(cmd, comments=True)
    except ValueError:
        words = []
    prog = words[0] if words else ""
    if prog.endswith("contactlab") and len(words) > 1 and words[1] == "run" and "--slurm" not in words:
        cmd = cmd.split(" #")[0].rstrip() + " --set trajectory.duration=0.2"
        notes.append("0.2 s of trajectory")
    if prog.endswith("contactlab") and len(words) > 1 and words[1] == "session":
        if "--duration" in words:
            cmd = re.sub(r"--duration\s+\S+", "--duration 0.5", cmd)
        else:
            cmd = cmd.split(" #")[0].rstrip() + " --duration 0.5"
        notes.append("0.5 s")
    if "/tmp/contactlab-" in cmd:
        cmd = cmd.replace("/tmp/contactlab-", f"{workdir}/tmp-contactlab-")
        notes.append("/tmp/contactlab-* in the page's folder")
    return cmd, notes


def outputs_named(cmd):
    try:
        words = shlex.split(cmd, comments=True)
    except ValueError:
        return []
    return [words[k + 1] for k, w in enumerate(words[:-1]) if w == "--out"]


def snapshot(root):
    files = {}
    for name in LINKED:
        for dirpath, _, filenames in os.walk(root / name):
            for f in filenames:
                p = pathlib.Path(dirpath) / f
                try:
                    st = p.stat()
                except OSError:
                    continue
                files[str(p.relative_to(root))] = (st.st_size, st.st_mtime_ns)
    return files


def workspace(root, bin_dir, python_dir, parent):
    work = pathlib.Path(tempfile.mkdtemp(prefix="page-", dir=parent))
    for name in LINKED:
        if (root / name).exists():
            (work / name).symlink_to(root / name)
    (work / "build").mkdir()
    (work / "build" / "bin").symlink_to(bin_dir)
    (work / "build" / "python").symlink_to(python_dir)
    return work


def main(argv):
    if len(argv) not in (5, 6):
        print(__doc__.strip().split("\n")[-1], file=sys.stderr)
        return 2
    root, bin_dir, python_dir, cache = (pathlib.Path(a).resolve() for a in argv[1:5])
    list_only = len(argv) == 6 and argv[5] == "--list"
    pages = [root / "README.md"] + sorted((root / "docs").rglob("*.md"))
    errors, skipped, to_run = [], [], []
    for page in pages:
        for b in blocks_of(page):
            if b.tag not in RUN_TAGS and b.tag != "python":
                continue
            if b.skip_reason is not None:
                if not b.skip_reason:
                    errors.append(f"{b.where(root)}: a 'not run' marker without a reason")
                else:
                    skipped.append(b)
                continue
            if b.tag == "python" and not b.text.startswith(PYTHON_HEADER):
                errors.append(f"{b.where(root)}: a python block that is neither a program (first line "
                              f"'{PYTHON_HEADER}') nor marked <!-- not run: REASON -->")
                continue
            if b.tag in RUN_TAGS and not commands_of(b):
                errors.append(f"{b.where(root)}: a {b.tag} block with no command")
                continue
            to_run.append(b)
    print(f"run_commands: {len(to_run)} blocks to run, {len(skipped)} not run:")
    for b in skipped:
        print(f"  not run  {b.where(root)}: {b.skip_reason}")
    if list_only:
        for b in to_run:
            print(f"  run      {b.where(root)} ({b.tag})")
        for e in errors:
            print(e, file=sys.stderr)
        return 1 if errors else 0

    env = dict(os.environ)
    # Not the build's bin/: a command must name build/bin/contactlab as a reader types it.
    env["PATH"] = "/usr/bin:/bin:" + env.get("PATH", "")
    env.update(CONTACTLAB_CACHE=str(cache), CONTACTLAB_DATA=str(root / "data"), PYTHONDONTWRITEBYTECODE="1",
               MPLBACKEND="Agg", PYTHONPATH=str(python_dir))
    before = snapshot(root)
    with tempfile.TemporaryDirectory(prefix="contactlab-docs-commands-") as parent:
        works = {}
        for b in to_run:
            if b.path not in works:
                works[b.path] = workspace(root, bin_dir, python_dir, parent)
            work = works[b.path]
            if b.tag == "python":
                program, notes = shortened(b.text, work)
                label, cmd = "python block", ["/usr/bin/python3", "-c", program]
                runs = [(label, cmd, notes, [])]
            else:
                runs = []
                for c in commands_of(b):
                    c2, notes = shortened(c, work)
                    runs.append((c, ["bash", "-e", "-o", "pipefail", "-c", c2], notes, outputs_named(c2)))
            for label, cmd, notes, outs in runs:
                t0 = time.monotonic()
                try:
                    p = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True, timeout=TIMEOUT)
                    rc, out, err = p.returncode, p.stdout, p.stderr
                except subprocess.TimeoutExpired:
                    rc, out, err = "timeout", "", f"did not end within {TIMEOUT} s"
                dt = time.monotonic() - t0
                shown = label.replace("\n", " ")
                print(f"  {'ok' if rc == 0 else 'FAILED'} {dt:6.1f} s  {b.where(root)}: {shown}"
                      + (f"  [{'; '.join(notes)}]" if notes else ""))
                if rc != 0:
                    errors.append(f"{b.where(root)}: `{shown}` failed (exit {rc}):\n{out[-2000:]}{err[-3000:]}")
                    continue
                for o in outs:
                    if not (work / o).exists():
                        errors.append(f"{b.where(root)}: `{shown}` did not write its --out {o}")
    after = snapshot(root)
    changed = sorted(k for k in after if before.get(k) != after[k])
    if changed:
        errors.append("the commands wrote into the checkout: " + ", ".join(changed[:20]))
    for e in errors:
        print(e, file=sys.stderr)
    if errors:
        print(f"run_commands: {len(errors)} problem(s)", file=sys.stderr)
        return 1
    print(f"run_commands: every shown command ran ({len(to_run)} blocks)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
