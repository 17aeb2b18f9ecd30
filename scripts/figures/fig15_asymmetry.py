"""Paper Fig. 15: force under role reversal, and its asymmetry against penetration depth in voxels."""
import math
from collections import defaultdict

from .common import CYCLES, axis, figure, num, plt


@figure(experiments=["fig15-asymmetry"], outputs=["fig15_asymmetry.png"])
def fig15_asymmetry(results):
    rows = results.load("fig15-asymmetry", CYCLES)
    if not rows:
        return False
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    angle_axis = axes[1].twinx()
    by = defaultdict(dict)
    for r in rows:
        by[(r[axis("resolution")], r[CYCLES.model])].setdefault(r[axis("roles")], []).append(r)
    for (res, model), roles in sorted(by.items()):
        if "normal" not in roles or "swapped" not in roles:
            continue
        a, b = roles["normal"], roles["swapped"]
        t = [num(r, CYCLES.t) for r in a]
        axes[0].plot(t, [math.hypot(num(r, CYCLES.fx), num(r, CYCLES.fy), num(r, CYCLES.fz)) for r in a], lw=0.9,
                     label=f"{res}³, moving dragon = field")
        axes[0].plot(t, [math.hypot(num(r, CYCLES.fx), num(r, CYCLES.fy), num(r, CYCLES.fz)) for r in b], "--", lw=0.9,
                     label=f"{res}³, moving dragon = pointshell")
        # Both roles follow the same motion (one placement): the magnitudes' difference and
        # the angle between the two forces, against the depth of the config's role order.
        depth, diff, angle = [], [], []
        for ra, rb in zip(a, b):
            fa = (num(ra, CYCLES.fx), num(ra, CYCLES.fy), num(ra, CYCLES.fz))
            fb = (num(rb, CYCLES.fx), num(rb, CYCLES.fy), num(rb, CYCLES.fz))
            na, nb = math.hypot(*fa), math.hypot(*fb)
            if na > 1e-9 and nb > 1e-9:
                depth.append(num(ra, CYCLES.depth_voxels))
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
    results.save(fig, "fig15_asymmetry.png")
    return True
