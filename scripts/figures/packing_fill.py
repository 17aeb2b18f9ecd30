"""Issue 46 item 2: the inner-spheres model against the exact overlap volume as its packing fills
the bodies (packing-fill: compare-volume's scenes and motion, the coverage target of both bodies
swept from 50 to 95 %).

x is the coverage the packings reached, sqrt(fill_A fill_B) (a mesh stops below the target
once its largest free sphere is under a tenth of a cell; the summed lens volume scales with the
product of the two fills where the bodies overlap). Panels: the force magnitude ratio against
the reference (1 / ref_scale, the fitted scale onto -k_V grad V), the relative error after that
scale, and the 99th-percentile cycle time with the 1 kHz budget. Also a table per scene and
target: fills reached, ratio, calibrated error, median direction error, p99 ("no force" where
no sphere pair overlapped on the whole motion).
"""
import math

from .common import SUMMARY, axis, figure, in_order, num, plt, scene_name

COVERAGE = axis("scene.bodies[*].inner_spheres.coverage")


def reached(row):
    return math.sqrt(num(row, SUMMARY.fill_A) * num(row, SUMMARY.fill_B))


@figure(experiments=["packing-fill"], outputs=["packing_fill.png", "packing_fill_table.png", "packing_fill_table.md"])
def packing_fill(results):
    rows = [r for r in results.load("packing-fill", SUMMARY) or [] if r[SUMMARY.model] == "inner-spheres"]
    if not rows:
        return False
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    lines = []
    for scene in in_order(rows, axis("scene")):
        rs = sorted((r for r in rows if r[axis("scene")] == scene), key=reached)
        x = [100 * reached(r) for r in rs]
        name = scene_name(scene)
        axes[0].plot(x, [1 / num(r, SUMMARY.ref_scale) for r in rs], "o-", label=name)
        axes[1].plot(x, [100 * num(r, SUMMARY.rms_rel_error_calibrated) for r in rs], "o-", label=name)
        axes[2].plot(x, [num(r, SUMMARY.p99_us) for r in rs], "o-", label=name)
        for r in rs:
            # No force on the whole motion (no sphere pair ever overlapped): no scale to fit.
            felt = not math.isnan(num(r, SUMMARY.ref_scale))
            lines.append([name, f"{100 * num(r, COVERAGE):.0f}", f"{100 * num(r, SUMMARY.fill_A):.1f}",
                          f"{100 * num(r, SUMMARY.fill_B):.1f}",
                          f"{1 / num(r, SUMMARY.ref_scale):.2f}" if felt else "no force",
                          f"{100 * num(r, SUMMARY.rms_rel_error_calibrated):.1f}" if felt else "-",
                          f"{num(r, SUMMARY.median_dir_error_deg):.1f}" if felt else "-",
                          f"{num(r, SUMMARY.p99_us):.0f}"])
    axes[0].axhline(1, color="0.5", ls=":", lw=1)
    axes[0].set_ylabel("|F| / |F_ref| (1 / ref_scale)")
    axes[0].set_title("force magnitude ratio against the overlap volume")
    axes[1].set_ylabel("relative RMS error after the fitted scale (%)")
    axes[1].set_title("calibrated error")
    axes[2].axhline(1000, color="red", ls="--", lw=1, label="1 kHz budget")
    axes[2].set_yscale("log")
    axes[2].set_ylabel("99th-percentile cycle time (µs, log)")
    axes[2].set_title("cycle time")
    for a in axes:
        a.set_xlabel("coverage reached, sqrt(fill_A fill_B) (%)")
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    results.save(fig, "packing_fill.png")
    results.save_table(["scene", "target %", "fill A %", "fill B %", "force ratio", "calibrated error %",
                        "median angle °", "p99 µs"], lines,
                       "inner-spheres against the overlap volume as the packing fills", "packing_fill_table")
    return True
