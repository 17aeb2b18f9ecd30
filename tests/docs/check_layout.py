#!/usr/bin/python3
"""Checks that docs/layout.md names every folder of the source tree, so the page cannot fall
behind when a folder is added or moved.

The folders checked are those of the tree as it is when the test runs: with git, every folder
holding a tracked file or an untracked file that is not ignored (so build*/, the runs under
results/ and caches never count); without git (a source archive), every folder on disk but
hidden ones, build*/, __pycache__/ and what the top-level .gitignore names. Required are the
top-level folders, every folder one level below them, and, under src/ and baselines/, two levels
below (src/view/web). Hidden folders (.ci/) are not required.

The page names a folder in its tree, a fenced block without a language tag (or `text`): one
folder a line, its name ending in "/", indented two spaces per level below its parent; text
indented further than that continues the description above. Folders the page names that do not
exist (yet) are allowed: the page may describe a layout being made.

Usage: check_layout.py ROOT [--list]
  --list  print the folders required and the folders the page names, then check
"""
import fnmatch
import os
import pathlib
import re
import subprocess
import sys

PAGE = "docs/layout.md"
DEEPER = {"src", "baselines"}  # top-level folders whose grandchildren are required too
FENCE = re.compile(r"^```\s*([\w+-]*)\s*$")
ENTRY = re.compile(r"^( *)([\w.+-]+/)(\s|$)")
SKIP_ON_DISK = re.compile(r"^(\..*|build.*|__pycache__)$")


def required_depth(parts):
    """Whether the folder with path components PARTS must be named."""
    if not parts or parts[0].startswith("."):
        return False
    if len(parts) <= 2:
        return True
    return len(parts) == 3 and parts[0] in DEEPER


def files_of(root):
    """The files of ROOT relative to it: git's view (tracked, or untracked and not ignored) when
    ROOT is the top of a git work tree, else every file on disk outside hidden and build folders."""
    try:
        top = subprocess.run(["git", "-C", str(root), "rev-parse", "--show-toplevel"],
                             capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        top = None
    if top is not None and top.returncode == 0 and pathlib.Path(top.stdout.strip()).resolve() == root.resolve():
        listed = subprocess.run(["git", "-C", str(root), "ls-files", "-z", "--cached", "--others",
                                 "--exclude-standard"], capture_output=True, text=True, check=True, timeout=60)
        # A file deleted from the work tree but still in the index does not keep its folder.
        return [f for f in listed.stdout.split("\0") if f and (root / f).exists()]
    ignored = ignore_patterns(root)
    files = []
    for dirpath, dirnames, filenames in os.walk(root):
        rel = pathlib.PurePosixPath(pathlib.Path(dirpath).relative_to(root).as_posix())
        dirnames[:] = sorted(d for d in dirnames
                             if not SKIP_ON_DISK.match(d) and not is_ignored(str(rel / d), ignored))
        files.extend(str(rel / f) for f in filenames)
    return files


def ignore_patterns(root):
    """The folder patterns of ROOT's .gitignore (negations and comments left out)."""
    path = root / ".gitignore"
    if not path.exists():
        return []
    lines = (line.strip() for line in path.read_text(encoding="utf-8").split("\n"))
    return [line.rstrip("/") for line in lines if line and not line.startswith(("#", "!"))]


def is_ignored(folder, patterns):
    """Whether FOLDER ('a/b', relative to the root) matches one of PATTERNS as git would: an
    anchored pattern ('/results/*') against the whole path, any other against the folder's name."""
    name = folder.rsplit("/", 1)[-1]
    for p in patterns:
        if p.startswith("/") or "/" in p:
            if fnmatch.fnmatchcase(folder, p.lstrip("/")):
                return True
        elif fnmatch.fnmatchcase(name, p):
            return True
    return False


def folders_of(root):
    """The folders of ROOT's tree that the page must name, as 'a/b' paths, sorted."""
    folders = set()
    for f in files_of(root):
        parts = pathlib.PurePosixPath(f).parts[:-1]
        for n in range(1, len(parts) + 1):
            if required_depth(parts[:n]):
                folders.add("/".join(parts[:n]))
    return sorted(folders)


def named_folders(page_text):
    """The folders the page's tree blocks name, as 'a/b' paths."""
    named = set()
    lines = page_text.split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        tag = m.group(1).lower()
        i += 1
        stack = []  # (indent, name) of the entries above the current line
        while i < len(lines) and not lines[i].startswith("```"):
            e = ENTRY.match(lines[i]) if tag in ("", "text") else None
            if e:
                indent = len(e.group(1))
                limit = stack[-1][0] + 2 if stack else 0
                if indent % 2 == 0 and indent <= limit:
                    while stack and stack[-1][0] >= indent:
                        stack.pop()
                    stack.append((indent, e.group(2).rstrip("/")))
                    named.add("/".join(name for _, name in stack))
            i += 1
        i += 1
    return named


def unnamed(root):
    """(required folders, folders the page names, required folders it does not name)."""
    required = folders_of(root)
    page = root / PAGE
    named = named_folders(page.read_text(encoding="utf-8")) if page.exists() else set()
    return required, named, [f for f in required if f not in named]


def main(argv):
    if len(argv) not in (2, 3) or (len(argv) == 3 and argv[2] != "--list"):
        print(__doc__.strip().split("\n")[-2], file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1])
    if not (root / PAGE).exists():
        print(f"check_layout: {root / PAGE} does not exist", file=sys.stderr)
        return 1
    required, named, missing = unnamed(root)
    if len(argv) == 3:
        print("required:\n  " + "\n  ".join(required))
        print("named in the page:\n  " + "\n  ".join(sorted(named)))
    if not required:
        print(f"check_layout: found no folders under {root}; wrong ROOT?", file=sys.stderr)
        return 1
    for f in missing:
        print(f"{PAGE}: the folder {f}/ is not named; add a line '{f.split('/')[-1]}/  what it holds' "
              f"under {'/'.join(f.split('/')[:-1]) + '/' if '/' in f else 'the top level'} in the page's tree",
              file=sys.stderr)
    if missing:
        print(f"check_layout: {len(missing)} of {len(required)} folders are not named in {PAGE}", file=sys.stderr)
        return 1
    print(f"check_layout: {PAGE} names all {len(required)} folders of the tree "
          f"({len(named - set(required))} more that do not exist yet or are not required)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
