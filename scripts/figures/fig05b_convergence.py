"""Paper Fig. 5(b): error against the eq. (2) limit as the pointshell grows."""
from collections import defaultdict

from .common import CONVERGENCE, SUMMARY, figure, model_line, models_in, num, plt


@figure(experiments=["fig05b-convergence"], outputs=["fig05b_convergence.png"])
def fig05b_convergence(results):
    rows = results.load("fig05b-convergence", SUMMARY)
    if not rows:
        return False
    conv = results.load("fig05b-convergence", CONVERGENCE) or []
    fig, ax = plt.subplots(figsize=(6, 4.2))
    by_model = defaultdict(list)
    for r in rows:
        by_model[r[SUMMARY.model]].append((num(r, SUMMARY.points), num(r, SUMMARY.rms_rel_error)))
    for model in models_in(rows):
        pts = sorted(by_model[model])
        ax.loglog([p for p, _ in pts], [e for _, e in pts], **model_line(model, len(pts), markevery=None))
    for c in conv:
        ax.text(0.05, 0.08, f"fitted order {float(c[CONVERGENCE.fitted_order]):.2f}", transform=ax.transAxes)
    ax.set_xlabel("pointshell points")
    ax.set_ylabel("RMS relative force error vs. limit")
    ax.set_title("Fig. 5(b): convergence to the volume-integral limit")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    results.save(fig, "fig05b_convergence.png")
    return True
