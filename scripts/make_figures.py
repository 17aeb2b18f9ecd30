#!/usr/bin/python3
"""Makes every figure of ContactLab's experiments from the files under results/.

Reads only results/<experiment>/{cycles,summary,convergence,field_error,field_slice,stability}.csv
and meta.json (written by `contactlab run`) and writes PNG figures, with labelled axes and units,
and tables (PNG and Markdown) to results/figures/. A figure whose results are missing is skipped
with a note.

The figures live in the package figures/ beside this script, one module per figure (or per
close group), each declaring the experiments it reads; they are found by scanning the package.
An experiment no module declares (a config of your own) gets the generic figure of
figures/generic.py: its forces along the trajectory per job and model, and its summary table.

Usage: scripts/make_figures.py [--results DIR] [--only NAME]
  DIR      a folder of experiment folders (default: results/), or one run's folder
           (`contactlab run CONFIG --out DIR`, or Python's contactlab.run(..., out=DIR));
           figures go to DIR/figures/
  NAME     draw only this: a figure (its function name, e.g. closed_loop_rate, or an output's
           file name) or an experiment (its figures, or its generic figure)
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
try:
    import figures  # noqa: E402
    from figures.common import Results  # noqa: E402
    from figures.generic import draw_generic, read_meta  # noqa: E402
except ImportError as e:
    # The figures draw with matplotlib: say which interpreter lacks it and how to get it.
    if not (e.name or "").split(".")[0] == "matplotlib":
        raise
    sys.exit(f"make_figures: {sys.executable} (Python {sys.version_info.major}.{sys.version_info.minor}) cannot "
             f"import matplotlib ({e}); install it for this interpreter (Debian: apt install python3-matplotlib) "
             f"or run the script with an interpreter that has it, e.g. /usr/bin/python3 {sys.argv[0]}")


def experiment_folders(root):
    """{experiment: folder} of the results under ROOT: ROOT itself when it is one run's folder
    (it holds a meta.json), else each sub-folder that holds one (its experiment's name from it,
    or the folder's name)."""
    meta = read_meta(root)
    if meta is not None:
        return {meta.get("experiment") or os.path.basename(os.path.normpath(root)): root}
    found = {}
    for name in sorted(os.listdir(root)) if os.path.isdir(root) else []:
        folder = os.path.join(root, name)
        if os.path.isdir(folder) and name != "figures":
            meta = read_meta(folder)
            if meta is not None:
                found[meta.get("experiment") or name] = folder
    return found


def selected(draw, only):
    if only is None:
        return True
    names = {draw.__name__} | set(draw.outputs) | {os.path.splitext(o)[0] for o in draw.outputs} | set(draw.experiments)
    return only in names


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", help="a folder of experiment folders (default: results/) or one run's folder")
    parser.add_argument("--only", metavar="NAME", help="draw only this figure or experiment")
    args = parser.parse_args()
    if args.results is None:
        root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "results"))
        os.makedirs(root, exist_ok=True)
    else:
        root = os.path.abspath(args.results)
        if not os.path.isdir(root):
            print(f"make_figures: --results {args.results}: no such folder", file=sys.stderr)
            return 1
    try:
        folders = experiment_folders(root)
    except ValueError as e:
        print(f"make_figures: {e}", file=sys.stderr)
        return 1
    results = Results(root, folders)
    declared = figures.all_figures()
    if read_meta(root) is not None:  # one run's folder: only the figures of its experiment
        declared = [(m, d) for m, d in declared if set(d.experiments) & set(folders)]
    claimed = {e for _, draw in declared for e in draw.experiments}
    unclaimed = [e for e in folders if e not in claimed]
    if args.only is not None and not any(selected(d, args.only) for _, d in declared) and args.only not in unclaimed:
        names = sorted({d.__name__ for _, d in declared} | set(unclaimed))
        print(f"make_figures: --only {args.only}: no such figure or experiment here; figures: {', '.join(names)}",
              file=sys.stderr)
        return 1
    for _, draw in declared:
        if not selected(draw, args.only):
            continue
        try:
            if not draw(results):
                print(f"make_figures: {draw.__name__}: no results yet (run {', '.join(draw.experiments)} first)",
                      file=sys.stderr)
        except (KeyError, ValueError) as e:
            print(f"make_figures: {draw.__name__}: results are malformed: {e}", file=sys.stderr)
            return 1
    for experiment in unclaimed:
        if args.only not in (None, experiment):
            continue
        try:
            if draw_generic(results, experiment) == 0:
                print(f"make_figures: {experiment}: {folders[experiment]} holds no result table", file=sys.stderr)
        except (KeyError, ValueError) as e:
            print(f"make_figures: {experiment}: results are malformed: {e}", file=sys.stderr)
            return 1
    for path in results.made:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
