"""Issue 15, tessellation invariance: per model, how much the force changes between two meshes
of one shape at the same poses: RMS |F_coarse - F_fine| / RMS |F_fine| over the cycles
(printed, and a bar per shape), and the force on both meshes over time."""
import math
from collections import defaultdict

from .common import CYCLES, figure, model_color, model_line, models_in, num, plt


@figure(experiments=["tessellation"], outputs=["tessellation.png"])
def tessellation(results):
    rows = results.load("tessellation", CYCLES)
    if not rows:
        return False
    case_axis = next(k for k in rows[0] if k.startswith("scene.bodies"))
    by = defaultdict(list)
    for r in rows:
        by[(r[case_axis], r[CYCLES.model])].append(r)
    meshes = sorted({k[0] for k in by})
    models = models_in(rows)
    # Pairs of labels "SHAPE-COUNT": coarse (fewer triangles) then fine.
    shapes = defaultdict(list)
    for m in meshes:
        shape, count = m.rsplit("-", 1)
        shapes[shape].append((int(count), m))
    fig, axes = plt.subplots(1, 1 + len(shapes), figsize=(5.0 * (1 + len(shapes)), 4.0), squeeze=False)
    width = 0.8 / max(1, len(models))
    for i, (shape, pair) in enumerate(sorted(shapes.items())):
        (_, coarse), (_, fine) = sorted(pair)[0], sorted(pair)[-1]
        ax = axes[0][1 + i]
        for j, model in enumerate(models):
            a, b = by.get((coarse, model), []), by.get((fine, model), [])
            if not a or len(a) != len(b):
                continue
            force = (CYCLES.fx, CYCLES.fy, CYCLES.fz)
            diff = sum(sum((num(x, c) - num(y, c)) ** 2 for c in force) for x, y in zip(a, b))
            ref = sum(sum(num(y, c) ** 2 for c in force) for y in b)
            change = math.sqrt(diff / ref) if ref > 0 else float("nan")
            print(f"tessellation {shape} {coarse} vs {fine} {model}: RMS |dF| / RMS |F| = {change:.4f}")
            axes[0][0].bar(i + (j - (len(models) - 1) / 2) * width, change, width, color=model_color(model),
                           label=model if i == 0 else None)
            # The fine mesh in the model's style; the coarse one thin and dotted in its colour.
            t = [num(r, CYCLES.t) for r in b]
            ax.plot(t, [math.hypot(*(num(r, c) for c in force)) for r in b],
                    **model_line(model, len(b), label=f"{model}, {fine}"))
            ax.plot(t, [math.hypot(*(num(r, c) for c in force)) for r in a], color=model_color(model),
                    lw=0.9, ls=":", zorder=3)
        ax.set_title(f"{shape}: {fine} in the model's line, {coarse} thin dotted", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_ylabel("|F| on the tool (N)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6)
    axes[0][0].set_xticks(range(len(shapes)))
    axes[0][0].set_xticklabels(sorted(shapes), fontsize=8)
    axes[0][0].set_ylabel("RMS |F_coarse - F_fine| / RMS |F_fine|")
    axes[0][0].set_title("Tessellation invariance (same poses)", fontsize=10)
    axes[0][0].grid(True, axis="y", alpha=0.3)
    axes[0][0].legend(fontsize=7)
    results.save(fig, "tessellation.png")
    return True
