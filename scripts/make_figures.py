#!/usr/bin/python3
"""Makes every figure of ContactLab's experiments from the files under results/.

Reads only results/<experiment>/{cycles,summary,convergence,field_error,field_slice}.csv (written by
`contactlab run`) and writes PNG figures, with labelled axes and units, and tables (PNG and
Markdown) to results/figures/. A figure whose results are missing is skipped with a note.

The figures live in the package figures/ beside this script, one module per figure (or per
close group), each declaring the experiments it reads; they are found by scanning the package.

Usage: scripts/make_figures.py [--results DIR]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
try:
    import figures  # noqa: E402
    from figures.common import Results  # noqa: E402
except ImportError as e:
    # The figures draw with matplotlib: say which interpreter lacks it and how to get it.
    if not (e.name or "").split(".")[0] == "matplotlib":
        raise
    sys.exit(f"make_figures: {sys.executable} (Python {sys.version_info.major}.{sys.version_info.minor}) cannot "
             f"import matplotlib ({e}); install it for this interpreter (Debian: apt install python3-matplotlib) "
             f"or run the script with an interpreter that has it, e.g. /usr/bin/python3 {sys.argv[0]}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default=os.path.join(os.path.dirname(__file__), "..", "results"))
    args = parser.parse_args()
    results = Results(os.path.abspath(args.results))
    for _, draw in figures.all_figures():
        try:
            if not draw(results):
                print(f"make_figures: {draw.__name__}: no results yet (run {', '.join(draw.experiments)} first)",
                      file=sys.stderr)
        except (KeyError, ValueError) as e:
            print(f"make_figures: {draw.__name__}: results are malformed: {e}", file=sys.stderr)
            return 1
    for path in results.made:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
