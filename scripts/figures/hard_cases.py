"""Issue 20, hard cases pushed through (baselines/README.md, "Hard cases"): per role order,
every model's force opposing the push against the depth, over the pressing half of the run."""
from collections import defaultdict

from .common import CYCLES, axis, figure, model_line, models_in, num, plt


# The curves of EXPERIMENT, one panel per role order, until DEEPEST picks the deepest cycle,
# with dotted lines at MARKS [(depth, label)]; TITLES[True] for the normal order.
def push_through(results, experiment, depth_of, force_of, deepest, marks, xlabel, ylabel, titles, out):
    rows = results.load(experiment, CYCLES)
    if not rows:
        return False
    by = defaultdict(list)
    for r in rows:
        by[(r.get(axis("roles"), "normal"), r[CYCLES.model])].append(r)
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
        results, "hard-cases-medial-axis", lambda r: 1000 * (top - num(r, CYCLES.z)), lambda r: num(r, CYCLES.fz),
        lambda rs: min(range(len(rs)), key=lambda i: num(rs[i], CYCLES.z)),
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
        results, "hard-cases-tube-peg", lambda r: 1000 * (num(r, CYCLES.x) - touch), lambda r: -num(r, CYCLES.fx),
        lambda rs: max(range(len(rs)), key=lambda i: num(rs[i], CYCLES.x)),
        [(0.25, "wall mid-surface in the peg"), (0.5, "wall through the peg's side")],
        "depth of the tube's inner wall in the peg (mm)",
        "force on the tube along -x, opposing the push (N)",
        {True: "tube (wall 0.5 mm) pushed into a peg: tube = pointshell",
         False: "tube (wall 0.5 mm) pushed into a peg: tube = field"},
        "hard_cases_tube_peg.png")


# Tools driven through a plate at 0.1-20 m/s (issue 33): per tool and plate, the largest force
# on the tool against the speed, per model and role order; a cross where the tool got through
# (no force once wholly past), a red ring where the force ever pulled it along its motion. And
# the counts per model and speed as a table.
TOOL_AXIS = axis("scene.bodies[name=tool].mesh")
PLATE_AXIS = axis("scene.bodies[name=plate].mesh")


def tunnelling_runs(rows):
    """(tool, plate, roles, speed, model) -> (peak |F| N, got through, pulled the wrong way)."""
    runs = defaultdict(list)
    for r in rows:
        key = (r[TOOL_AXIS], r[PLATE_AXIS], r.get(axis("roles"), "normal"), float(r[axis("trajectory.speed")]),
               r[CYCLES.model])
        runs[key].append(r)
    out = {}
    for key, rs in runs.items():
        forces = [(num(r, CYCLES.fx), num(r, CYCLES.fy), num(r, CYCLES.fz)) for r in rs]
        mags = [(fx * fx + fy * fy + fz * fz) ** 0.5 for fx, fy, fz in forces]
        wrong = any(m > 1e-6 and f[2] < -0.05 * m for f, m in zip(forces, mags))  # along the motion, -z
        out[key] = (max(mags), mags[-1] <= 1e-9, wrong)
    return out


@figure(experiments=["hard-cases-tunnelling"],
        outputs=["hard_cases_tunnelling.png", "hard_cases_tunnelling_table.png", "hard_cases_tunnelling_table.md"])
def hard_cases_tunnelling(results):
    rows = results.load("hard-cases-tunnelling", CYCLES)
    if not rows:
        return False
    runs = tunnelling_runs(rows)
    tools = sorted({k[0] for k in runs}, key=["ball", "blade", "tube"].index)
    plates = sorted({k[1] for k in runs})
    models = models_in(rows)
    fig, axes = plt.subplots(len(plates), len(tools), figsize=(4.6 * len(tools), 3.8 * len(plates)), squeeze=False)
    for i, plate in enumerate(plates):
        for j, tool in enumerate(tools):
            ax = axes[i][j]
            for model in models:
                for roles, ls in (("normal", "-"), ("swapped", ":")):
                    pts = sorted((k[3], v) for k, v in runs.items() if k[:3] == (tool, plate, roles) and k[4] == model)
                    if not pts:
                        continue
                    speeds = [s for s, _ in pts]
                    peaks = [max(v[0], 1e-3) for _, v in pts]
                    kw = model_line(model, len(pts), ls=ls, marker=None, label=model if roles == "normal" else None)
                    ax.plot(speeds, peaks, **kw)
                    for s, (peak, through, wrong) in pts:
                        ax.plot([s], [max(peak, 1e-3)], marker="x" if through else "o", color=kw["color"], ms=6,
                                mfc="none" if through else kw["color"], ls="none")
                        if wrong:
                            ax.plot([s], [max(peak, 1e-3)], marker="o", ms=11, mfc="none", mec="red", ls="none")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("speed (m/s) = mm per 1 kHz cycle")
            ax.set_ylabel("largest force on the tool (N)")
            ax.set_title(f"{tool} through the {plate} (solid: tool = pointshell)", fontsize=9)
            ax.grid(True, alpha=0.3, which="both")
    axes[0][0].legend(fontsize=7, title="x: got through, red ring: pulled through", title_fontsize=7)
    results.save(fig, "hard_cases_tunnelling.png")
    # Counts per model and speed over tools, plates and role orders.
    speeds = sorted({k[3] for k in runs})
    header = ["model"] + [f"{s:g} m/s" for s in speeds]
    lines = []
    for model in models:
        line = [model]
        for s in speeds:
            vs = [v for k, v in runs.items() if k[4] == model and k[3] == s]
            held = sum(1 for v in vs if not v[1])
            wrong = sum(1 for v in vs if v[2])
            line.append(f"held {held}/{len(vs)}, pulled {wrong}")
        lines.append(line)
    results.save_table(header, lines, "Tools through a 1 mm plate and a 0.5 mm wall: runs where the tool was held "
                       "(force at the end) and where the force pulled it through", "hard_cases_tunnelling_table")
    return True
