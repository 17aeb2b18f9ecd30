"""Paper Fig. 14(b): force while scanning the bumps, per pointshell size."""
from collections import defaultdict

from .common import CYCLES, axis, figure, num, plt


@figure(experiments=["fig14b-bumps"], outputs=["fig14b_bumps.png"])
def fig14b_bumps(results):
    rows = results.load("fig14b-bumps", CYCLES)
    if not rows:
        return False
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    groups = defaultdict(list)
    for r in rows:
        groups[int(r[axis("points")])].append(r)
    for points, rs in sorted(groups.items()):
        x = [1000 * num(r, CYCLES.x) for r in rs]
        axes[0].plot(x, [num(r, CYCLES.fz) for r in rs], lw=0.8, label=f"{points} points")
        axes[1].plot(x, [num(r, CYCLES.fx) for r in rs], lw=0.8, label=f"{points} points")
    axes[0].set_ylabel("normal force $F_z$ (N)")
    axes[1].set_ylabel("tangential force $F_x$ (N)")
    axes[1].set_xlabel("scan position x (mm)")
    axes[0].set_title("Fig. 14(b): scanning bumps with progressively finer pointshells")
    for a in axes:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    results.save(fig, "fig14b_bumps.png")
    return True
