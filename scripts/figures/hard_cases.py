"""Issue 20, hard cases pushed through (baselines/README.md, "Hard cases"): per role order,
every model's force opposing the push against the depth, over the pressing half of the run."""
from collections import defaultdict

from .common import figure, model_line, models_in, num, plt


# The curves of EXPERIMENT, one panel per role order, until DEEPEST picks the deepest cycle,
# with dotted lines at MARKS [(depth, label)]; TITLES[True] for the normal order.
def push_through(results, experiment, depth_of, force_of, deepest, marks, xlabel, ylabel, titles, out):
    rows = results.load(experiment, "cycles")
    if not rows:
        return False
    by = defaultdict(list)
    for r in rows:
        by[(r.get("roles", "normal"), r["model"])].append(r)
    orders = sorted({k[0] for k in by})
    fig, axes = plt.subplots(1, len(orders), figsize=(5.5 * len(orders), 4.2), squeeze=False)
    for ax, order in zip(axes[0], orders):
        for model in models_in(rows):
            rs = by.get((order, model))
            if not rs:
                continue
            rs = rs[: deepest(rs) + 1]
            ax.plot([depth_of(r) for r in rs], [force_of(r) for r in rs], **model_line(model, len(rs)))
        for d, what in marks:
            ax.axvline(d, color="0.5", ls=":", lw=0.8)
            ax.text(d, 0, " " + what, rotation=90, va="bottom", fontsize=7, color="0.4")
        ax.axhline(0, color="k", lw=0.6)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(titles[order == "normal"], fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    results.save(fig, out)
    return True


# A ball pushed through a thin plate: the force on the ball along the push against the depth
# of its lowest point below the plate's top.
@figure(experiments=["hard-cases-medial-axis"], outputs=["hard_cases_medial_axis.png"])
def hard_cases_medial_axis(results):
    top = 0.002 + 0.01  # ball centre when its lowest point touches the plate's top face, m
    return push_through(
        results, "hard-cases-medial-axis", lambda r: 1000 * (top - num(r, "z")), lambda r: num(r, "fz"),
        lambda rs: min(range(len(rs)), key=lambda i: num(rs[i], "z")),
        [(2, "lowest point at mid-plane"), (12, "centre at mid-plane")],
        "depth of the ball's lowest point below the plate's top (mm)",
        "force on the ball along +z, opposing the push (N)",
        {True: "ball r 1 cm through a 4 mm plate: ball = pointshell",
         False: "ball r 1 cm through a 4 mm plate: ball = field"},
        "hard_cases_medial_axis.png")


# A thin-walled tube over a peg pushed sideways into it and on through its 0.5 mm wall: the
# force on the tube opposing the push against the depth.
@figure(experiments=["hard-cases-tube-peg"], outputs=["hard_cases_tube_peg.png"])
def hard_cases_tube_peg(results):
    touch = 0.0015  # tube offset along x where its inner wall touches the peg, m
    return push_through(
        results, "hard-cases-tube-peg", lambda r: 1000 * (num(r, "x") - touch), lambda r: -num(r, "fx"),
        lambda rs: max(range(len(rs)), key=lambda i: num(rs[i], "x")),
        [(0.25, "wall mid-surface in the peg"), (0.5, "wall through the peg's side")],
        "depth of the tube's inner wall in the peg (mm)",
        "force on the tube along -x, opposing the push (N)",
        {True: "tube (wall 0.5 mm) pushed into a peg: tube = pointshell",
         False: "tube (wall 0.5 mm) pushed into a peg: tube = field"},
        "hard_cases_tube_peg.png")
