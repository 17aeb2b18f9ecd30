"""Closed-loop stability (study: closed-loop): per scene, model and stiffness rule, the verdict at
each coupling stiffness and the largest stable one. With the config's `stiffness` axis (own or
matched: model.stiffness in the scene reference) each model appears at its own stiffness and at
the paper's model's, with the factor applied to its wrench."""
from collections import defaultdict

from .common import STABILITY, axis, figure, largest_stable, scene_name


@figure(experiments=["closed-loop-stability"], outputs=["closed_loop_stability.png", "closed_loop_stability.md"])
def closed_loop_stability(results):
    return stability_table(results, "closed-loop-stability", "closed_loop_stability")


@figure(experiments=["closed-loop-matched"], outputs=["closed_loop_matched.png", "closed_loop_matched.md"])
def closed_loop_matched(results):
    return stability_table(results, "closed-loop-matched", "closed_loop_matched")


@figure(experiments=["closed-loop-friction"], outputs=["closed_loop_friction.png", "closed_loop_friction.md"])
def closed_loop_friction(results):
    return stability_table(results, "closed-loop-friction", "closed_loop_friction",
                           variant=("scene.model.friction", "friction"),
                           title="; with and without Coulomb friction (static / dynamic)")


# EXPERIMENT's stability.csv as a table of verdicts, saved as NAME.png and NAME.md. VARIANT:
# (axis, column name) of a further sweep axis the rows are split by; TITLE: added to the title.
def stability_table(results, experiment, name, variant=None, title=""):
    rows = results.load(experiment, STABILITY)
    if not rows:
        return False
    # (scene, model, stiffness rule) -> k_vc -> the reasons of its unstable motions ("" when all
    # were stable); the same key -> the wrench scale.
    verdicts = defaultdict(lambda: defaultdict(list))
    scales = {}
    stiffnesses = set()
    rules = any(r.get(axis("stiffness")) for r in rows)
    for r in rows:
        rule = r.get(axis("stiffness"), "") or "own"
        if variant:
            rule = r.get(axis(variant[0]), "")
        key = (scene_name(r.get(axis("scene"), "")), r[STABILITY.model], rule)
        k = float(r[STABILITY.k_vc])
        stiffnesses.add(k)
        scales[key] = float(r[STABILITY.wrench_scale])
        verdicts[key][k]
        if r[STABILITY.stable] != "1":
            verdicts[key][k].append(f"{r[STABILITY.verdict]} ({r[STABILITY.motion]})")
    stiffnesses = sorted(stiffnesses)
    header = (["scene", "model"] + (["stiffness", "wrench scale"] if rules else []) + ([variant[1]] if variant else [])
              + [f"{k:g} N/m" for k in stiffnesses] + ["largest stable k_VC"])
    lines = []
    for key, by_k in sorted(verdicts.items()):
        scene, model, rule = key
        line = [scene, model] + ([rule, f"{scales[key]:.3g}"] if rules else []) + ([rule] if variant else [])
        line += [(", ".join(by_k[k]) or "ok") if k in by_k else "" for k in stiffnesses]
        largest = largest_stable({k: not bad for k, bad in by_k.items()})
        line.append(f"{largest:g}" if largest is not None else "none")
        lines.append(line)
    title = ("Closed-loop stability per scene and model (static virtual coupling, alpha 0.5, 1 kHz simulated; "
             "push, slide, corner)") + title
    if rules:
        title += "; stiffness matched: every model scaled to push back like the paper's model on a reference press"
    results.save_table(header, lines, title, name)
    return True
