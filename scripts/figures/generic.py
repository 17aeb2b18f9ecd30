"""The figure of an experiment no figure module declares (a user's own config, a Python run's
folder): from its meta.json and whatever result tables it holds, per model, drawn the same way
for every study.

- cycles.csv (study contact): |F| on the moving body along the trajectory, one panel per job
  (titled with the job's sweep values), one line per model: EXPERIMENT.png.
- summary.csv, stability.csv, field_error.csv: a table per row of the file with the job's sweep
  values and the columns that mean something for the rows present (a column empty in every row,
  no value for any of them, is left out): EXPERIMENT_summary.png/.md
  (stability.csv: EXPERIMENT_stability, field_error.csv: EXPERIMENT_field_error).
"""
import json
import math
import os

from .common import CYCLES, FIELD_ERROR, STABILITY, SUMMARY, model_line, models_in, num, plt

MAX_PANELS = 12  # jobs drawn as force panels; more are named in the last panel's title
MAX_TABLE_COLUMNS = 12  # a wider table does not fit a page: the first ones, the rest in the .md only

# The per-file columns a generic table leads with, when present; the rest follow in file order.
_LEADING = {
    SUMMARY.file: [SUMMARY.model, SUMMARY.max_force_N, SUMMARY.mean_force_N, SUMMARY.max_jump_N,
                   SUMMARY.max_jump_rel, SUMMARY.median_us, SUMMARY.p99_us, SUMMARY.rms_rel_error_calibrated,
                   SUMMARY.max_dir_error_deg],
    STABILITY.file: [STABILITY.model, STABILITY.motion, STABILITY.k_vc, STABILITY.rate_hz, STABILITY.verdict,
                     STABILITY.energy_into_hand_J, STABILITY.max_force_jump_N],
    FIELD_ERROR.file: [],
}
_SUFFIX = {SUMMARY.file: "summary", STABILITY.file: "stability", FIELD_ERROR.file: "field_error"}


def read_meta(folder):
    """FOLDER's meta.json as a dict, or None when it has none (not a results folder)."""
    path = os.path.join(folder, "meta.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        try:
            return json.load(f)
        except json.JSONDecodeError as e:
            raise ValueError(f"{path}: not JSON: {e}") from e


def sweep_axes(rows, declared_first):
    """The sweep axes of a keyed table: the columns between `job` and DECLARED_FIRST (the table's
    first declared column after the keys)."""
    if not rows:
        return []
    header = list(rows[0])
    if "job" not in header or declared_first not in header:
        return []
    return header[header.index("job") + 1:header.index(declared_first)]


def job_label(row, axes):
    values = ", ".join(f"{a}={os.path.splitext(os.path.basename(row[a]))[0] if a == 'scene' else row[a]}"
                       for a in axes)
    return f"job {row.get('job', '?')}" + (f" ({values})" if values else "")


def draw_forces(results, experiment, rows):
    """|F| along the trajectory per job and model, from cycles.csv's ROWS."""
    axes_cols = sweep_axes(rows, CYCLES.model)
    jobs = []
    for r in rows:
        if r["job"] not in jobs:
            jobs.append(r["job"])
    shown = jobs[:MAX_PANELS]
    cols = min(3, len(shown))
    nrows = math.ceil(len(shown) / cols)
    height = 3.0 * nrows + 0.8  # inches: the panels, and the title and legend above them
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, height), squeeze=False)
    for i, job in enumerate(shown):
        ax = axes[i // cols][i % cols]
        in_job = [r for r in rows if r["job"] == job]
        time_axis = all(r.get(CYCLES.t, "") != "" for r in in_job)
        for model in models_in(in_job, CYCLES.model):
            mine = [r for r in in_job if r[CYCLES.model] == model]
            xs = [num(r, CYCLES.t) if time_axis else num(r, CYCLES.cycle) for r in mine]
            ys = [math.sqrt(num(r, CYCLES.fx) ** 2 + num(r, CYCLES.fy) ** 2 + num(r, CYCLES.fz) ** 2) for r in mine]
            ax.plot(xs, ys, **model_line(model, len(xs)))
        ax.set_xlabel("t (s)" if time_axis else "cycle")
        ax.set_ylabel("|F| on the moving body (N)")
        title = job_label(in_job[0], axes_cols)
        if i == len(shown) - 1 and len(jobs) > len(shown):
            title += f"; {len(jobs) - len(shown)} more jobs not drawn"
        ax.set_title(title, fontsize=8)
    for j in range(len(shown), nrows * cols):
        axes[j // cols][j % cols].axis("off")
    handles, labels = axes[0][0].get_legend_handles_labels()
    top = 1 - 0.8 / height
    fig.suptitle(f"{experiment}: |F| along the trajectory per job", y=0.995, fontsize=10)
    fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 1 - 0.3 / height),
               ncol=min(6, max(1, len(labels))), fontsize=8)
    results.save(fig, f"{experiment}.png", rect=(0, 0, 1, top))


def _meaningful(rows, column):
    return any(r.get(column, "") != "" for r in rows)


def draw_table(results, experiment, table, rows):
    """A table of ROWS (TABLE's file): job and sweep values, then the columns with a value."""
    leading = [c for c in _LEADING[table.file] if rows and c in rows[0]]
    first_declared = leading[0] if leading else (list(rows[0])[2] if len(rows[0]) > 2 else "")
    axes_cols = sweep_axes(rows, first_declared)
    skip = {"experiment", "job", "wall_s"} | set(axes_cols)
    columns = leading + [c for c in rows[0] if c not in leading and c not in skip]
    columns = [c for c in columns if _meaningful(rows, c)]
    header = ["job"] + columns
    lines = [[job_label(r, axes_cols)] + [r.get(c, "") for c in columns] for r in rows]
    name = f"{experiment}_{_SUFFIX[table.file]}"
    wide = len(header) > MAX_TABLE_COLUMNS
    title = f"{experiment}: {table.file}" + (" (first columns; all in the .md)" if wide else "")
    results.save_table(header[:MAX_TABLE_COLUMNS], [line[:MAX_TABLE_COLUMNS] for line in lines], title, name)
    if wide:  # the Markdown keeps every column
        results.save_markdown(header, lines, name)


def draw_generic(results, experiment):
    """Draws what EXPERIMENT's folder holds; returns the number of files it wrote (0: no table)."""
    before = len(results.made)
    cycles = results.load(experiment, CYCLES)
    if cycles:
        draw_forces(results, experiment, cycles)
    for table in (SUMMARY, STABILITY, FIELD_ERROR):
        rows = results.load(experiment, table)
        if rows:
            draw_table(results, experiment, table, rows)
    return len(results.made) - before
