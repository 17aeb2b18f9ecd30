#!/usr/bin/python3
"""Builds the documentation site with `mkdocs build --strict` into a temporary folder (never into
the source tree) and checks what it made: a page for every entry of mkdocs.yml's nav, and no
script, stylesheet or font loaded from another host (the site must work offline).

Usage: mkdocs_build.py MKDOCS ROOT
"""
import pathlib
import re
import subprocess
import sys
import tempfile

import yaml

EXTERNAL = re.compile(r"<(script|img)\b[^>]*\bsrc=\"(https?:)?//[^\"]*\"|<link\b[^>]*\bhref=\"(https?:)?//[^\"]*\"[^>]*>")


def nav_pages(nav):
    for entry in nav:
        value = next(iter(entry.values())) if isinstance(entry, dict) else entry
        if isinstance(value, list):
            yield from nav_pages(value)
        else:
            yield value


def main(mkdocs, root):
    root = pathlib.Path(root)
    config = root / "mkdocs.yml"
    with tempfile.TemporaryDirectory(prefix="contactlab-site-") as site:
        p = subprocess.run([mkdocs, "build", "--strict", "--config-file", str(config), "--site-dir", site],
                           capture_output=True, text=True, timeout=240)
        sys.stdout.write(p.stdout)
        sys.stderr.write(p.stderr)
        if p.returncode != 0:
            print(f"mkdocs_build: `mkdocs build --strict` of {config} failed (exit {p.returncode}); "
                  "the WARNING lines above name each broken link or page", file=sys.stderr)
            return 1
        problems = []
        # mkdocs' own loader understands its !! tags; the nav needs only plain YAML.
        nav = yaml.safe_load(config.read_text())["nav"]
        for page in nav_pages(nav):
            stem = re.sub(r"\.md$", "", page)
            built = [pathlib.Path(site) / (stem + ".html"), pathlib.Path(site) / stem / "index.html"]
            if not any(html.exists() for html in built):  # use_directory_urls false, or true
                problems.append(f"{config}: nav page {page} was not built ({stem}.html missing)")
        for html in sorted(pathlib.Path(site).rglob("*.html")):
            for m in EXTERNAL.finditer(html.read_text(encoding="utf-8")):
                if m.group(0).startswith("<link") and "stylesheet" not in m.group(0) and "preconnect" not in m.group(0):
                    continue  # a plain hyperlink target such as rel="canonical"
                problems.append(f"{html.relative_to(site)}: loads from another host: {m.group(0)[:160]}")
        for line in problems:
            print(line, file=sys.stderr)
        if problems:
            return 1
        print(f"mkdocs_build: built {sum(1 for _ in nav_pages(nav))} nav pages strictly, nothing loaded from another host")
        return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__.strip().split("\n")[-1], file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
