"""Beyond the paper: every model's cycle time against its force error, per scene."""
from matplotlib.lines import Line2D

from .common import SUMMARY, axis, figure, model_color, models_in, num, plt, scene_name

SCENE_MARKERS = "osD^v<>p*"


@figure(experiments=["speed-vs-error"], outputs=["speed_vs_error.png"])
def speed_vs_error(results):
    summary = results.load("speed-vs-error", SUMMARY)
    if not summary:
        return False
    fig, ax = plt.subplots(figsize=(9.5, 5))
    scenes = sorted({r[axis("scene")] for r in summary})
    # Colour: the model; marker: the scene; hollow: the pointshell on its default offset
    # surface, filled: offset 0; a line from the median to the 99th percentile.
    for model in models_in(summary):
        color = model_color(model)
        for i, scene in enumerate(scenes):
            for r in summary:
                if r[SUMMARY.model] == model and r[axis("scene")] == scene and num(r, SUMMARY.rms_rel_error) >= 0:
                    hollow = r.get(axis("offset"), "0") == "default"
                    ax.scatter(num(r, SUMMARY.median_us), num(r, SUMMARY.rms_rel_error),
                               marker=SCENE_MARKERS[i % len(SCENE_MARKERS)],
                               facecolors="none" if hollow else color, edgecolors=color,
                               label=model if (i == 0 and not hollow) else None)
                    ax.plot([num(r, SUMMARY.median_us), num(r, SUMMARY.p99_us)], [num(r, SUMMARY.rms_rel_error)] * 2,
                            color=color, lw=0.8)
    # A second legend for the scenes (marker shapes).
    handles = [Line2D([], [], marker=SCENE_MARKERS[i % len(SCENE_MARKERS)], color="gray", ls="",
                      label=scene_name(sc)) for i, sc in enumerate(scenes)]
    ax.add_artist(ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(1.01, 0.0), fontsize=8, title="scene"))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cycle time (µs): median, line to 99th percentile")
    ax.set_ylabel("RMS relative force error vs. quadrature reference")
    ax.set_title("Speed against error (hollow: pointshell on its default offset surface)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="model")
    results.save(fig, "speed_vs_error.png")
    return True
