"""Paper Fig. 11: cycle time, nodes and level on a recorded trajectory, with and without budget."""
from collections import defaultdict

from .common import CYCLES, axis, figure, num, plt


@figure(experiments=["fig11-degradation"], outputs=["fig11_degradation.png"])
def fig11_degradation(results):
    rows = results.load("fig11-degradation", CYCLES)
    if not rows:
        return False
    fig, axes = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
    groups = defaultdict(list)
    for r in rows:
        groups[r[axis("node_budget")]].append(r)
    for budget, rs in sorted(groups.items(), key=lambda kv: int(kv[0])):
        label = "no budget" if budget == "0" else f"budget {budget} nodes"
        t = [num(r, CYCLES.t) for r in rs]
        axes[0].plot(t, [num(r, CYCLES.time_us) for r in rs], lw=0.6, label=label)
        axes[1].plot(t, [num(r, CYCLES.nodes) for r in rs], lw=0.6, label=label)
        axes[2].plot(t, [num(r, CYCLES.level) for r in rs], lw=0.9, label=label)
    axes[0].set_ylabel("cycle time (µs)")
    axes[1].set_ylabel("nodes visited")
    axes[2].set_ylabel("level rendered")
    axes[2].set_xlabel("time (s)")
    axes[0].set_title("Fig. 11: graceful degradation on a recorded trajectory")
    for a in axes:
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    results.save(fig, "fig11_degradation.png")
    return True
