"""Closed-loop stability (study: closed-loop): per scene and model, the verdict at each coupling
stiffness and the largest stable one."""
from collections import defaultdict

from .common import STABILITY, axis, figure, largest_stable, scene_name


@figure(experiments=["closed-loop-stability"], outputs=["closed_loop_stability.png", "closed_loop_stability.md"])
def closed_loop_stability(results):
    rows = results.load("closed-loop-stability", STABILITY)
    if not rows:
        return False
    # (scene, model) -> k_vc -> the reasons of its unstable motions ("" when all were stable).
    verdicts = defaultdict(lambda: defaultdict(list))
    stiffnesses = set()
    for r in rows:
        key = (scene_name(r.get(axis("scene"), "")), r[STABILITY.model])
        k = float(r[STABILITY.k_vc])
        stiffnesses.add(k)
        verdicts[key][k]
        if r[STABILITY.stable] != "1":
            verdicts[key][k].append(f"{r[STABILITY.verdict]} ({r[STABILITY.motion]})")
    stiffnesses = sorted(stiffnesses)
    header = ["scene", "model"] + [f"{k:g} N/m" for k in stiffnesses] + ["largest stable k_VC"]
    lines = []
    for (scene, model), by_k in sorted(verdicts.items()):
        line = [scene, model] + [(", ".join(by_k[k]) or "ok") if k in by_k else "" for k in stiffnesses]
        largest = largest_stable({k: not bad for k, bad in by_k.items()})
        line.append(f"{largest:g}" if largest is not None else "none")
        lines.append(line)
    results.save_table(header, lines, "Closed-loop stability per scene and model (static virtual coupling, "
                       "alpha 0.5, 1 kHz simulated; push, slide, corner)", "closed_loop_stability")
    return True
