"""Issue 15: error against the closed-form eq. (2) limit as the pointshell grows, per shape and
sampling method (fitted order with its 95 % interval), and the force's continuity per method
along the slide (largest jump relative to the median force)."""
from collections import defaultdict

from .common import CONVERGENCE, SUMMARY, axis, figure, in_order, num, plt


@figure(experiments=["convergence-eq2"], outputs=["convergence_eq2.png"])
def convergence_eq2(results):
    rows = results.load("convergence-eq2", SUMMARY)
    if not rows:
        return False
    conv = {c[CONVERGENCE.group]: c for c in (results.load("convergence-eq2", CONVERGENCE) or [])}
    case_axis = next(k for k in rows[0] if k.startswith("scene.bodies"))
    shapes = sorted({r[case_axis] for r in rows})
    methods = in_order(rows, axis("method"))
    fig, axes = plt.subplots(1, len(shapes) + 1, figsize=(5.0 * (len(shapes) + 1), 4.2), squeeze=False)
    # One panel per shape: every sampling (seed) a dot, convergence.csv's pooled RMS per size a line.
    for i, shape in enumerate(shapes):
        ax = axes[0][i]
        for j, method in enumerate(methods):
            pts = sorted((num(r, SUMMARY.points), num(r, SUMMARY.rms_rel_error)) for r in rows
                         if r[case_axis] == shape and r[axis("method")] == method
                         and 0 <= num(r, SUMMARY.rms_rel_error) < float("inf"))
            if not pts:
                continue
            ax.loglog([p for p, _ in pts], [e for _, e in pts], ".", color=f"C{j}", alpha=0.5)
            group = next((c for g, c in conv.items() if f"={shape};" in g + ";" and f"method={method}" in g), None)
            label = method
            if group:
                order, ci = group[CONVERGENCE.fitted_order], group[CONVERGENCE.order_ci95]
                if order not in ("nan", ""):
                    label += f": order {float(order):.2f} ± {float(ci):.2f}"
                xs = [float(v) for v in group[CONVERGENCE.points].split()]
                ys = [float(v) for v in group[CONVERGENCE.errors].split()]
                ax.loglog(xs, ys, "o-", color=f"C{j}", label=label)
        ax.set_xlabel("pointshell points")
        ax.set_ylabel("RMS relative force error vs. closed-form eq. (2) limit")
        ax.set_title(f"{shape} on a halfspace (offset 0)", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    # Last panel: continuity per method and shape (mean over seeds).
    ax = axes[0][-1]
    for j, method in enumerate(methods):
        for k, shape in enumerate(shapes):
            by_n = defaultdict(list)
            for r in rows:
                if r[case_axis] == shape and r[axis("method")] == method:
                    by_n[num(r, SUMMARY.points)].append(num(r, SUMMARY.max_jump_rel))
            xs = sorted(by_n)
            ax.loglog(xs, [max(sum(by_n[x]) / len(by_n[x]), 1e-6) for x in xs], "o-" if k == 0 else "s--",
                      color=f"C{j}", label=f"{method}, {shape}", ms=4)
    ax.set_xlabel("pointshell points")
    ax.set_ylabel("largest per-cycle jump / median |F| (mean over seeds)")
    ax.set_title("continuity (press and slide), per sampling method", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    results.save(fig, "convergence_eq2.png")
    return True
