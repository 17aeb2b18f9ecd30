"""Beyond the paper: every model's cycle time against its force error, per scene.

Two error axes, side by side. The first is model-neutral: each model's RMS force error against
the exact overlap-volume law (compare-volume's reference, -k_V grad V on the meshes) after the
one stiffness scale fitted per model and scene (summary.csv's rms_rel_error_calibrated, as the
trust table scores). The second is the paper's own law, the eq. (2) limit of dense quadrature
(speed-vs-error's reference): the pointshell family's continuum limit, by construction far from
a pressure field or a sphere packing, labelled so.

Where an experiment sweeps node_budget (speed-vs-error does: each model's per-cycle work budget
in its own unit, docs/models.md "Time budgets"), a run under a budget that bound on some cycle
(degraded_share > 0) is drawn small, joined by a dotted line to the same model's unbudgeted
point: what the model costs and how far off it is as it runs in the live loop. A budget that
never bound changes nothing but the timing and is not drawn.
"""
from matplotlib.lines import Line2D

from .common import SUMMARY, axis, figure, model_color, models_in, num, plt, scene_name

SCENE_MARKERS = "osD^v<>p*"

PANELS = [
    # (experiment, error column, y label, title)
    ("compare-volume", SUMMARY.rms_rel_error_calibrated,
     "RMS relative error vs. overlap-volume law\n(after the fitted stiffness scale)",
     "Model-neutral: the exact overlap volume"),
    ("speed-vs-error", SUMMARY.rms_rel_error,
     "RMS relative error vs. eq. (2) quadrature",
     "The paper's own law (hollow: pointshell on its default offset;\nsmall, dotted: under a node budget that bound)"),
]


def _budget(row):
    """The row's node_budget (0: none, also where the experiment does not sweep it)."""
    b = num(row, axis("node_budget"))
    return b if b == b else 0.0


def _panel(ax, summary, error, scenes):
    """One panel: a point per model and scene at (median time, ERROR), a line to the p99 time;
    a budget that bound, small, dotted from the unbudgeted point."""
    def where(r):
        return (r[SUMMARY.model], r[axis("scene")], r.get(axis("offset"), "0"))

    unbudgeted = {where(r): r for r in summary if _budget(r) == 0 and num(r, error) >= 0}
    for model in models_in(summary):
        color = model_color(model)
        for r in summary:
            if r[SUMMARY.model] != model or not num(r, error) >= 0:
                continue
            budget = _budget(r)
            if budget > 0 and not num(r, SUMMARY.degraded_share) > 0:
                continue  # the budget never bound: the same run
            i = scenes.index(scene_name(r[axis("scene")]))
            hollow = r.get(axis("offset"), "0") == "default"
            x, y = num(r, SUMMARY.median_us), num(r, error)
            ax.scatter(x, y, marker=SCENE_MARKERS[i % len(SCENE_MARKERS)], s=12 if budget > 0 else None,
                       facecolors="none" if hollow else color, edgecolors=color)
            ax.plot([x, num(r, SUMMARY.p99_us)], [y] * 2, color=color, lw=0.8)
            base = unbudgeted.get(where(r))
            if budget > 0 and base is not None:
                ax.plot([num(base, SUMMARY.median_us), x], [num(base, error), y], color=color, lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cycle time (µs): median, line to 99th percentile")
    ax.grid(True, which="both", alpha=0.3)


@figure(experiments=["compare-volume", "speed-vs-error"], outputs=["speed_vs_error.png"])
def speed_vs_error(results):
    loaded = [(p, results.load(p[0], SUMMARY)) for p in PANELS]
    loaded = [(p, rows) for p, rows in loaded if rows]
    if not loaded:
        return False
    fig, axes = plt.subplots(1, len(loaded), figsize=(6.2 * len(loaded) + 2.2, 5), squeeze=False)
    every = [r for _, rows in loaded for r in rows]
    scenes = sorted({scene_name(r[axis("scene")]) for r in every})
    for ax, ((experiment, error, ylabel, title), rows) in zip(axes[0], loaded):
        _panel(ax, rows, error, scenes)
        ax.set_ylabel(ylabel)
        ax.set_title(f"{title}\n({experiment})", fontsize=10)
    # One legend of the models (colour) and one of the scenes (marker), beside the panels.
    models = [Line2D([], [], marker="o", color=model_color(m), ls="", label=m) for m in models_in(every)]
    shapes = [Line2D([], [], marker=SCENE_MARKERS[i % len(SCENE_MARKERS)], color="gray", ls="", label=s)
              for i, s in enumerate(scenes)]
    fig.legend(handles=models, loc="upper right", fontsize=8, title="model")
    fig.legend(handles=shapes, loc="lower right", fontsize=8, title="scene")
    fig.suptitle("Speed against error: every model, scored by a neutral law and by the paper's own")
    results.save(fig, "speed_vs_error.png", rect=(0, 0, 1 - 2.0 / (6.2 * len(loaded) + 2.2), 0.95))
    return True
