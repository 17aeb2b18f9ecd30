"""Paper sec. 4.1: the deformable pointshell two-way coupled, on a cantilever pressed by a probe."""
from .common import CYCLES, SUMMARY, axis, figure, model_line, num, plt


@figure(experiments=["deformable-cantilever"], outputs=["deformable_cantilever.png"])
def deformable_cantilever(results):
    rows = results.load("deformable-cantilever", CYCLES)
    summary = results.load("deformable-cantilever", SUMMARY)
    if not rows or not summary:
        return False
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    # Deflection and contact force over time, per mesh size (tree model).
    for cells in sorted({r[axis("cells")] for r in rows}, key=int):
        rs = [r for r in rows if r[axis("cells")] == cells and r[CYCLES.model] == "pointshell"]
        t = [num(r, CYCLES.t) for r in rs]
        axes[0].plot(t, [1e3 * num(r, CYCLES.max_displacement) for r in rs], lw=0.9, label=f"{cells} cells")
        axes[1].plot(t, [num(r, CYCLES.fz) for r in rs], lw=0.9, label=f"{cells} cells")
    axes[0].set_ylabel("largest displacement, free end (mm)")
    axes[0].set_title("beam deflection")
    axes[1].set_ylabel("contact force on the probe, z (N)")
    axes[1].set_title("contact force")
    for a in axes[:2]:
        a.set_xlabel("time (s)")
    # Cost per cycle: each model's query in its own style, the StVK step in black.
    tree = [r for r in summary if r[SUMMARY.model] == "pointshell"]
    lin = {r[axis("cells")]: r for r in summary if r[SUMMARY.model] == "pointshell-linear"}
    x = [int(r[axis("cells")]) for r in tree]
    axes[2].plot(x, [num(r, SUMMARY.median_us) for r in tree],
                 **model_line("pointshell", len(x), markevery=None, label="tree traversal (pointshell)"))
    axes[2].plot(x, [num(lin.get(r[axis("cells")], {}), SUMMARY.median_us) for r in tree],
                 **model_line("pointshell-linear", len(x), markevery=None, label="tree-less (pointshell-linear)"))
    axes[2].plot(x, [num(r, SUMMARY.median_step_us) for r in tree], "^-", color="k", lw=1.2,
                 label="reduced StVK step")
    axes[2].set_xlabel("simulation mesh cells along the beam")
    axes[2].set_ylabel("median time per cycle (µs)")
    axes[2].set_yscale("log")
    axes[2].set_title("cycle cost")
    for a in axes:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    results.save(fig, "deformable_cantilever.png")
    return True
