"""Issue 15: every model against a reference, per case (a sweep axis): direction error (median,
bar; p95, whisker), magnitude error after the fitted stiffness scale, and the largest per-cycle
force jump relative to the model's own median force. Against the exact overlap volume
(compare-volume, which also prints monotonicity) and against the closed-form eq. (2) limit
(analytic-cases)."""
import math
from collections import defaultdict

from .common import CYCLES, SUMMARY, axis, figure, model_color, models_in, num, plt, scene_name


def model_bars(results, experiment, axis_prefix, reference, title, out):
    rows = results.load(experiment, SUMMARY)
    if not rows:
        return False
    case_axis = next(k for k in rows[0] if k.startswith(axis_prefix))
    cases = sorted({r[case_axis] for r in rows})
    models = models_in(rows)
    panels = [(SUMMARY.median_dir_error_deg, SUMMARY.p95_dir_error_deg,
               f"angle to {reference} (°): median, whisker p95"),
              (SUMMARY.rms_rel_error_calibrated, None, "relative RMS error after the fitted scale"),
              (SUMMARY.max_jump_rel, None, "largest jump / median |F| in contact")]
    fig, axes = plt.subplots(1, len(panels), figsize=(5.0 * len(panels), 4.2), squeeze=False)
    width = 0.8 / max(1, len(models))
    for ax, (key, whisker, label) in zip(axes[0], panels):
        for j, model in enumerate(models):
            xs, ys, hi = [], [], []
            for i, case in enumerate(cases):
                for r in rows:
                    if r[case_axis] == case and r[SUMMARY.model] == model and num(r, key) >= 0:
                        xs.append(i + (j - (len(models) - 1) / 2) * width)
                        ys.append(num(r, key))
                        hi.append(num(r, whisker) - num(r, key) if whisker else 0)
            ax.bar(xs, ys, width, color=model_color(model), label=model,
                   yerr=[[0] * len(hi), hi] if whisker else None, capsize=2)
        ax.set_xticks(range(len(cases)))
        ax.set_xticklabels([scene_name(c) for c in cases], fontsize=8)
        ax.set_ylabel(label, fontsize=9)
        ax.grid(True, axis="y", alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    results.save(fig, out)
    return True


# Monotonicity along a pure approach: while the moving body presses deeper (the first half of
# an approach-press run, every cycle deeper than the one before; over these shallow presses the
# overlap volume grows with the depth), |F| should not fall. Prints, per scene and model, the
# cycles where it falls by more than 1 % of the model's median force in contact.
def monotonicity(results, experiment):
    rows = results.load(experiment, CYCLES) or []
    by = defaultdict(list)
    for r in rows:
        by[(r[axis("scene")], r[CYCLES.model])].append(r)
    for (scene, model), rs in sorted(by.items()):
        half = rs[: len(rs) // 2 + 1]
        forces = [math.hypot(num(r, CYCLES.fx), num(r, CYCLES.fy), num(r, CYCLES.fz)) for r in half]
        touching = sorted(f for f in forces if f > 0)
        if not touching:
            continue
        tol = 0.01 * touching[len(touching) // 2]
        drops = sum(1 for a, b in zip(forces, forces[1:]) if b < a - tol)
        print(f"monotonicity {scene_name(scene)} {model}: {drops} of {len(forces) - 1} pressing cycles with |F| "
              f"falling by more than 1 % of the median force")


@figure(experiments=["compare-volume"], outputs=["compare_volume.png"])
def compare_volume(results):
    made = model_bars(results, "compare-volume", "scene", "-∇V",
                      "Against the exact overlap volume (reference 'volume'), per model and scene",
                      "compare_volume.png")
    if made:
        monotonicity(results, "compare-volume")
    return made


@figure(experiments=["analytic-cases"], outputs=["analytic_cases.png"])
def analytic_cases(results):
    return model_bars(results, "analytic-cases", "scene.bodies", "the limit",
                      "Against the closed-form eq. (2) limit (reference 'eq2-halfspace'), per model and case",
                      "analytic_cases.png")
