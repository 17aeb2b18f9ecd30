"""Beyond the paper: force continuity of every model while sliding, per scene."""
import math
from collections import defaultdict

from .common import CYCLES, SUMMARY, axis, figure, model_color, model_line, models_in, num, plt, scene_name


@figure(experiments=["continuity-models"], outputs=["continuity_models.png"])
def continuity_models(results):
    rows = results.load("continuity-models", CYCLES)
    summary = results.load("continuity-models", SUMMARY)
    if not rows or not summary:
        return False
    scenes = sorted({r[axis("scene")] for r in rows})
    fig, axes = plt.subplots(len(scenes), 2, figsize=(11, 3.6 * len(scenes)), squeeze=False)
    for i, scene in enumerate(scenes):
        # |F| over time, one curve per model.
        groups = defaultdict(list)
        for r in rows:
            if r[axis("scene")] == scene:
                groups[r[CYCLES.model]].append(r)
        for model in models_in([r for r in rows if r[axis("scene")] == scene]):
            rs = groups[model]
            axes[i][0].plot([num(r, CYCLES.t) for r in rs],
                            [math.hypot(num(r, CYCLES.fx), num(r, CYCLES.fy), num(r, CYCLES.fz)) for r in rs],
                            **model_line(model, len(rs), lw=0.8 * model_line(model, 1)["lw"], ms=4))
        name = scene_name(scene)
        axes[i][0].set_title(f"{name}: |F| while sliding")
        axes[i][0].set_xlabel("time (s)")
        axes[i][0].set_ylabel("|F| (N)")
        axes[i][0].legend(fontsize=8)
        # The largest per-cycle jump, one bar per model.
        s = {r[SUMMARY.model]: r for r in summary if r[axis("scene")] == scene}
        order = models_in(list(s.values()))
        axes[i][1].bar(order, [num(s[m], SUMMARY.max_jump_N) for m in order], color=[model_color(m) for m in order])
        axes[i][1].set_ylabel("largest per-cycle force jump (N)")
        axes[i][1].set_title(f"{name}: force continuity")
        axes[i][1].tick_params(axis="x", rotation=30)
        for a in axes[i]:
            a.grid(True, alpha=0.3)
    results.save(fig, "continuity_models.png")
    return True
