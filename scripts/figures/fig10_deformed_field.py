"""Paper Fig. 10: the deformed distance field against the exact deformed distance: isocontours
on a slice per pose and domain option, and the contact-band error against query time."""
import math

from matplotlib.lines import Line2D
from matplotlib.patches import Patch

from .common import FIELD_ERROR, FIELD_SLICE, figure, num, plt


@figure(experiments=["fig10-deformed-field"], outputs=["fig10_deformed_field.png"])
def fig10_deformed_field(results):
    error = results.load("fig10-deformed-field", FIELD_ERROR)
    slices = results.load("fig10-deformed-field", FIELD_SLICE) or []
    if not error:
        return False
    by_job = {r[FIELD_ERROR.job]: r for r in error}

    def pose(r):  # the pose's largest displacement as a fraction of the body's size
        return num(r, FIELD_ERROR.max_displacement_m) / num(r, FIELD_ERROR.body_size_m)

    def option(r):  # how the domains were made
        n = r[FIELD_ERROR.domains]
        if n == "1":
            return "1 domain"
        return f"{n} planes/boxes" if r[FIELD_ERROR.domain_kind] == "regions" else f"{n} k-means"

    slice_jobs = sorted({r[FIELD_SLICE.job] for r in slices}, key=int)
    poses = sorted({round(pose(by_job[j]), 3) for j in slice_jobs})
    options = []
    for j in slice_jobs:
        if option(by_job[j]) not in options:
            options.append(option(by_job[j]))
    ncols = max(2, len(options))
    nrows = len(poses) + 1
    fig = plt.figure(figsize=(4.4 * ncols, 3.2 * len(poses) + 4.4))
    gs = fig.add_gridspec(nrows, ncols, height_ratios=[3.2] * len(poses) + [4.4])
    # (a) Isocontours on the slice: exact solid, approximate dashed, approximate inside shaded.
    for job in slice_jobs:
        e = by_job[job]
        row, col = poses.index(round(pose(e), 3)), options.index(option(e))
        rows = [r for r in slices if r[FIELD_SLICE.job] == job]
        ni = max(int(r[FIELD_SLICE.i]) for r in rows) + 1
        nj = max(int(r[FIELD_SLICE.j]) for r in rows) + 1
        xyz = (FIELD_SLICE.x, FIELD_SLICE.y, FIELD_SLICE.z)
        axes_xyz = [a for a in xyz if len({r[a] for r in rows}) > 1]  # the plane's axes vary
        grid = {k: [[math.nan] * ni for _ in range(nj)] for k in axes_xyz + [FIELD_SLICE.exact_m, FIELD_SLICE.approx_m]}
        for r in rows:
            for k in grid:
                grid[k][int(r[FIELD_SLICE.j])][int(r[FIELD_SLICE.i])] = num(r, k)
        h = num(e, FIELD_ERROR.cell_m)
        ax = fig.add_subplot(gs[row, col])
        u, v = grid[axes_xyz[0]], grid[axes_xyz[1]]
        ax.contourf(u, v, grid[FIELD_SLICE.approx_m], levels=[-1e9, 0], colors=["#b8e0b0"])
        levels = [0, 2 * h, 5 * h]
        ax.contour(u, v, grid[FIELD_SLICE.exact_m], levels=levels, colors="C0", linewidths=1.1, linestyles="solid")
        ax.contour(u, v, grid[FIELD_SLICE.approx_m], levels=levels, colors="C3", linewidths=1.1, linestyles="dashed")
        ax.set_title(f"pose: feet moved {100 * pose(e):.0f}% of height; {option(e)}\n"
                     f"{e[FIELD_ERROR.proxies]} proxies, k = {e[FIELD_ERROR.neighbours]}: "
                     f"band RMS {num(e, FIELD_ERROR.rms_cells):.2f}, "
                     f"max {num(e, FIELD_ERROR.max_cells):.2f} cells", fontsize=8)
        ax.set_xlabel(f"{axes_xyz[0]} (m)")
        ax.set_ylabel(f"{axes_xyz[1]} (m)")
        ax.set_aspect("equal")
        if row == 0 and col == 0:
            ax.legend(handles=[Line2D([], [], color="C0", label="exact: d = 0, 2, 5 cells"),
                               Line2D([], [], color="C3", ls="--", label="approximate"),
                               Patch(color="#b8e0b0", label="inside (approximate)")], fontsize=7, loc="upper right")
    # (b) Contact-band error against query time over proxies x k x domains, per pose.
    markers = {"3": "v", "4": "s", "5": "o", "8": "^"}
    all_options = []
    for r in error:
        if option(r) not in all_options:
            all_options.append(option(r))
    all_poses = sorted({round(pose(r), 3) for r in error})
    panels = [(FIELD_ERROR.rms_cells, "RMS", 0.5), (FIELD_ERROR.max_cells, "largest", None)]
    for c, (key, label, target) in enumerate(panels):
        ax = fig.add_subplot(gs[nrows - 1, c])
        for r in error:
            filled = all_poses.index(round(pose(r), 3)) == 0
            color = f"C{all_options.index(option(r))}"
            ax.scatter(num(r, FIELD_ERROR.query_ns), num(r, key), marker=markers.get(r[FIELD_ERROR.neighbours], "D"),
                       s=10 + 0.8 * num(r, FIELD_ERROR.proxies), facecolors=color if filled else "none",
                       edgecolors=color)
        for i, o in enumerate(all_options):
            ax.scatter([], [], color=f"C{i}", label=o)
        for k, m in markers.items():
            if any(r[FIELD_ERROR.neighbours] == k for r in error):
                ax.scatter([], [], color="gray", marker=m, label=f"k = {k}")
        if target:
            ax.axhline(target, color="gray", lw=0.7, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("query time (ns; mean over the band points)")
        ax.set_ylabel(f"{label} error, band |d| ≤ 2 cells (cells)")
        sizes = ", ".join(sorted({r[FIELD_ERROR.proxies] for r in error}, key=int))
        poses_text = " / ".join(f"{100 * p:.0f}%" for p in all_poses)
        ax.set_title(f"{label} error vs query time (filled / hollow: pose {poses_text};\n"
                     f"marker size: {sizes} proxies)", fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    results.save(fig, "fig10_deformed_field.png")
    return True
