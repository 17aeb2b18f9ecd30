"""Beyond the paper: force continuity of every model while sliding, per scene.

The models' forces differ by two orders of magnitude (the pressure field's default modulus
pushes back about 100x more softly than the penalty models), so |F| is drawn on a log axis and
continuity is the relative jump, the largest per-cycle jump over the model's median |F| in
contact (max_jump_rel); the absolute jump in newtons is written above each bar. One legend for
the figure, beside the panels, so no trace is covered.
"""
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
    fig, axes = plt.subplots(len(scenes), 2, figsize=(12.5, 3.6 * len(scenes)), squeeze=False)
    handles = {}
    for i, scene in enumerate(scenes):
        # |F| over time, one curve per model; a cycle with no force has no point on the log axis.
        groups = defaultdict(list)
        for r in rows:
            if r[axis("scene")] == scene:
                groups[r[CYCLES.model]].append(r)
        for model in models_in([r for r in rows if r[axis("scene")] == scene]):
            rs = groups[model]
            f = [math.hypot(num(r, CYCLES.fx), num(r, CYCLES.fy), num(r, CYCLES.fz)) for r in rs]
            (line,) = axes[i][0].plot([num(r, CYCLES.t) for r in rs], [v if v > 0 else math.nan for v in f],
                                      **model_line(model, len(rs), lw=0.8 * model_line(model, 1)["lw"], ms=4))
            handles.setdefault(model, line)
        name = scene_name(scene)
        axes[i][0].set_yscale("log")
        axes[i][0].set_title(f"{name}: |F| while sliding")
        axes[i][0].set_xlabel("time (s)")
        axes[i][0].set_ylabel("|F| (N, log)")
        # The largest per-cycle jump relative to the model's own force, one bar per model.
        s = {r[SUMMARY.model]: r for r in summary if r[axis("scene")] == scene}
        order = models_in(list(s.values()))
        rel = [num(s[m], SUMMARY.max_jump_rel) for m in order]
        bars = axes[i][1].bar(order, [100 * v for v in rel], color=[model_color(m) for m in order])
        for bar, m in zip(bars, order):
            axes[i][1].annotate(f"{num(s[m], SUMMARY.max_jump_N):.3g} N", (bar.get_x() + bar.get_width() / 2,
                                bar.get_height()), ha="center", va="bottom", fontsize=7)
        axes[i][1].set_ylabel("largest jump / median |F| (%)")
        axes[i][1].set_title(f"{name}: force continuity (relative; absolute above each bar)")
        axes[i][1].tick_params(axis="x", rotation=30)
        axes[i][1].margins(y=0.15)
        for a in axes[i]:
            a.grid(True, alpha=0.3)
    fig.legend(list(handles.values()), list(handles), loc="center right", fontsize=8, title="model")
    results.save(fig, "continuity_models.png", rect=(0, 0, 0.84, 1))
    return True
