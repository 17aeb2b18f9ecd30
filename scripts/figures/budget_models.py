"""Issue 45 item 3, the paper's Fig. 11 for every real-time model (budget-models): A pressed
20 mm past first contact and back, the scene's node_budget swept (each model's own unit).

Per model, one panel: against the budget, the relative RMS force error of the budgeted run
against the same model without a budget on the same poses (sqrt(sum |F_b - F_0|^2 / sum |F_0|^2)
over the cycles), and on a second axis the 99th-percentile cycle time with the 1 kHz budget.
A table per scene, model and budget adds the share of cycles the budget made the model degrade
(summary.csv's degraded_share).
"""
import math
from collections import defaultdict

from .common import CYCLES, SUMMARY, axis, figure, in_order, num, plt, scene_name

BUDGET = axis("node_budget")
SCENE = axis("scene")


def forces(rows):
    """(cycle -> force vector) of one run."""
    return {int(num(r, CYCLES.cycle)): (num(r, CYCLES.fx), num(r, CYCLES.fy), num(r, CYCLES.fz)) for r in rows}


def rms_error(budgeted, free):
    """Relative RMS distance of the budgeted forces from the free ones over their common cycles."""
    num_sq = den_sq = 0.0
    for c, f0 in free.items():
        fb = budgeted.get(c)
        if fb is None:
            continue
        num_sq += sum((a - b) ** 2 for a, b in zip(fb, f0))
        den_sq += sum(a * a for a in f0)
    return math.sqrt(num_sq / den_sq) if den_sq > 0 else float("nan")


@figure(experiments=["budget-models"],
        outputs=["budget_models.png", "budget_models_table.png", "budget_models_table.md"])
def budget_models(results):
    cycles = results.load("budget-models", CYCLES)
    summary = results.load("budget-models", SUMMARY)
    if not cycles or not summary:
        return False
    runs = defaultdict(list)  # (scene, model, budget) -> cycle rows
    for r in cycles:
        runs[(r[SCENE], r[CYCLES.model], int(r[BUDGET]))].append(r)
    stats = {(r[SCENE], r[SUMMARY.model], int(r[BUDGET])): r for r in summary}
    models = in_order(cycles, CYCLES.model)
    scenes = in_order(cycles, SCENE)
    columns = min(3, len(models))
    rows_of_panels = math.ceil(len(models) / columns)
    fig, axes = plt.subplots(rows_of_panels, columns, figsize=(5.2 * columns, 3.9 * rows_of_panels), squeeze=False)
    lines = []
    for i, model in enumerate(models):
        ax = axes[i // columns][i % columns]
        twin = ax.twinx()
        for k, scene in enumerate(scenes):
            free = forces(runs.get((scene, model, 0), []))
            budgets = sorted(b for (s, m, b) in runs if s == scene and m == model and b > 0)
            if not free or not budgets:
                continue
            errors = [100 * rms_error(forces(runs[(scene, model, b)]), free) for b in budgets]
            p99 = [num(stats[(scene, model, b)], SUMMARY.p99_us) if (scene, model, b) in stats else float("nan")
                   for b in budgets]
            color = f"C{k}"
            name = scene_name(scene)
            ax.plot(budgets, errors, "o-", color=color, label=name)
            twin.plot(budgets, p99, "s--", color=color, alpha=0.6)
            if (scene, model, 0) in stats:
                twin.axhline(num(stats[(scene, model, 0)], SUMMARY.p99_us), color=color, ls=":", lw=1)
            for b, e, t in zip([0] + budgets, [0.0] + errors,
                               [num(stats[(scene, model, 0)], SUMMARY.p99_us) if (scene, model, 0) in stats
                                else float("nan")] + p99):
                share = num(stats[(scene, model, b)], SUMMARY.degraded_share) if (scene, model, b) in stats else float("nan")
                lines.append([name, model, "none" if b == 0 else str(b), f"{100 * share:.0f}", f"{e:.2f}", f"{t:.0f}"])
        twin.axhline(1000, color="red", ls="--", lw=1)
        twin.set_yscale("log")
        twin.set_ylabel("p99 cycle time (µs, dashed; dotted: no budget)")
        ax.set_xscale("log")
        ax.set_xlabel("node_budget (the model's own unit)")
        ax.set_ylabel("force error against no budget (% RMS)")
        ax.set_title(model)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper right")
    for j in range(len(models), rows_of_panels * columns):
        axes[j // columns][j % columns].axis("off")
    fig.suptitle("The force error each model pays for its time budget, 20 mm deep (red: 1 kHz)")
    results.save(fig, "budget_models.png")
    results.save_table(["scene", "model", "budget", "cycles degraded %", "force error %", "p99 µs"], lines,
                       "Time budgets: force error against the unbudgeted model, and the p99 cycle time",
                       "budget_models_table")
    return True
