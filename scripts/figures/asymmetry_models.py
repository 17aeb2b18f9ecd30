"""Issue 15, role reversal on identical motion, every model: per scene and model the median
relative difference of the force magnitudes and the median angle between the two forces over
the cycles where both orders have a force (printed, and bars)."""
import math
from collections import defaultdict

from .common import CYCLES, axis, figure, model_color, models_in, num, plt, scene_name


@figure(experiments=["asymmetry-models"], outputs=["asymmetry_models.png"])
def asymmetry_models(results):
    rows = results.load("asymmetry-models", CYCLES)
    if not rows:
        return False
    by = defaultdict(list)
    for r in rows:
        by[(r[axis("scene")], r[CYCLES.model], r[axis("roles")])].append(r)
    scenes = sorted({k[0] for k in by})
    models = models_in(rows)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.0))
    width = 0.8 / max(1, len(models))
    for i, scene in enumerate(scenes):
        for j, model in enumerate(models):
            a, b = by.get((scene, model, "normal"), []), by.get((scene, model, "swapped"), [])
            mags, angles = [], []
            for ra, rb in zip(a, b):
                fa = [num(ra, c) for c in (CYCLES.fx, CYCLES.fy, CYCLES.fz)]
                fb = [num(rb, c) for c in (CYCLES.fx, CYCLES.fy, CYCLES.fz)]
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
            print(f"asymmetry {scene_name(scene)} {model}: median magnitude difference {mag:.3f}, "
                  f"median angle {ang:.2f} deg ({len(mags)} cycles)")
            x = i + (j - (len(models) - 1) / 2) * width
            axes[0].bar(x, mag, width, color=model_color(model), label=model if i == 0 else None)
            axes[1].bar(x, ang, width, color=model_color(model))
    for ax, label in zip(axes, ["median ||F₁| − |F₂|| / max", "median angle between F₁ and F₂ (°)"]):
        ax.set_xticks(range(len(scenes)))
        ax.set_xticklabels([scene_name(sc) for sc in scenes], fontsize=8)
        ax.set_ylabel(label)
        ax.grid(True, axis="y", alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle("Role reversal on identical motion, every model", fontsize=10)
    results.save(fig, "asymmetry_models.png")
    return True
