"""What the haptic rate buys (study: closed-loop, swept over model.cycle_seconds): per model, the
largest stable coupling stiffness against the rate (the simulated counterpart of Choi & Tan's
perceived-stiffness curve) and the largest force jump from one cycle to the next against the
rate; one row of panels per scene and damping rule (alpha per 1 ms, or per cycle when the config
sweeps loop.alpha_per_cycle)."""
from collections import defaultdict

from .common import STABILITY, axis, figure, largest_stable, model_line, models_in, plt, scene_name


@figure(experiments=["closed-loop-rate"], outputs=["closed_loop_rate.png", "closed_loop_rate_table.png", "closed_loop_rate_table.md"])
def closed_loop_rate(results):
    rows = results.load("closed-loop-rate", STABILITY)
    if not rows:
        return False
    def group(r):
        damping = "alpha per cycle" if r.get(axis("alpha_per_cycle"), "false") == "true" else "alpha per 1 ms"
        scene = scene_name(r.get(axis("scene"), ""))  # empty: the config's one scene (no scene axis)
        return f"{scene}, {damping}" if scene else damping

    scenes = sorted({group(r) for r in rows})
    models = models_in(rows, STABILITY.model)
    # (scene, model, rate) -> k_vc -> all motions stable; and the largest force jump per cycle
    # over the motions at the smallest stiffness swept.
    stable = defaultdict(lambda: defaultdict(lambda: True))
    jumps = defaultdict(dict)
    k_min = min(float(r[STABILITY.k_vc]) for r in rows)
    for r in rows:
        key = (group(r), r[STABILITY.model], float(r[STABILITY.rate_hz]))
        k = float(r[STABILITY.k_vc])
        stable[key][k] = stable[key][k] and r[STABILITY.stable] == "1"
        if k == k_min:
            jumps[key][r[STABILITY.motion]] = float(r[STABILITY.max_force_jump_N])
    rates = sorted({key[2] for key in stable})
    k_max = max(float(r[STABILITY.k_vc]) for r in rows)

    fig, axes = plt.subplots(len(scenes), 2, figsize=(11, 3.6 * len(scenes)), squeeze=False)
    lines = []
    for i, scene in enumerate(scenes):
        for model in models:
            ks, js = [], []
            for rate in rates:
                key = (scene, model, rate)
                if key not in stable:
                    ks.append(None)
                    js.append(None)
                    continue
                largest = largest_stable(stable[key])
                ks.append(largest)
                js.append(max(jumps[key].values()) if jumps[key] else None)
                lines.append([scene, model, f"{rate:g}", f"{largest:g}" if largest else "none",
                              f"{js[-1]:.4g}" if js[-1] is not None else ""])
            xs = [x for x, k in zip(rates, ks) if k]
            axes[i][0].plot(xs, [k for k in ks if k], **model_line(model, len(xs), markevery=1))
            xj = [x for x, j in zip(rates, js) if j is not None]
            axes[i][1].plot(xj, [j for j in js if j is not None], **model_line(model, len(xj), markevery=1))
        ax = axes[i][0]
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.axhline(k_max, color="0.6", lw=0.8, ls=":")
        ax.set_xlabel("haptic rate (Hz)")
        ax.set_ylabel("largest stable k_VC (N/m)")
        ax.set_title(f"{scene}: largest stable coupling (top line: largest swept)", fontsize=9)
        ax = axes[i][1]
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("haptic rate (Hz)")
        ax.set_ylabel("largest force jump per cycle (N)")
        ax.set_title(f"{scene}: force jump per cycle at k_VC = {k_min:g} N/m", fontsize=9)
    handles, labels = axes[0][1].get_legend_handles_labels()
    fig.legend(handles, labels, loc="center right", fontsize=8)
    results.save(fig, "closed_loop_rate.png", rect=(0, 0, 0.84, 1))
    results.save_table(["scene, damping", "model", "rate Hz", "largest stable k_VC", f"max jump N at {k_min:g} N/m"], lines,
                       "Closed-loop stability against the haptic rate (alpha 0.5; push, slide, corner)",
                       "closed_loop_rate_table")
    return True
