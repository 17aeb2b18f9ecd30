#!/usr/bin/python3
"""Makes every figure of ContactLab's experiments from the files under results/.

Reads only results/<experiment>/{cycles,summary,convergence,field_error,field_slice}.csv (written by
`contactlab run`) and writes PNG figures, with labelled axes and units, to
results/figures/. An experiment whose results are missing is skipped with a note.

Usage: scripts/make_figures.py [--results DIR]
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FuncFormatter, NullLocator  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(row, key):
    v = row.get(key, "")
    return float(v) if v not in ("", None) else math.nan


class Figures:
    def __init__(self, results):
        self.results = results
        self.out = os.path.join(results, "figures")
        os.makedirs(self.out, exist_ok=True)
        self.made = []

    def load(self, name, kind):
        path = os.path.join(self.results, name, kind + ".csv")
        if not os.path.exists(path):
            return None
        return read_csv(path)

    # RECT (left, bottom, right, top, figure fraction): where tight_layout puts the axes, leaving
    # room for a figure legend.
    def save(self, fig, name, rect=None):
        path = os.path.join(self.out, name)
        tmp = path + ".tmp.png"
        fig.tight_layout(rect=rect)
        fig.savefig(tmp, dpi=110)
        plt.close(fig)
        os.replace(tmp, path)
        self.made.append(path)

    # A table as a figure (NAME.png) and as Markdown (NAME.md).
    def save_table(self, header, lines, title, name, width):
        fig, ax = plt.subplots(figsize=(width, 0.6 + 0.45 * len(lines)))
        ax.axis("off")
        t = ax.table(cellText=lines, colLabels=header, loc="center")
        t.auto_set_font_size(False)
        t.set_fontsize(9)
        t.scale(1, 1.4)
        ax.set_title(title)
        self.save(fig, name + ".png")
        md = os.path.join(self.out, name + ".md")
        with open(md + ".tmp", "w") as f:
            f.write("| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n")
            for line in lines:
                f.write("| " + " | ".join(str(c) for c in line) + " |\n")
        os.replace(md + ".tmp", md)
        self.made.append(md)

    # Paper Fig. 5(b): error against the eq. (2) limit as the pointshell grows.
    def fig05b(self):
        rows = self.load("fig05b-convergence", "summary")
        if not rows:
            return False
        conv = self.load("fig05b-convergence", "convergence") or []
        fig, ax = plt.subplots(figsize=(6, 4.2))
        by_model = defaultdict(list)
        for r in rows:
            by_model[r["model"]].append((num(r, "points"), num(r, "rms_rel_error")))
        for model, pts in by_model.items():
            pts.sort()
            ax.loglog([p for p, _ in pts], [e for _, e in pts], "o-", label=model)
        for c in conv:
            ax.text(0.05, 0.08, f"fitted order {float(c['fitted_order']):.2f}", transform=ax.transAxes)
        ax.set_xlabel("pointshell points")
        ax.set_ylabel("RMS relative force error vs. limit")
        ax.set_title("Fig. 5(b): convergence to the volume-integral limit")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
        self.save(fig, "fig05b_convergence.png")
        return True

    # Issue 15: error against the closed-form eq. (2) limit as the pointshell grows, per shape
    # and sampling method (fitted order with its 95 % interval), and the force's continuity per
    # method along the slide (largest jump relative to the median force, high-frequency share).
    def convergence_eq2(self):
        rows = self.load("convergence-eq2", "summary")
        if not rows:
            return False
        conv = {c["group"]: c for c in (self.load("convergence-eq2", "convergence") or [])}
        axis = next(k for k in rows[0] if k.startswith("scene.bodies"))
        shapes = sorted({r[axis] for r in rows})
        methods = []
        for r in rows:
            if r["method"] not in methods:
                methods.append(r["method"])
        fig, axes = plt.subplots(1, len(shapes) + 1, figsize=(5.0 * (len(shapes) + 1), 4.2), squeeze=False)
        for i, shape in enumerate(shapes):
            ax = axes[0][i]
            for j, method in enumerate(methods):
                # Each sampling (seed) a dot; the line is convergence.csv's pooled RMS per size.
                pts = sorted((num(r, "points"), num(r, "rms_rel_error")) for r in rows
                             if r[axis] == shape and r["method"] == method and 0 <= num(r, "rms_rel_error") < float("inf"))
                if not pts:
                    continue
                ax.loglog([p for p, _ in pts], [e for _, e in pts], ".", color=f"C{j}", alpha=0.5)
                group = next((c for g, c in conv.items() if f"={shape};" in g + ";" and f"method={method}" in g), None)
                label = method
                if group:
                    if group["fitted_order"] not in ("nan", ""):
                        label += f": order {float(group['fitted_order']):.2f} ± {float(group['order_ci95']):.2f}"
                    xs = [float(v) for v in group["points"].split()]
                    ys = [float(v) for v in group["errors"].split()]
                    ax.loglog(xs, ys, "o-", color=f"C{j}", label=label)
            ax.set_xlabel("pointshell points")
            ax.set_ylabel("RMS relative force error vs. closed-form eq. (2) limit")
            ax.set_title(f"{shape} on a halfspace (offset 0)", fontsize=10)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        ax = axes[0][-1]
        for j, method in enumerate(methods):
            for k, shape in enumerate(shapes):
                by_n = defaultdict(list)
                for r in rows:
                    if r[axis] == shape and r["method"] == method:
                        by_n[num(r, "points")].append(num(r, "max_jump_rel"))
                xs = sorted(by_n)
                ax.loglog(xs, [max(sum(by_n[x]) / len(by_n[x]), 1e-6) for x in xs], "o-" if k == 0 else "s--",
                          color=f"C{j}", label=f"{method}, {shape}", ms=4)
        ax.set_xlabel("pointshell points")
        ax.set_ylabel("largest per-cycle jump / median |F| (mean over seeds)")
        ax.set_title("continuity (press and slide), per sampling method", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        self.save(fig, "convergence_eq2.png")
        return True

    # Paper Fig. 11: cycle time, nodes and level on a recorded trajectory, with and without budget.
    def fig11(self):
        rows = self.load("fig11-degradation", "cycles")
        if not rows:
            return False
        fig, axes = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
        groups = defaultdict(list)
        for r in rows:
            groups[r["node_budget"]].append(r)
        for budget, rs in sorted(groups.items(), key=lambda kv: int(kv[0])):
            label = "no budget" if budget == "0" else f"budget {budget} nodes"
            t = [num(r, "t") for r in rs]
            axes[0].plot(t, [num(r, "time_us") for r in rs], lw=0.6, label=label)
            axes[1].plot(t, [num(r, "nodes") for r in rs], lw=0.6, label=label)
            axes[2].plot(t, [num(r, "level") for r in rs], lw=0.9, label=label)
        axes[0].set_ylabel("cycle time (µs)")
        axes[1].set_ylabel("nodes visited")
        axes[2].set_ylabel("level rendered")
        axes[2].set_xlabel("time (s)")
        axes[0].set_title("Fig. 11: graceful degradation on a recorded trajectory")
        for a in axes:
            a.grid(True, alpha=0.3)
            a.legend(fontsize=8)
        self.save(fig, "fig11_degradation.png")
        return True

    # Paper Fig. 14(b): force while scanning the bumps, per pointshell size.
    def fig14b(self):
        rows = self.load("fig14b-bumps", "cycles")
        if not rows:
            return False
        fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
        groups = defaultdict(list)
        for r in rows:
            groups[int(r["points"])].append(r)
        for points, rs in sorted(groups.items()):
            x = [1000 * num(r, "x") for r in rs]
            axes[0].plot(x, [num(r, "fz") for r in rs], lw=0.8, label=f"{points} points")
            axes[1].plot(x, [num(r, "fx") for r in rs], lw=0.8, label=f"{points} points")
        axes[0].set_ylabel("normal force $F_z$ (N)")
        axes[1].set_ylabel("tangential force $F_x$ (N)")
        axes[1].set_xlabel("scan position x (mm)")
        axes[0].set_title("Fig. 14(b): scanning bumps with progressively finer pointshells")
        for a in axes:
            a.grid(True, alpha=0.3)
            a.legend(fontsize=8)
        self.save(fig, "fig14b_bumps.png")
        return True

    # Paper Fig. 15: force under role reversal against penetration depth in voxels.
    def fig15(self):
        rows = self.load("fig15-asymmetry", "cycles")
        if not rows:
            return False
        fig, axes = plt.subplots(1, 2, figsize=(11, 4))
        angle_axis = axes[1].twinx()
        by = defaultdict(dict)
        for r in rows:
            by[(r["resolution"], r["model"])].setdefault(r["roles"], []).append(r)
        for (res, model), roles in sorted(by.items()):
            if "normal" not in roles or "swapped" not in roles:
                continue
            a, b = roles["normal"], roles["swapped"]
            t = [num(r, "t") for r in a]
            axes[0].plot(t, [math.hypot(num(r, "fx"), num(r, "fy"), num(r, "fz")) for r in a], lw=0.9,
                         label=f"{res}³, moving dragon = field")
            axes[0].plot(t, [math.hypot(num(r, "fx"), num(r, "fy"), num(r, "fz")) for r in b], "--", lw=0.9,
                         label=f"{res}³, moving dragon = pointshell")
            # Both roles follow the same motion (one placement): the magnitudes' difference and
            # the angle between the two forces, against the depth of the config's role order.
            depth, diff, angle = [], [], []
            for ra, rb in zip(a, b):
                fa = (num(ra, "fx"), num(ra, "fy"), num(ra, "fz"))
                fb = (num(rb, "fx"), num(rb, "fy"), num(rb, "fz"))
                na, nb = math.hypot(*fa), math.hypot(*fb)
                if na > 1e-9 and nb > 1e-9:
                    depth.append(num(ra, "depth_voxels"))
                    diff.append(abs(na - nb) / max(na, nb))
                    cos = sum(x * y for x, y in zip(fa, fb)) / (na * nb)
                    angle.append(math.degrees(math.acos(max(-1.0, min(1.0, cos)))))
            line = axes[1].plot(depth, diff, ".", ms=3, label=f"field {res}³: magnitude")[0]
            angle_axis.plot(depth, angle, "x", ms=2, alpha=0.35, color=line.get_color(),
                            label=f"field {res}³: angle")
        axes[0].set_xlabel("time (s)")
        axes[0].set_ylabel("|F| on the moving dragon (N)")
        axes[0].set_title("Fig. 15: role reversal")
        axes[1].axvline(1.0, color="0.4", ls=":", lw=0.8)
        axes[1].text(1.0, 1.0, " one voxel (paper: a few % within it)", fontsize=7, color="0.3", va="top")
        axes[1].set_xlabel("penetration depth (field voxels), both roles on the same motion")
        axes[1].set_ylabel("||F₁| − |F₂|| / max(|F₁|, |F₂|)  (dots)")
        axes[1].set_ylim(0, 1)
        angle_axis.set_ylabel("angle between F₁ and F₂ (°, crosses)")
        angle_axis.set_ylim(0, 60)
        axes[1].set_title("asymmetry against depth (same motion)")
        for a in axes:
            a.grid(True, alpha=0.3)
            a.legend(fontsize=8)
        self.save(fig, "fig15_asymmetry.png")
        return True

    # Table 1's summary rows of EXPERIMENT by scene and (model, coherence), and the most
    # frequent level the tree model rendered per scene; (None, None) without results.
    def table1_cells(self, experiment):
        rows = self.load(experiment, "summary")
        if not rows:
            return None, None
        levels = defaultdict(lambda: defaultdict(int))
        for r in self.load(experiment, "cycles") or []:
            if r["model"] == "pointshell" and r["coherence"] == "false":
                levels[os.path.splitext(os.path.basename(r["scene"]))[0]][r["level"]] += 1
        table = defaultdict(dict)
        for r in rows:
            table[os.path.splitext(os.path.basename(r["scene"]))[0]][(r["model"], r["coherence"])] = r
        return table, levels

    # Paper Table 1: statistics per scene.
    def table1(self):
        table, levels = self.table1_cells("table1-statistics")
        if table is None:
            return False
        header = ["scene", "points", "nodes (tree)", "tree µs (median)", "tree+TC µs", "level", "tree-less µs"]
        lines = []
        for scene, cells in sorted(table.items()):
            tree = cells.get(("pointshell", "false"), {})
            tc = cells.get(("pointshell", "true"), {})
            lin = cells.get(("pointshell-linear", "false"), {})
            lines.append([scene, tree.get("points", ""), f"{num(tree, 'mean_nodes'):.0f}",
                          f"{num(tree, 'median_us'):.1f}", f"{num(tc, 'median_us'):.1f}",
                          max(levels[scene], key=levels[scene].get) if levels[scene] else "",
                          f"{num(lin, 'median_us'):.1f}"])
        self.save_table(header, lines, "Table 1: traversal statistics per scene (circling contact, 1 mm deep)",
                        "table1_statistics", 9)
        return True

    # Paper sec. 4.1: the deformable pointshell two-way coupled, on a cantilever pressed by a probe.
    def deformable_cantilever(self):
        rows = self.load("deformable-cantilever", "cycles")
        summary = self.load("deformable-cantilever", "summary")
        if not rows or not summary:
            return False
        fig, axes = plt.subplots(1, 3, figsize=(14, 4))
        for cells in sorted({r["cells"] for r in rows}, key=int):
            rs = [r for r in rows if r["cells"] == cells and r["model"] == "pointshell"]
            t = [num(r, "t") for r in rs]
            axes[0].plot(t, [1e3 * num(r, "max_displacement") for r in rs], lw=0.9, label=f"{cells} cells")
            axes[1].plot(t, [num(r, "fz") for r in rs], lw=0.9, label=f"{cells} cells")
        axes[0].set_ylabel("largest displacement, free end (mm)")
        axes[0].set_title("beam deflection")
        axes[1].set_ylabel("contact force on the probe, z (N)")
        axes[1].set_title("contact force")
        for a in axes[:2]:
            a.set_xlabel("time (s)")
        tree = [r for r in summary if r["model"] == "pointshell"]
        lin = {r["cells"]: r for r in summary if r["model"] == "pointshell-linear"}
        x = [int(r["cells"]) for r in tree]
        axes[2].plot(x, [num(r, "median_us") for r in tree], "o-", label="tree traversal")
        axes[2].plot(x, [num(lin.get(r["cells"], {}), "median_us") for r in tree], "s-", label="tree-less")
        axes[2].plot(x, [num(r, "median_step_us") for r in tree], "^-", label="reduced StVK step")
        axes[2].set_xlabel("simulation mesh cells along the beam")
        axes[2].set_ylabel("median time per cycle (µs)")
        axes[2].set_yscale("log")
        axes[2].set_title("cycle cost")
        for a in axes:
            a.grid(True, alpha=0.3)
            a.legend(fontsize=8)
        self.save(fig, "deformable_cantilever.png")
        return True

    # Paper Table 1, deformable rows.
    def table1_deformable(self):
        table, levels = self.table1_cells("table1-deformable")
        if table is None:
            return False
        header = ["scene", "points", "r", "StVK step µs", "nodes (tree)", "tree µs (median)", "tree+TC µs", "level",
                  "tree-less µs"]
        lines = []
        for scene, cells in sorted(table.items()):
            tree = cells.get(("pointshell", "false"), {})
            tc = cells.get(("pointshell", "true"), {})
            lin = cells.get(("pointshell-linear", "false"), {})
            lines.append([scene, tree.get("points", ""), tree.get("modes", ""), f"{num(tree, 'median_step_us'):.1f}",
                          f"{num(tree, 'mean_nodes'):.0f}", f"{num(tree, 'median_us'):.1f}",
                          f"{num(tc, 'median_us'):.1f}",
                          max(levels[scene], key=levels[scene].get) if levels[scene] else "",
                          f"{num(lin, 'median_us'):.1f}"])
        self.save_table(header, lines,
                        "Table 1, deformable pointshells: traversal and reduced StVK step (circling contact)",
                        "table1_deformable", 11)
        return True

    # Paper Table 1, defo-defo rows (Fig. 13 scenes): both bodies' StVK steps, the traversal
    # against the deformed distance field, and the force continuity of the circling contact.
    def table1_defo_defo(self):
        table, levels = self.table1_cells("table1-defo-defo")
        if table is None:
            return False
        # No temporal-coherence column: the model refuses coherence against a deformed field.
        header = ["scene", "points", "r (A / B)", "StVK µs (A / B)", "nodes (tree)", "tree µs (median)",
                  "tree µs (p99.9)", "level", "tree-less µs", "max jump N"]
        # p99.9 of the tree's per-cycle time, with the deformation steps (the whole cycle's work).
        cycle_us = defaultdict(list)
        for r in self.load("table1-defo-defo", "cycles") or []:
            if r["model"] == "pointshell":
                cycle_us[os.path.splitext(os.path.basename(r["scene"]))[0]].append(
                    num(r, "time_us") + num(r, "step_us") + num(r, "step_B_us"))
        def p999(values):
            v = sorted(values)
            return v[min(len(v) - 1, int(math.ceil(0.999 * len(v))) - 1)] if v else float("nan")
        lines = []
        for scene, cells in sorted(table.items()):
            tree = cells.get(("pointshell", "false"), {})
            lin = cells.get(("pointshell-linear", "false"), {})
            lines.append([scene, tree.get("points", ""), f"{tree.get('modes', '')} / {tree.get('modes_B', '')}",
                          f"{num(tree, 'median_step_us'):.1f} / {num(tree, 'median_step_B_us'):.1f}",
                          f"{num(tree, 'mean_nodes'):.0f}", f"{num(tree, 'median_us'):.1f}",
                          f"{p999(cycle_us[scene]):.1f}",
                          max(levels[scene], key=levels[scene].get) if levels[scene] else "",
                          f"{num(lin, 'median_us'):.1f}", f"{num(tree, 'max_jump_N'):.3g}"])
        self.save_table(header, lines,
                        "Table 1, defo-defo: deformable pointshell vs deformed distance field (circling contact)",
                        "table1_defo_defo", 11)
        return True

    # Paper Fig. 10: the deformed distance field against the exact deformed distance.
    def fig10(self):
        error = self.load("fig10-deformed-field", "field_error")
        slices = self.load("fig10-deformed-field", "field_slice") or []
        if not error:
            return False
        by_job = {r["job"]: r for r in error}

        def pose(r):  # the pose's largest displacement as a fraction of the body's size
            return num(r, "max_displacement_m") / num(r, "body_size_m")

        def option(r):  # how the domains were made
            n = r["domains"]
            return "1 domain" if n == "1" else (f"{n} planes/boxes" if r["domain_kind"] == "regions" else f"{n} k-means")

        slice_jobs = sorted({r["job"] for r in slices}, key=int)
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
            rows = [r for r in slices if r["job"] == job]
            ni = max(int(r["i"]) for r in rows) + 1
            nj = max(int(r["j"]) for r in rows) + 1
            axes_xyz = [a for a in "xyz" if len({r[a] for r in rows}) > 1]  # the plane's axes vary
            grid = {k: [[math.nan] * ni for _ in range(nj)] for k in axes_xyz + ["exact_m", "approx_m"]}
            for r in rows:
                for k in grid:
                    grid[k][int(r["j"])][int(r["i"])] = num(r, k)
            h = num(e, "cell_m")
            ax = fig.add_subplot(gs[row, col])
            u, v = grid[axes_xyz[0]], grid[axes_xyz[1]]
            ax.contourf(u, v, grid["approx_m"], levels=[-1e9, 0], colors=["#b8e0b0"])
            levels = [0, 2 * h, 5 * h]
            ax.contour(u, v, grid["exact_m"], levels=levels, colors="C0", linewidths=1.1, linestyles="solid")
            ax.contour(u, v, grid["approx_m"], levels=levels, colors="C3", linewidths=1.1, linestyles="dashed")
            ax.set_title(f"pose: feet moved {100 * pose(e):.0f}% of height; {option(e)}\n"
                         f"{e['proxies']} proxies, k = {e['neighbours']}: band RMS {num(e, 'rms_cells'):.2f}, "
                         f"max {num(e, 'max_cells'):.2f} cells", fontsize=8)
            ax.set_xlabel(f"{axes_xyz[0]} (m)")
            ax.set_ylabel(f"{axes_xyz[1]} (m)")
            ax.set_aspect("equal")
            if row == 0 and col == 0:
                from matplotlib.lines import Line2D
                from matplotlib.patches import Patch
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
        for c, (key, label, target) in enumerate([("rms_cells", "RMS", 0.5), ("max_cells", "largest", None)]):
            ax = fig.add_subplot(gs[nrows - 1, c])
            for r in error:
                filled = all_poses.index(round(pose(r), 3)) == 0
                color = f"C{all_options.index(option(r))}"
                ax.scatter(num(r, "query_ns"), num(r, key), marker=markers.get(r["neighbours"], "D"),
                           s=10 + 0.8 * num(r, "proxies"), facecolors=color if filled else "none", edgecolors=color)
            for i, o in enumerate(all_options):
                ax.scatter([], [], color=f"C{i}", label=o)
            for k, m in markers.items():
                if any(r["neighbours"] == k for r in error):
                    ax.scatter([], [], color="gray", marker=m, label=f"k = {k}")
            if target:
                ax.axhline(target, color="gray", lw=0.7, ls=":")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("query time (ns; mean over the band points)")
            ax.set_ylabel(f"{label} error, band |d| ≤ 2 cells (cells)")
            sizes = ", ".join(sorted({r["proxies"] for r in error}, key=int))
            poses_text = " / ".join(f"{100 * p:.0f}%" for p in all_poses)
            ax.set_title(f"{label} error vs query time (filled / hollow: pose {poses_text};\n"
                         f"marker size: {sizes} proxies)", fontsize=8)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=7)
        self.save(fig, "fig10_deformed_field.png")
        return True

    # Beyond the paper: continuity across models.
    def continuity(self):
        rows = self.load("continuity-models", "cycles")
        summary = self.load("continuity-models", "summary")
        if not rows or not summary:
            return False
        scenes = sorted({r["scene"] for r in rows})
        fig, axes = plt.subplots(len(scenes), 2, figsize=(11, 3.6 * len(scenes)), squeeze=False)
        for i, scene in enumerate(scenes):
            groups = defaultdict(list)
            for r in rows:
                if r["scene"] == scene:
                    groups[r["model"]].append(r)
            for model, rs in groups.items():
                axes[i][0].plot([num(r, "t") for r in rs],
                                [math.hypot(num(r, "fx"), num(r, "fy"), num(r, "fz")) for r in rs], lw=0.7,
                                label=model)
            name = os.path.splitext(os.path.basename(scene))[0]
            axes[i][0].set_title(f"{name}: |F| while sliding")
            axes[i][0].set_xlabel("time (s)")
            axes[i][0].set_ylabel("|F| (N)")
            axes[i][0].legend(fontsize=8)
            s = [r for r in summary if r["scene"] == scene]
            axes[i][1].bar([r["model"] for r in s], [num(r, "max_jump_N") for r in s])
            axes[i][1].set_ylabel("largest per-cycle force jump (N)")
            axes[i][1].set_title(f"{name}: force continuity")
            axes[i][1].tick_params(axis="x", rotation=30)
            for a in axes[i]:
                a.grid(True, alpha=0.3)
        self.save(fig, "continuity_models.png")
        return True

    # Beyond the paper: speed against error.
    def speed_vs_error(self):
        summary = self.load("speed-vs-error", "summary")
        if not summary:
            return False
        fig, ax = plt.subplots(figsize=(9.5, 5))
        markers = "osD^v<>p*"
        scenes = sorted({r["scene"] for r in summary})
        models = sorted({r["model"] for r in summary})
        for j, model in enumerate(models):
            for i, scene in enumerate(scenes):
                for r in summary:
                    if r["model"] == model and r["scene"] == scene and num(r, "rms_rel_error") >= 0:
                        # Hollow markers: the pointshell on its default offset surface; filled: offset 0.
                        hollow = r.get("offset", "0") == "default"
                        ax.scatter(num(r, "median_us"), num(r, "rms_rel_error"), marker=markers[i % len(markers)],
                                   facecolors="none" if hollow else f"C{j}", edgecolors=f"C{j}",
                                   label=model if (i == 0 and not hollow) else None)
                        ax.plot([num(r, "median_us"), num(r, "p99_us")], [num(r, "rms_rel_error")] * 2,
                                color=f"C{j}", lw=0.8)
        # A second legend for the scenes (marker shapes).
        from matplotlib.lines import Line2D
        handles = [Line2D([], [], marker=markers[i % len(markers)], color="gray", ls="",
                          label=os.path.splitext(os.path.basename(sc))[0]) for i, sc in enumerate(scenes)]
        ax.add_artist(ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(1.01, 0.0), fontsize=8,
                                title="scene"))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("cycle time (µs): median, line to 99th percentile")
        ax.set_ylabel("RMS relative force error vs. quadrature reference")
        ax.set_title("Speed against error (hollow: pointshell on its default offset surface)")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="model")
        self.save(fig, "speed_vs_error.png")
        return True


    # Issue 20, hard cases pushed through: per role order, every model's force opposing the push
    # against the depth, over the pressing half of the run (until DEEPEST picks the deepest
    # cycle), with dotted lines at MARKS [(depth, label)].
    def push_through(self, experiment, depth_of, force_of, deepest, marks, xlabel, ylabel, titles, out):
        rows = self.load(experiment, "cycles")
        if not rows:
            return False
        by = defaultdict(list)
        for r in rows:
            by[(r.get("roles", "normal"), r["model"])].append(r)
        orders = sorted({k[0] for k in by})
        fig, axes = plt.subplots(1, len(orders), figsize=(5.5 * len(orders), 4.2), squeeze=False)
        for ax, order in zip(axes[0], orders):
            for (o, model), rs in sorted(by.items()):
                if o != order:
                    continue
                rs = rs[: deepest(rs) + 1]
                ax.plot([depth_of(r) for r in rs], [force_of(r) for r in rs], lw=1.0, label=model,
                        ls="--" if model.endswith("-linear") else "-")
            for d, what in marks:
                ax.axvline(d, color="0.5", ls=":", lw=0.8)
                ax.text(d, 0, " " + what, rotation=90, va="bottom", fontsize=7, color="0.4")
            ax.axhline(0, color="k", lw=0.6)
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            ax.set_title(titles[order == "normal"], fontsize=10)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=8)
        self.save(fig, out)
        return True

    # A ball pushed through a thin plate: the force on the ball along the push against the depth
    # of its lowest point below the plate's top.
    def hard_cases_medial_axis(self):
        top = 0.002 + 0.01  # ball centre when its lowest point touches the plate's top face, m
        return self.push_through(
            "hard-cases-medial-axis", lambda r: 1000 * (top - num(r, "z")), lambda r: num(r, "fz"),
            lambda rs: min(range(len(rs)), key=lambda i: num(rs[i], "z")),
            [(2, "lowest point at mid-plane"), (12, "centre at mid-plane")],
            "depth of the ball's lowest point below the plate's top (mm)",
            "force on the ball along +z, opposing the push (N)",
            {True: "ball r 1 cm through a 4 mm plate: ball = pointshell",
             False: "ball r 1 cm through a 4 mm plate: ball = field"},
            "hard_cases_medial_axis.png")

    # A thin-walled tube over a peg pushed sideways into it and on through its 0.5 mm wall: the
    # force on the tube opposing the push against the depth.
    def hard_cases_tube_peg(self):
        touch = 0.0015  # tube offset along x where its inner wall touches the peg, m
        return self.push_through(
            "hard-cases-tube-peg", lambda r: 1000 * (num(r, "x") - touch), lambda r: -num(r, "fx"),
            lambda rs: max(range(len(rs)), key=lambda i: num(rs[i], "x")),
            [(0.25, "wall mid-surface in the peg"), (0.5, "wall through the peg's side")],
            "depth of the tube's inner wall in the peg (mm)",
            "force on the tube along -x, opposing the push (N)",
            {True: "tube (wall 0.5 mm) pushed into a peg: tube = pointshell",
             False: "tube (wall 0.5 mm) pushed into a peg: tube = field"},
            "hard_cases_tube_peg.png")

    # Issue 15: every model against a reference, per case (a sweep axis): direction error
    # (median, bar; p95, whisker), magnitude error after the fitted stiffness scale, and the
    # largest per-cycle force jump relative to the model's own median force.
    def model_bars(self, experiment, axis_prefix, reference, title, out):
        rows = self.load(experiment, "summary")
        if not rows:
            return False
        axis = next(k for k in rows[0] if k.startswith(axis_prefix))
        cases = sorted({r[axis] for r in rows})
        models = []
        for r in rows:
            if r["model"] not in models:
                models.append(r["model"])
        panels = [("median_dir_error_deg", "p95_dir_error_deg", f"angle to {reference} (°): median, whisker p95"),
                  ("rms_rel_error_calibrated", None, "relative RMS error after the fitted scale"),
                  ("max_jump_rel", None, "largest jump / median |F| in contact")]
        fig, axes = plt.subplots(1, len(panels), figsize=(5.0 * len(panels), 4.2), squeeze=False)
        width = 0.8 / max(1, len(models))
        for ax, (key, whisker, label) in zip(axes[0], panels):
            for j, model in enumerate(models):
                xs, ys, hi = [], [], []
                for i, case in enumerate(cases):
                    for r in rows:
                        if r[axis] == case and r["model"] == model and num(r, key) >= 0:
                            xs.append(i + (j - (len(models) - 1) / 2) * width)
                            ys.append(num(r, key))
                            hi.append(num(r, whisker) - num(r, key) if whisker else 0)
                ax.bar(xs, ys, width, color=f"C{j}", label=model,
                       yerr=[[0] * len(hi), hi] if whisker else None, capsize=2)
            ax.set_xticks(range(len(cases)))
            ax.set_xticklabels([os.path.splitext(os.path.basename(c))[0] for c in cases], fontsize=8)
            ax.set_ylabel(label, fontsize=9)
            ax.grid(True, axis="y", alpha=0.3)
        axes[0][0].legend(fontsize=7)
        fig.suptitle(title, fontsize=10)
        self.save(fig, out)
        return True

    def compare_volume(self):
        made = self.model_bars("compare-volume", "scene", "-∇V",
                               "Against the exact overlap volume (reference 'volume'), per model and scene",
                               "compare_volume.png")
        if made:
            self.monotonicity("compare-volume")
        return made

    # Monotonicity along a pure approach: while the moving body presses deeper (the first half
    # of an approach-press run, every cycle deeper than the one before; over these shallow
    # presses the overlap volume grows with the depth), |F| should not fall. Prints, per scene and model, the cycles where it falls by
    # more than 1 % of the model's median force in contact.
    def monotonicity(self, experiment):
        rows = self.load(experiment, "cycles")
        by = defaultdict(list)
        for r in rows:
            by[(r["scene"], r["model"])].append(r)
        for (scene, model), rs in sorted(by.items()):
            half = rs[: len(rs) // 2 + 1]
            forces = [math.hypot(num(r, "fx"), num(r, "fy"), num(r, "fz")) for r in half]
            touching = sorted(f for f in forces if f > 0)
            if not touching:
                continue
            tol = 0.01 * touching[len(touching) // 2]
            drops = sum(1 for a, b in zip(forces, forces[1:]) if b < a - tol)
            name = os.path.splitext(os.path.basename(scene))[0]
            print(f"monotonicity {name} {model}: {drops} of {len(forces) - 1} pressing cycles with |F| falling "
                  f"by more than 1 % of the median force")

    def analytic_cases(self):
        return self.model_bars("analytic-cases", "scene.bodies", "the limit",
                               "Against the closed-form eq. (2) limit (reference 'eq2-halfspace'), per model and case",
                               "analytic_cases.png")

    # Issue 15, role reversal on identical motion, every model: per scene and model the median
    # relative difference of the force magnitudes and the median angle between the two forces
    # over the cycles where both orders have a force (printed, and bars).
    def asymmetry_models(self):
        rows = self.load("asymmetry-models", "cycles")
        if not rows:
            return False
        by = defaultdict(list)
        for r in rows:
            by[(r["scene"], r["model"], r["roles"])].append(r)
        scenes = sorted({k[0] for k in by})
        models = []
        for r in rows:
            if r["model"] not in models:
                models.append(r["model"])
        fig, axes = plt.subplots(1, 2, figsize=(10, 4.0))
        width = 0.8 / max(1, len(models))
        for i, scene in enumerate(scenes):
            for j, model in enumerate(models):
                a, b = by.get((scene, model, "normal"), []), by.get((scene, model, "swapped"), [])
                mags, angles = [], []
                for ra, rb in zip(a, b):
                    fa = [num(ra, c) for c in ("fx", "fy", "fz")]
                    fb = [num(rb, c) for c in ("fx", "fy", "fz")]
                    na, nb = math.hypot(*fa), math.hypot(*fb)
                    if na > 1e-9 and nb > 1e-9:
                        mags.append(abs(na - nb) / max(na, nb))
                        cos = sum(x * y for x, y in zip(fa, fb)) / (na * nb)
                        angles.append(math.degrees(math.acos(max(-1.0, min(1.0, cos)))))
                if not mags:
                    continue
                mags.sort()
                angles.sort()
                mag, ang = mags[len(mags) // 2], angles[len(angles) // 2]
                name = os.path.splitext(os.path.basename(scene))[0]
                print(f"asymmetry {name} {model}: median magnitude difference {mag:.3f}, median angle {ang:.2f} deg "
                      f"({len(mags)} cycles)")
                x = i + (j - (len(models) - 1) / 2) * width
                axes[0].bar(x, mag, width, color=f"C{j}", label=model if i == 0 else None)
                axes[1].bar(x, ang, width, color=f"C{j}")
        for ax, label in zip(axes, ["median ||F₁| − |F₂|| / max", "median angle between F₁ and F₂ (°)"]):
            ax.set_xticks(range(len(scenes)))
            ax.set_xticklabels([os.path.splitext(os.path.basename(sc))[0] for sc in scenes], fontsize=8)
            ax.set_ylabel(label)
            ax.grid(True, axis="y", alpha=0.3)
        axes[0].legend(fontsize=7)
        fig.suptitle("Role reversal on identical motion, every model", fontsize=10)
        self.save(fig, "asymmetry_models.png")
        return True

    # Issue 15, tessellation invariance: per model, how much the force changes between two
    # meshes of one shape at the same poses: RMS |F_coarse - F_fine| / RMS |F_fine| over the
    # cycles (printed, and a bar per shape), and the force on both meshes over time.
    def tessellation(self):
        rows = self.load("tessellation", "cycles")
        if not rows:
            return False
        axis = next(k for k in rows[0] if k.startswith("scene.bodies"))
        by = defaultdict(list)
        for r in rows:
            by[(r[axis], r["model"])].append(r)
        meshes = sorted({k[0] for k in by})
        models = []
        for r in rows:
            if r["model"] not in models:
                models.append(r["model"])
        # Pairs of labels "SHAPE-COUNT": coarse (fewer triangles) then fine.
        shapes = defaultdict(list)
        for m in meshes:
            shape, count = m.rsplit("-", 1)
            shapes[shape].append((int(count), m))
        fig, axes = plt.subplots(1, 1 + len(shapes), figsize=(5.0 * (1 + len(shapes)), 4.0), squeeze=False)
        width = 0.8 / max(1, len(models))
        for i, (shape, pair) in enumerate(sorted(shapes.items())):
            (_, coarse), (_, fine) = sorted(pair)[0], sorted(pair)[-1]
            for j, model in enumerate(models):
                a, b = by.get((coarse, model), []), by.get((fine, model), [])
                if not a or len(a) != len(b):
                    continue
                diff = sum(sum((num(x, c) - num(y, c)) ** 2 for c in ("fx", "fy", "fz")) for x, y in zip(a, b))
                ref = sum(sum(num(y, c) ** 2 for c in ("fx", "fy", "fz")) for y in b)
                change = math.sqrt(diff / ref) if ref > 0 else float("nan")
                print(f"tessellation {shape} {coarse} vs {fine} {model}: RMS |dF| / RMS |F| = {change:.4f}")
                axes[0][0].bar(i + (j - (len(models) - 1) / 2) * width, change, width, color=f"C{j}",
                               label=model if i == 0 else None)
                ax = axes[0][1 + i]
                t = [num(r, "t") for r in b]
                ax.plot(t, [math.hypot(num(r, "fx"), num(r, "fy"), num(r, "fz")) for r in b], color=f"C{j}", lw=0.9,
                        label=f"{model}, {fine}")
                ax.plot(t, [math.hypot(num(r, "fx"), num(r, "fy"), num(r, "fz")) for r in a], color=f"C{j}", lw=0.9,
                        ls="--")
            axes[0][1 + i].set_title(f"{shape}: solid {fine}, dashed {coarse}", fontsize=9)
            axes[0][1 + i].set_xlabel("time (s)")
            axes[0][1 + i].set_ylabel("|F| on the tool (N)")
            axes[0][1 + i].grid(True, alpha=0.3)
            axes[0][1 + i].legend(fontsize=6)
        axes[0][0].set_xticks(range(len(shapes)))
        axes[0][0].set_xticklabels(sorted(shapes), fontsize=8)
        axes[0][0].set_ylabel("RMS |F_coarse - F_fine| / RMS |F_fine|")
        axes[0][0].set_title("Tessellation invariance (same poses)", fontsize=10)
        axes[0][0].grid(True, axis="y", alpha=0.3)
        axes[0][0].legend(fontsize=7)
        self.save(fig, "tessellation.png")
        return True


    # Scale study (experiments/scale-points.yaml and scale-resolution.yaml): cycle time of every
    # model against pointshell size and against field resolution, shallow and deep contact, and
    # the memory of each body against the resolution.
    def scale_study(self):
        points = self.load("scale-points", "summary")
        resolution = self.load("scale-resolution", "summary")
        if not points and not resolution:
            return False
        fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
        models = ["pointshell", "pointshell-linear", "fcl", "bullet"]
        styles = {"shallow": ("-", "o"), "deep": ("--", "s")}

        # Median per model and depth, with a bar up to the 99th percentile.
        def time_panel(ax, rows, size_of, xlabel, title):
            if not rows:
                ax.text(0.5, 0.5, "no results yet", ha="center", transform=ax.transAxes)
                ax.set_title(title)
                return
            extra = sorted({r["model"] for r in rows} - set(models))
            for j, model in enumerate(models + extra):
                for depth, (ls, marker) in styles.items():
                    rs = sorted((r for r in rows if r["model"] == model and r["trajectory.depth"] == depth), key=size_of)
                    if not rs:
                        continue
                    x = [size_of(r) for r in rs]
                    med = [num(r, "median_us") for r in rs]
                    up = [max(0.0, num(r, "p99_us") - m) for r, m in zip(rs, med)]
                    ax.errorbar(x, med, yerr=[[0] * len(med), up], color=f"C{j}", ls=ls, marker=marker, ms=4,
                                capsize=2, lw=1.1, elinewidth=0.7, label=f"{model}, {depth}")
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
            for key in ("scene.bodies[role=field].field", "resolution"):
                if key in r:
                    return r[key]
            raise KeyError("scene.bodies[role=field].field")

        def resolution_of(r):
            return float(resolution_label(r).split()[0])

        time_panel(axes[0], points, lambda r: num(r, "points"), "pointshell points (dragon, body A)",
                   "Cycle time against pointshell size (bunny field 128³)")
        time_panel(axes[1], resolution, resolution_of, "field resolution, cells along the longest side (bunny, body B)",
                   "Cycle time against field resolution (65k points)")
        handles, labels = axes[0].get_legend_handles_labels() if points else axes[1].get_legend_handles_labels()
        fig.legend(handles, labels, fontsize=8, ncol=4, loc="lower center", bbox_to_anchor=(0.36, 0.0))

        # Memory per body: the bunny's field and the dragon's pointshell, as read by the paper's model.
        ax = axes[2]
        mem = sorted((r for r in (resolution or []) if r["model"] == "pointshell-linear" and r["trajectory.depth"] == "shallow"
                      and num(r, "field_B_bytes") > 0), key=resolution_of)
        if mem:
            x = [resolution_of(r) for r in mem]
            ax.plot(x, [num(r, "field_B_bytes") / 2**20 for r in mem], "o-", color="C0", label="field (bunny, body B)")
            ax.plot(x, [num(r, "pointshell_A_bytes") / 2**20 for r in mem], "s--", color="C1",
                    label=f"pointshell (dragon, body A, {int(num(mem[0], 'points'))} points)")
            for xi, r in zip(x, mem):
                for key in ("field_B_bytes", "pointshell_A_bytes"):
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
        for ax, rows, size_of in ((axes[0], points, lambda r: num(r, "points")), (axes[1], resolution, resolution_of),
                                  (axes[2], resolution, resolution_of)):
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
        self.save(fig, "scale_study.png", rect=(0, 0.1, 1, 1))
        return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default=os.path.join(os.path.dirname(__file__), "..", "results"))
    args = parser.parse_args()
    figs = Figures(os.path.abspath(args.results))
    for name in ["fig05b", "convergence_eq2", "fig10", "fig11", "fig14b", "fig15", "table1", "table1_deformable", "table1_defo_defo",
                 "deformable_cantilever",
                 "continuity", "speed_vs_error", "compare_volume", "analytic_cases", "asymmetry_models", "tessellation", "hard_cases_medial_axis", "hard_cases_tube_peg",
                 "scale_study"]:
        try:
            if not getattr(figs, name)():
                print(f"make_figures: {name}: no results yet (run its experiment first)", file=sys.stderr)
        except (KeyError, ValueError) as e:
            print(f"make_figures: {name}: results are malformed: {e}", file=sys.stderr)
            return 1
    for path in figs.made:
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
