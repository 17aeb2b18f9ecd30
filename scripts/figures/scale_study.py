"""Scale study (experiments/scale-points.yaml and scale-resolution.yaml): cycle time of every
model against pointshell size and against field resolution, shallow and deep contact, and the
memory of each body against the resolution."""
from matplotlib.ticker import FuncFormatter, NullLocator

from .common import SUMMARY, axis, figure, model_style, models_in, num, plt


@figure(experiments=["scale-points", "scale-resolution"], outputs=["scale_study.png"])
def scale_study(results):
    points = results.load("scale-points", SUMMARY)
    resolution = results.load("scale-resolution", SUMMARY)
    if not points and not resolution:
        return False
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    # Depth: solid line and filled markers shallow, dashed and hollow deep; colour and marker:
    # the model.
    depths = {"shallow": ("-", True), "deep": ("--", False)}

    # Median per model and depth, with a bar up to the 99th percentile.
    def time_panel(ax, rows, size_of, xlabel, title):
        if not rows:
            ax.text(0.5, 0.5, "no results yet", ha="center", transform=ax.transAxes)
            ax.set_title(title)
            return
        for model in models_in(rows):
            st = model_style(model)
            for depth, (ls, filled) in depths.items():
                rs = sorted((r for r in rows if r[SUMMARY.model] == model and r[axis("trajectory.depth")] == depth),
                            key=size_of)
                if not rs:
                    continue
                x = [size_of(r) for r in rs]
                med = [num(r, SUMMARY.median_us) for r in rs]
                up = [max(0.0, num(r, SUMMARY.p99_us) - m) for r, m in zip(rs, med)]
                ax.errorbar(x, med, yerr=[[0] * len(med), up], color=st["color"], ls=ls, marker=st["marker"], ms=5,
                            mfc=st["color"] if filled else "white", capsize=2, lw=1.1, elinewidth=0.7,
                            zorder=st["zorder"], label=f"{model}, {depth}")
        ax.axhline(1000, color="gray", lw=0.8, ls=":")
        ax.text(min(size_of(r) for r in rows), 1000, " 1 kHz cycle", va="bottom",
                fontsize=7, color="gray")
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("cycle time (µs): median, bar to 99th percentile")
        ax.set_title(title)
        ax.grid(True, which="both", alpha=0.3)

    # The resolution axis's label: cells, then "sparse" for a sparse field ("1024 sparse").
    def resolution_label(r):
        for key in (axis("scene.bodies[role=field].field"), axis("resolution")):
            if key in r:
                return r[key]
        raise KeyError("scene.bodies[role=field].field")

    def resolution_of(r):
        return float(resolution_label(r).split()[0])

    time_panel(axes[0], points, lambda r: num(r, SUMMARY.points), "pointshell points (dragon, body A)",
               "Cycle time against pointshell size (bunny field 128³)")
    time_panel(axes[1], resolution, resolution_of, "field resolution, cells along the longest side (bunny, body B)",
               "Cycle time against field resolution (65k points)")
    handles, labels = axes[0].get_legend_handles_labels() if points else axes[1].get_legend_handles_labels()
    fig.legend(handles, labels, fontsize=8, ncol=4, loc="lower center", bbox_to_anchor=(0.36, 0.0))

    # Memory per body: the bunny's field and the dragon's pointshell, as read by the paper's model.
    ax = axes[2]
    mem = sorted((r for r in (resolution or []) if r[SUMMARY.model] == "pointshell-linear"
                  and r[axis("trajectory.depth")] == "shallow" and num(r, SUMMARY.field_B_bytes) > 0),
                 key=resolution_of)
    if mem:
        x = [resolution_of(r) for r in mem]
        ax.plot(x, [num(r, SUMMARY.field_B_bytes) / 2**20 for r in mem], "o-", color="k",
                label="field (bunny, body B)")
        ax.plot(x, [num(r, SUMMARY.pointshell_A_bytes) / 2**20 for r in mem], "s--", color="0.55",
                label=f"pointshell (dragon, body A, {int(num(mem[0], SUMMARY.points))} points)")
        for xi, r in zip(x, mem):
            for key in (SUMMARY.field_B_bytes, SUMMARY.pointshell_A_bytes):
                ax.annotate(f"{num(r, key) / 2**20:.3g} MiB", (xi, num(r, key) / 2**20),
                            textcoords="offset points", xytext=(4, -10), fontsize=7)
        ax.legend(fontsize=7, loc="upper left")
    else:
        ax.text(0.5, 0.5, "no results with memory columns yet", ha="center", transform=ax.transAxes)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xlabel("field resolution, cells along the longest side")
    ax.set_ylabel("memory (MiB)")
    ax.set_title("Memory per body against field resolution")
    ax.grid(True, which="both", alpha=0.3)
    # Ticks at the sizes measured, written out.
    for ax, rows, size_of in ((axes[0], points, lambda r: num(r, SUMMARY.points)),
                              (axes[1], resolution, resolution_of), (axes[2], resolution, resolution_of)):
        if rows:
            ticks = sorted({size_of(r) for r in rows})
            ax.set_xticks(ticks)
            sparse = {size_of(r) for r in rows if size_of is resolution_of and "sparse" in resolution_label(r)}
            ax.set_xticklabels([f"{t:.0f}" + ("\nsparse" if t in sparse else "") for t in ticks],
                               rotation=30 if len(ticks) > 4 else 0)
            ax.xaxis.set_minor_locator(NullLocator())
            ax.set_xlim(ticks[0] / 1.4, ticks[-1] * 1.4)
    # Memory in plain numbers: every decade, and 2 and 5 times it.
    axes[2].yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axes[2].yaxis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}" if f"{v:.0e}"[0] in "25" else ""))
    results.save(fig, "scale_study.png", rect=(0, 0.1, 1, 1))
    return True
