"""Paper Table 1: traversal statistics per scene, for rigid, deformable and defo-defo contact."""
import math
from collections import defaultdict

from .common import CYCLES, SUMMARY, axis, figure, num, scene_name


# EXPERIMENT's summary rows by scene and (model, coherence), and how often the tree model (no
# coherence) rendered each level per scene; (None, None) without results.
def table1_cells(results, experiment):
    rows = results.load(experiment, SUMMARY)
    if not rows:
        return None, None
    levels = defaultdict(lambda: defaultdict(int))
    for r in results.load(experiment, CYCLES) or []:
        if r[CYCLES.model] == "pointshell" and r.get(axis("coherence"), "false") == "false":
            levels[scene_name(r[axis("scene")])][r[CYCLES.level]] += 1
    table = defaultdict(dict)
    for r in rows:
        table[scene_name(r[axis("scene")])][(r[SUMMARY.model], r.get(axis("coherence"), "false"))] = r
    return table, levels


# The level rendered most often in a scene, or "" when none was recorded.
def usual_level(levels):
    return max(levels, key=levels.get) if levels else ""


@figure(experiments=["table1-statistics"], outputs=["table1_statistics.png", "table1_statistics.md"])
def table1_statistics(results):
    table, levels = table1_cells(results, "table1-statistics")
    if table is None:
        return False
    header = ["scene", "points", "nodes (tree)", "tree µs (median)", "tree+TC µs", "level", "tree-less µs"]
    lines = []
    for scene, cells in sorted(table.items()):
        tree = cells.get(("pointshell", "false"), {})
        tc = cells.get(("pointshell", "true"), {})
        lin = cells.get(("pointshell-linear", "false"), {})
        lines.append([scene, tree.get(SUMMARY.points, ""), f"{num(tree, SUMMARY.mean_nodes):.0f}",
                      f"{num(tree, SUMMARY.median_us):.1f}", f"{num(tc, SUMMARY.median_us):.1f}",
                      usual_level(levels[scene]), f"{num(lin, SUMMARY.median_us):.1f}"])
    results.save_table(header, lines, "Table 1: traversal statistics per scene (circling contact, 1 mm deep)",
                       "table1_statistics")
    return True


@figure(experiments=["table1-deformable"], outputs=["table1_deformable.png", "table1_deformable.md"])
def table1_deformable(results):
    table, levels = table1_cells(results, "table1-deformable")
    if table is None:
        return False
    header = ["scene", "points", "r", "StVK step µs", "nodes (tree)", "tree µs (median)", "tree+TC µs", "level",
              "tree-less µs"]
    lines = []
    for scene, cells in sorted(table.items()):
        tree = cells.get(("pointshell", "false"), {})
        tc = cells.get(("pointshell", "true"), {})
        lin = cells.get(("pointshell-linear", "false"), {})
        lines.append([scene, tree.get(SUMMARY.points, ""), tree.get(SUMMARY.modes, ""),
                      f"{num(tree, SUMMARY.median_step_us):.1f}", f"{num(tree, SUMMARY.mean_nodes):.0f}",
                      f"{num(tree, SUMMARY.median_us):.1f}", f"{num(tc, SUMMARY.median_us):.1f}",
                      usual_level(levels[scene]), f"{num(lin, SUMMARY.median_us):.1f}"])
    results.save_table(header, lines,
                       "Table 1, deformable pointshells: traversal and reduced StVK step (circling contact)",
                       "table1_deformable")
    return True


# Defo-defo rows (Fig. 13 scenes): both bodies' StVK steps, the traversal against the deformed
# distance field, and the force continuity of the circling contact. No temporal-coherence
# column: the model refuses coherence against a deformed field (rows with coherence=true, from
# older runs, are ignored).
@figure(experiments=["table1-defo-defo"], outputs=["table1_defo_defo.png", "table1_defo_defo.md"])
def table1_defo_defo(results):
    table, levels = table1_cells(results, "table1-defo-defo")
    if table is None:
        return False
    header = ["scene", "points", "r (A / B)", "StVK µs (A / B)", "nodes (tree)", "tree µs (median)",
              "tree µs (p99.9)", "level", "tree-less µs", "max jump N"]
    # p99.9 of the tree's per-cycle time, with the deformation steps (the whole cycle's work).
    cycle_us = defaultdict(list)
    for r in results.load("table1-defo-defo", CYCLES) or []:
        if r[CYCLES.model] == "pointshell" and r.get(axis("coherence"), "false") == "false":
            cycle_us[scene_name(r[axis("scene")])].append(
                num(r, CYCLES.time_us) + num(r, CYCLES.step_us) + num(r, CYCLES.step_B_us))

    def p999(values):
        v = sorted(values)
        return v[min(len(v) - 1, int(math.ceil(0.999 * len(v))) - 1)] if v else float("nan")

    lines = []
    for scene, cells in sorted(table.items()):
        tree = cells.get(("pointshell", "false"), {})
        lin = cells.get(("pointshell-linear", "false"), {})
        lines.append([scene, tree.get(SUMMARY.points, ""),
                      f"{tree.get(SUMMARY.modes, '')} / {tree.get(SUMMARY.modes_B, '')}",
                      f"{num(tree, SUMMARY.median_step_us):.1f} / {num(tree, SUMMARY.median_step_B_us):.1f}",
                      f"{num(tree, SUMMARY.mean_nodes):.0f}", f"{num(tree, SUMMARY.median_us):.1f}",
                      f"{p999(cycle_us[scene]):.1f}", usual_level(levels[scene]),
                      f"{num(lin, SUMMARY.median_us):.1f}", f"{num(tree, SUMMARY.max_jump_N):.3g}"])
    results.save_table(header, lines,
                       "Table 1, defo-defo: deformable pointshell vs deformed distance field (circling contact)",
                       "table1_defo_defo")
    return True
