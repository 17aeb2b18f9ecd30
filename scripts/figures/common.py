"""What every figure module shares: reading results, saving figures and tables, and the look.

A figure module (any other module in this package) declares its figures with @figure; see
__init__.py for how they are found and docs/experiments.md ("Adding a figure") for how to add one.
"""
import csv
import math
import os
import re
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401  (re-exported for the figure modules)
from matplotlib.patches import Rectangle  # noqa: E402

DPI = 110  # every PNG, figures and tables


# ---------------------------------------------------------------------------------------------
# The result tables and their columns. Every column a figure reads is named through its table:
# SUMMARY.max_jump_N is "max_jump_N", a column the study that writes summary.csv declares (its
# name, unit and meaning beside the C++ writer; `contactlab columns` lists them, and each run's
# meta.json records them under "columns"). The figure test checks every such name against the
# program's declarations, so renaming a column in C++ fails it. A sweep axis (scene, roles,
# trajectory.speed, ...) is a column the config adds, named with axis().

class Table:
    """A result table of the studies, by its file under results/<experiment>/; attributes are
    its column names."""

    def __init__(self, file):
        self.file = file

    def __getattr__(self, column):
        if column.startswith("__"):
            raise AttributeError(column)
        return column

    def __repr__(self):
        return f"Table({self.file!r})"


CYCLES = Table("cycles.csv")            # study contact: one row per cycle per model
SUMMARY = Table("summary.csv")          # study contact: one row per model per job
CONVERGENCE = Table("convergence.csv")  # study contact: the fitted order per model and group
FIELD_ERROR = Table("field_error.csv")  # study deformed-field: one row per job
FIELD_SLICE = Table("field_slice.csv")  # study deformed-field: the slice's grid points
STABILITY = Table("stability.csv")      # study closed-loop: one row per job, model and motion
WORLD_CYCLES = Table("world_cycles.csv")    # study many-bodies: the tool's totals per cycle
WORLD_PAIRS = Table("world_pairs.csv")      # study many-bodies: one row per near pair per cycle
WORLD_BODIES = Table("world_bodies.csv")    # study many-bodies: one row per deformable body per cycle
WORLD_SUMMARY = Table("world_summary.csv")  # study many-bodies: one row per model per job
TABLES = {t.file: t for t in (CYCLES, SUMMARY, CONVERGENCE, FIELD_ERROR, FIELD_SLICE, STABILITY, WORLD_CYCLES,
                              WORLD_PAIRS, WORLD_BODIES, WORLD_SUMMARY)}


def axis(name):
    """NAME, a sweep axis of an experiment's config: a column its sweep adds to every table of a
    job (after experiment and job), not one a study declares."""
    return name


def read_csv(path):
    """PATH as a list of {column: cell} dicts, read as contactlab writes it (RFC 4180 quoting: a
    name holding a comma stays one cell). Raises ValueError naming the file and line for a row
    with another number of cells than the header, which DictReader would shift into None."""
    with open(path, newline="") as f:
        reader = csv.reader(f, strict=True)
        header = next(reader, [])
        rows, start = [], reader.line_num
        for cells in reader:
            if cells and len(cells) != len(header):
                raise ValueError(f"{path}:{start + 1}: {len(cells)} cells, the header (line 1) has {len(header)}")
            if cells:
                rows.append(dict(zip(header, cells)))
            start = reader.line_num
        return rows


# ROW[KEY] as a float; NaN when the column is missing or empty.
def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else math.nan


# A scene's short name: "data/scenes/block-joint.yaml" -> "block-joint".
def scene_name(path):
    return os.path.splitext(os.path.basename(path))[0]


# The largest stiffness of BY_K ({k_vc: every motion stable}) at which it and every smaller one
# are stable, or None (closed-loop studies).
def largest_stable(by_k):
    largest = None
    for k in sorted(by_k):
        if not by_k[k]:
            break
        largest = k
    return largest


# The distinct values of KEY over ROWS, in the order they first appear.
def in_order(rows, key):
    seen = []
    for r in rows:
        if r[key] not in seen:
            seen.append(r[key])
    return seen


def figure(experiments, outputs):
    """Declares a figure: the function draws it from the results of EXPERIMENTS (names of
    folders under results/) into OUTPUTS (file names under results/figures/).

    The function takes a Results and returns False when its results are missing (the entry
    point then notes it as skipped), True when it wrote its outputs. It raises KeyError or
    ValueError when the results are malformed.
    """
    if isinstance(experiments, str) or isinstance(outputs, str):
        raise TypeError("@figure: experiments and outputs are lists of names")
    if not experiments or not outputs:
        raise ValueError("@figure: a figure names at least one experiment and one output")

    def declare(draw):
        draw.experiments = tuple(experiments)
        draw.outputs = tuple(outputs)
        return draw
    return declare


class Results:
    """The results folder a run of make_figures reads, and its figures/ folder it writes.
    FOLDERS maps an experiment to the folder holding its tables when that is not
    RESULTS/EXPERIMENT (a single run's folder: `contactlab run --out DIR`)."""

    def __init__(self, results, folders=None):
        self.results = results
        self.folders = dict(folders or {})
        self.out = os.path.join(results, "figures")
        os.makedirs(self.out, exist_ok=True)
        self.made = []

    # The folder of EXPERIMENT's tables.
    def folder(self, experiment):
        return self.folders.get(experiment, os.path.join(self.results, experiment))

    # results/EXPERIMENT/TABLE (a Table above) as a list of dicts, or None when it does not exist.
    def load(self, experiment, table):
        path = os.path.join(self.folder(experiment), table.file)
        if not os.path.exists(path):
            return None
        return read_csv(path)

    # Writes FIG to figures/NAME and closes it. RECT (left, bottom, right, top, figure
    # fraction): where tight_layout puts the axes, leaving room for a figure legend; TIGHT=False
    # keeps the figure's own size and layout (tables).
    def save(self, fig, name, rect=None, tight=True):
        path = os.path.join(self.out, name)
        tmp = path + ".tmp.png"
        if tight:
            fig.tight_layout(rect=rect)
        fig.savefig(tmp, dpi=DPI)
        plt.close(fig)
        os.replace(tmp, path)
        self.made.append(path)

    # A table as a figure (NAME.png, sized to its text) and as Markdown (NAME.md).
    def save_table(self, header, lines, title, name):
        lines = [[str(c) for c in line] for line in lines]
        self.save(table_figure(header, lines, title), name + ".png", tight=False)
        self.save_markdown(header, lines, name)

    # A table as Markdown only (NAME.md; written again, it replaces the one save_table wrote).
    def save_markdown(self, header, lines, name):
        lines = [[str(c) for c in line] for line in lines]
        md = os.path.join(self.out, name + ".md")
        with open(md + ".tmp", "w") as f:
            f.write("| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n")
            for line in lines:
                f.write("| " + " | ".join(line) + " |\n")
        os.replace(md + ".tmp", md)
        if md not in self.made:
            self.made.append(md)


# ---------------------------------------------------------------------------------------------
# Tables: every column as wide as its widest text, headers wrapped at spaces to no wider than
# their column needs for its cells (or their longest word), the figure as large as the table
# and its title. Widths are measured with the renderer that draws the PNG, in pixels at DPI.

TABLE_FONT = 9        # points, cells and headers
TABLE_TITLE_FONT = 11
_PX = DPI / 72.0      # pixels per point


def _looks_numeric(cell):
    parts = [p for p in cell.replace("/", " ").split() if p]
    if not parts:
        return True
    try:
        [float(p) for p in parts]
        return True
    except ValueError:
        return False


def _wrap(words, fits):
    lines = []
    for w in words:
        if lines and fits(lines[-1] + " " + w):
            lines[-1] += " " + w
        else:
            lines.append(w)
    return lines or [""]


def table_figure(header, lines, title):
    """HEADER (n strings) over LINES (rows of n strings) under TITLE, as a figure sized to fit.

    Returns the figure (not yet saved). Raises ValueError when a row's length differs from
    the header's.
    """
    for line in lines:
        if len(line) != len(header):
            raise ValueError(f"table '{title}': a row has {len(line)} cells, the header {len(header)}")
    fig = plt.figure(dpi=DPI)
    renderer = fig.canvas.get_renderer()

    def width(text, size=TABLE_FONT, weight="normal"):
        t = fig.text(0, 0, text, fontsize=size, fontweight=weight)
        w = t.get_window_extent(renderer).width
        t.remove()
        return w

    pad = 0.8 * TABLE_FONT * _PX          # each side of a cell's text
    line_h = 1.25 * TABLE_FONT * _PX      # one line of text
    row_h = line_h + 0.8 * TABLE_FONT * _PX
    margin = 1.0 * TABLE_FONT * _PX

    # Column widths: the widest cell, or the header's longest word if wider; headers wrap at
    # spaces to that width, or to ten digits' width in a narrow column; a parenthesis is not
    # broken.
    wrapped, col_w = [], []
    narrow = width("0" * 10, weight="bold")
    for c, head in enumerate(header):
        body = max([width(line[c]) for line in lines] + [0.0])
        words = re.findall(r"\([^)]*\)|[^\s(]+", head)  # a parenthesis stays on one line
        limit = max([body, narrow] + [width(w, weight="bold") for w in words])
        wrapped.append(_wrap(words, lambda s, limit=limit: width(s, weight="bold") <= limit + 0.5))
        col_w.append(max([body] + [width(s, weight="bold") for s in wrapped[-1]]) + 2 * pad)
    numeric = [c > 0 and all(_looks_numeric(line[c]) for line in lines) for c in range(len(header))]
    head_lines = max(len(w) for w in wrapped)
    head_h = head_lines * line_h + 0.8 * TABLE_FONT * _PX
    table_w = sum(col_w)
    title_w = width(title, TABLE_TITLE_FONT)
    title_h = 1.3 * TABLE_TITLE_FONT * _PX
    W = max(table_w, title_w) + 2 * margin
    H = margin + title_h + 0.6 * margin + head_h + len(lines) * row_h + margin
    fig.set_size_inches(W / DPI, H / DPI)

    # Pixels from the top-left corner to figure fractions.
    def at(x, y):
        return x / W, 1 - y / H

    # Title, centred over the figure.
    fig.text(*at(W / 2, margin), title, fontsize=TABLE_TITLE_FONT, ha="center", va="top")
    x0 = (W - table_w) / 2
    top = margin + title_h + 0.6 * margin
    # Header row: shaded, bold, centred lines.
    x = x0
    for c, head in enumerate(wrapped):
        fig.add_artist(Rectangle(at(x, top + head_h), col_w[c] / W, head_h / H, transform=fig.transFigure,
                                 facecolor="#e8e8e8", edgecolor="0.3", lw=0.8))
        fig.text(*at(x + col_w[c] / 2, top + head_h / 2), "\n".join(head), fontsize=TABLE_FONT,
                 fontweight="bold", ha="center", va="center", linespacing=1.15)
        x += col_w[c]
    # Body rows: the first column and text columns left-aligned, numbers right-aligned.
    for i, line in enumerate(lines):
        y = top + head_h + i * row_h
        x = x0
        for c, cell in enumerate(line):
            fig.add_artist(Rectangle(at(x, y + row_h), col_w[c] / W, row_h / H, transform=fig.transFigure,
                                     facecolor="white" if i % 2 == 0 else "#f7f7f7", edgecolor="0.3", lw=0.8))
            if numeric[c]:
                fig.text(*at(x + col_w[c] - pad, y + row_h / 2), cell, fontsize=TABLE_FONT, ha="right", va="center")
            else:
                fig.text(*at(x + pad, y + row_h / 2), cell, fontsize=TABLE_FONT, ha="left", va="center")
            x += col_w[c]
    return fig


# ---------------------------------------------------------------------------------------------
# One look per contact model (the names `contactlab` registers), the same in every figure.
# tab10 colours, one per model, none a mix of two others. The pairs whose forces coincide or
# nearly do (pointshell and pointshell-linear give the same force by construction; vps and
# vps-repulsion, fcl and bullet often agree) differ in colour, line style and marker, and the
# second of each pair is drawn thinner and on top, so the first shows on both sides of it.
MODEL_STYLES = {
    "pointshell":        dict(color="#1f77b4", ls="-", lw=2.6, marker="o", zorder=2.0, phase=0.0),
    "pointshell-linear": dict(color="#ff7f0e", ls=(0, (4, 2.5)), lw=1.3, marker="x", zorder=2.6, phase=0.5),
    "vps":               dict(color="#2ca02c", ls="-", lw=2.0, marker="s", zorder=2.1, phase=0.15),
    "vps-repulsion":     dict(color="#9467bd", ls=(0, (6, 2, 1.5, 2)), lw=1.3, marker="^", zorder=2.5, phase=0.65),
    "fcl":               dict(color="#d62728", ls="-", lw=1.3, marker="D", zorder=2.2, phase=0.3),
    "bullet":            dict(color="#8c564b", ls="-", lw=1.1, marker="v", zorder=2.4, phase=0.8),
    "pointshell-ccd":    dict(color="#17becf", ls="-", lw=2.2, marker="h", zorder=2.8, phase=0.55),
    "pressure-field":    dict(color="#bcbd22", ls="-", lw=1.8, marker="p", zorder=2.3, phase=0.2),
    "inner-spheres":     dict(color="#e377c2", ls="-.", lw=1.6, marker="<", zorder=2.35, phase=0.7),
    "reference":         dict(color="#000000", ls=":", lw=1.6, marker="*", zorder=2.7, phase=0.4),
    "volume":            dict(color="#555555", ls="--", lw=1.4, marker="P", zorder=2.7, phase=0.9),
    "eq2-halfspace":     dict(color="#7f7f7f", ls="-.", lw=1.4, marker="X", zorder=2.7, phase=0.9),
}
# For a model not in the table: colours no named model uses, chosen by a hash of the name.
_FALLBACK_COLORS = ["#aec7e8", "#ffbb78", "#98df8a", "#c5b0d5", "#f7b6d2", "#dbdb8d", "#9edae5"]
_FALLBACK_LS = ["-", "--", "-.", (0, (1, 1.5))]
_FALLBACK_MARKERS = ["h", "p", "<", ">", "d", "8"]


def model_style(model):
    """The colour, line style (ls), width (lw), marker, zorder and marker phase (where along a
    curve its markers start, a fraction of their spacing) of MODEL, a dict; a name not
    in MODEL_STYLES gets a fixed one derived from the name (the same in every run)."""
    if model in MODEL_STYLES:
        return dict(MODEL_STYLES[model])
    h = zlib.crc32(model.encode())
    return dict(color=_FALLBACK_COLORS[h % len(_FALLBACK_COLORS)],
                ls=_FALLBACK_LS[(h // 7) % len(_FALLBACK_LS)],
                marker=_FALLBACK_MARKERS[(h // 31) % len(_FALLBACK_MARKERS)], lw=1.4, zorder=2.3,
                phase=(h % 97) / 97.0)


def model_color(model):
    return model_style(model)["color"]


# Keywords for ax.plot of MODEL's curve of N points: its style, with markers every N/10
# points, staggered per model so markers of coinciding curves fall side by side; OVERRIDES win.
def model_line(model, n, **overrides):
    st = model_style(model)
    step = max(1, n // 10)
    kw = dict(color=st["color"], ls=st["ls"], lw=st["lw"], marker=st["marker"], ms=5, zorder=st["zorder"],
              markevery=(int(st["phase"] * step), step), label=model)
    if st["marker"] in "x+*":
        kw["mew"] = 1.5
    kw.update(overrides)
    return kw


# Models present in ROWS, in a fixed order: the table's order, then any others by name.
def models_in(rows, key=CYCLES.model):
    present = {r[key] for r in rows}
    return [m for m in MODEL_STYLES if m in present] + sorted(present - set(MODEL_STYLES))
