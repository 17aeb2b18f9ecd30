"""Issue 61, item 6: a preloaded peg pulled out of a hole against friction
(experiments/extraction-friction.yaml), per model and role order, against the closed form of a
peg in a hole under radial preload.

With a contact per pointshell point and no stiffness scaling (L: 0), each point of the overlap
pushes with k_C d along the hole's radius, so the summed normal load is k_C d n A: d the radial
interference, n the pointshell's points per unit area, A = 2 pi r L(s) the overlapping wall (r
the radius the points sit on, L(s) the length of peg inside the hole after a pull of s). While
the peg sticks, friction rises to mu_s times that load; while it slides, it is mu_d times it.
The friction force is the pull's force with friction less the frictionless run's at the same
cycle (which holds what the ends' normal forces do along the axis)."""
import math
from collections import defaultdict

from .common import CYCLES, axis, figure, model_line, models_in, num, plt

EXPERIMENT = "extraction-friction"
FRICTION = axis("scene.model.friction")
ROLES = axis("roles")

# The config's geometry, m: the peg (capsule:R,H; 64 segments, scene_assets.cc), the hole (a
# tube:OUTER,BORE,H_HOLE,192), both centred at the origin; the pointshells' points; k_C, N/m.
PEG_R, PEG_H, PEG_SEGMENTS = 0.004, 0.008, 64
BORE_R, BORE_SEGMENTS, HOLE_OUTER, HOLE_H = 0.0039, 192, 0.008, 0.005
PEG_POINTS, HOLE_POINTS, K_C = 4096, 8192, 1000.0
# The models with a contact per point of the configured pointshell (the closed form's n); VPS
# has one per voxel of its voxmap, FCL and Bullet one per triangle pair.
PER_POINT = {"pointshell", "pointshell-linear", "vps-repulsion"}
# Pulls (m) over which the peg slides with all of it in the hole (L = 2 HOLE_H), and over which
# L falls by one metre per metre of pull (the peg's lower end in the hole, its cap not yet).
FULL_OVERLAP = (0.001, PEG_H - HOLE_H)
SHRINKING = (PEG_H - HOLE_H + 0.0005, PEG_H + HOLE_H - 0.0015)


def mean_radius(vertex_radius, segments):
    """The mean distance from the axis over the sides of a regular polygon of SEGMENTS sides
    with its vertices at VERTEX_RADIUS (the faceted meshes' radius as their points see it)."""
    a = vertex_radius * math.cos(math.pi / segments)  # apothem
    b = vertex_radius * math.sin(math.pi / segments)  # half a side
    return (b * vertex_radius + a * a * math.log((b + vertex_radius) / a)) / (2 * b)


INTERFERENCE = mean_radius(PEG_R, PEG_SEGMENTS) - mean_radius(BORE_R, BORE_SEGMENTS)


def overlap(s):
    """The length of the peg's cylinder inside the hole after a pull of S along +z."""
    return max(0.0, min(HOLE_H, PEG_H + s) - max(-HOLE_H, -PEG_H + s))


def load_per_length(role):
    """The closed form's normal load per metre of overlap, N/m: k_C d n 2 pi r for the body whose
    pointshell touches (the peg in the normal order, the hole's bore when swapped)."""
    if role == "normal":
        area = 2 * math.pi * PEG_R * 2 * PEG_H + 4 * math.pi * PEG_R ** 2
        return K_C * INTERFERENCE * PEG_POINTS / area * 2 * math.pi * PEG_R
    area = 2 * math.pi * (HOLE_OUTER + BORE_R) * 2 * HOLE_H + 2 * math.pi * (HOLE_OUTER ** 2 - BORE_R ** 2)
    return K_C * INTERFERENCE * HOLE_POINTS / area * 2 * math.pi * BORE_R


def coefficients(label):
    """(mu_s, mu_d) of a friction label "S / D"; ValueError for any other."""
    parts = label.split("/")
    if len(parts) != 2:
        raise ValueError(f"{EXPERIMENT}: friction label '{label}' is not 'static / dynamic'")
    return float(parts[0]), float(parts[1])


def friction_curves(rows):
    """{(role, model, label): ([pull m], [friction force N])}: the force opposing the pull with
    friction LABEL less the frictionless run's at the same cycle."""
    runs = defaultdict(dict)  # (role, model, label) -> cycle -> (pull, force opposing the pull)
    for r in rows:
        key = (r.get(ROLES, "normal"), r[CYCLES.model], r[FRICTION])
        runs[key][int(num(r, CYCLES.cycle))] = (num(r, CYCLES.z), -num(r, CYCLES.fz))
    curves = {}
    for (role, model, label), by_cycle in runs.items():
        if label == "none":
            continue
        base = runs.get((role, model, "none"))
        if base is None:
            raise ValueError(f"{EXPERIMENT}: {model} ({role}) has no frictionless run to subtract")
        cycles = sorted(c for c in by_cycle if c in base)
        curves[(role, model, label)] = ([by_cycle[c][0] for c in cycles],
                                        [by_cycle[c][1] - base[c][1] for c in cycles])
    return curves


def median(values):
    v = sorted(values)
    if not v:
        return math.nan
    return 0.5 * (v[(len(v) - 1) // 2] + v[len(v) // 2])


def slope(xs, ys):
    """Least-squares slope of YS against XS."""
    n = len(xs)
    if n < 2:
        return math.nan
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else math.nan


def within(pulls, forces, span):
    return [(s, f) for s, f in zip(pulls, forces) if span[0] <= s <= span[1]]


def error_cell(value, reference):
    return f"{100 * (value / reference - 1):+.1f} %" if reference and math.isfinite(value) else "-"


@figure(experiments=[EXPERIMENT], outputs=["extraction_friction.png", "extraction_friction.md"])
def extraction_friction(results):
    rows = results.load(EXPERIMENT, CYCLES)
    if not rows:
        return False
    curves = friction_curves(rows)
    roles = sorted({k[0] for k in curves})
    labels = sorted({k[2] for k in curves}, key=lambda lab: coefficients(lab)[1])
    fig, axes = plt.subplots(1, len(roles), figsize=(6 * len(roles), 4.4), squeeze=False)
    header = ["roles", "model", "friction", "stick peak (N)", "vs mu_s load", "sliding, whole peg in (N)",
              "vs mu_d load", "fall per mm of pull (N/mm)", "vs closed form"]
    lines = []
    for ax, role in zip(axes[0], roles):
        per_length = load_per_length(role)
        for label in labels:
            mu_s, mu_d = coefficients(label)
            strongest = label == labels[-1]
            for model in models_in(rows):
                key = (role, model, label)
                if key not in curves:
                    continue
                pulls, forces = curves[key]
                if strongest:
                    ax.plot([1000 * s for s in pulls], forces, **model_line(model, len(pulls)))
                closed = model in PER_POINT
                stick = [f for s, f in zip(pulls, forces) if s < FULL_OVERLAP[0]]
                peak = max(stick) if stick else math.nan
                full = median([f for _, f in within(pulls, forces, FULL_OVERLAP)])
                falling = within(pulls, forces, SHRINKING)
                fall = -slope([s for s, _ in falling], [f for _, f in falling]) / 1000
                whole = per_length * 2 * HOLE_H
                lines.append([role, model, label, f"{peak:.3g}", error_cell(peak, mu_s * whole) if closed else "-",
                              f"{full:.3g}", error_cell(full, mu_d * whole) if closed else "-", f"{fall:.3g}",
                              error_cell(fall, mu_d * per_length / 1000) if closed else "-"])
            if strongest:
                grid = [i * 0.0001 for i in range(int(round((PEG_H + HOLE_H) / 0.0001)) + 1)]
                ax.plot([1000 * s for s in grid], [mu_d * per_length * overlap(s) for s in grid], color="k",
                        ls="--", lw=1.0, label=f"closed form, mu_d {mu_d:g} (per-point models)")
        ax.axhline(0, color="k", lw=0.6)
        ax.set_xlabel("pull along the hole's axis (mm)")
        ax.set_ylabel(f"friction force opposing the pull (N), friction {labels[-1]}")
        ax.set_title(f"peg r {1000 * PEG_R:g} mm in a {1000 * BORE_R:g} mm hole: "
                     + ("peg = pointshell" if role == "normal" else "hole = pointshell"), fontsize=10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    results.save(fig, "extraction_friction.png")
    results.save_markdown(header, lines, "extraction_friction")
    return True
