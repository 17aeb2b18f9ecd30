#!/usr/bin/python3
"""Every relative link of README.md and docs/**/*.md points to a file that exists and, when it
names an anchor (page.md#anchor or #anchor), to a heading of that page.

mkdocs --strict reports links to missing pages but not missing anchors; this check covers both,
and README.md, which is not part of the site. Anchors are the heading ids mkdocs makes (the
Markdown toc extension's slugify, duplicates numbered _1, _2, ...).

Usage: check_links.py ROOT     exit 0 when every link resolves, 1 listing each broken one.
"""
import pathlib
import re
import sys

from markdown.extensions.toc import slugify, unique

FENCE = re.compile(r"^\s*(```|~~~)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
INLINE_CODE = re.compile(r"`[^`]*`")
# [text](target) and ![alt](target); target up to the first space or closing parenthesis.
LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")


def prose_lines(text):
    """(line number, line) of the lines outside fenced code blocks."""
    fenced = False
    for number, line in enumerate(text.split("\n"), 1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            yield number, line


def heading_ids(path):
    """The ids mkdocs gives the headings of a Markdown file."""
    ids = set()
    for _, line in prose_lines(path.read_text(encoding="utf-8")):
        m = HEADING.match(line)
        if m:
            text = INLINE_CODE.sub(lambda c: c.group(0)[1:-1], m.group(2))
            text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)  # a link's text only
            ids.add(unique(slugify(text, "-"), ids))
    return ids


def markdown_files(root):
    files = [root / "README.md"] if (root / "README.md").exists() else []
    return files + sorted((root / "docs").rglob("*.md"))


def broken_links(root):
    """One message per broken link: 'FILE:LINE: link TARGET: what is wrong'."""
    root = pathlib.Path(root).resolve()
    ids_of = {}
    problems = []
    for path in markdown_files(root):
        for number, line in prose_lines(path.read_text(encoding="utf-8")):
            for m in LINK.finditer(INLINE_CODE.sub("", line)):
                target = m.group(1)
                if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # http:, https:, mailto:
                    continue
                where = f"{path.relative_to(root)}:{number}: link {target}"
                file_part, _, anchor = target.partition("#")
                linked = (path.parent / file_part).resolve() if file_part else path
                if not linked.exists():
                    problems.append(f"{where}: {file_part} does not exist")
                    continue
                if anchor:
                    if linked.suffix != ".md":
                        problems.append(f"{where}: an anchor into {file_part}, which is not a Markdown page")
                        continue
                    if linked not in ids_of:
                        ids_of[linked] = heading_ids(linked)
                    if anchor not in ids_of[linked]:
                        problems.append(f"{where}: {linked.relative_to(root)} has no heading with the id "
                                        f"'{anchor}' (its ids: {', '.join(sorted(ids_of[linked]))})")
    return problems


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().split("\n")[-1], file=sys.stderr)
        return 2
    problems = broken_links(argv[1])
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_links: {len(problems)} broken link(s)", file=sys.stderr)
        return 1
    print(f"check_links: every link of README.md and docs/ resolves ({len(markdown_files(pathlib.Path(argv[1])))} files)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
