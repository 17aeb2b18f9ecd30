"""Paper Fig. 3's setting (study: many-bodies): a rigid part slid between two deformable hoses.
Per model: the force each pair puts on its body B and the net force on the part along the
trajectory, each hose's largest displacement, and the world's cycle time with the pairs near."""
from collections import defaultdict

from .common import WORLD_BODIES, WORLD_CYCLES, WORLD_PAIRS, WORLD_SUMMARY, figure, in_order, num, plt

EXPERIMENT = "fig03-hoses"


@figure(experiments=[EXPERIMENT], outputs=["fig03_hoses.png", "fig03_hoses_table.png", "fig03_hoses_table.md"])
def fig03_hoses(results):
    cycles = results.load(EXPERIMENT, WORLD_CYCLES)
    pairs = results.load(EXPERIMENT, WORLD_PAIRS) or []
    bodies = results.load(EXPERIMENT, WORLD_BODIES) or []
    summary = results.load(EXPERIMENT, WORLD_SUMMARY) or []
    if not cycles:
        return False
    models = in_order(cycles, WORLD_CYCLES.model)
    fig, axes = plt.subplots(len(models), 3, figsize=(15, 3.8 * len(models)), squeeze=False)
    for i, model in enumerate(models):
        mine = [r for r in cycles if r[WORLD_CYCLES.model] == model and r[WORLD_CYCLES.job] == cycles[0][WORLD_CYCLES.job]]
        t = [num(r, WORLD_CYCLES.t) for r in mine]
        # (a) Each pair's force on its B, and the net force on the part: the hoses' pushes cancel.
        ax = axes[i][0]
        by_pair = defaultdict(lambda: ([], []))
        for r in pairs:
            if r[WORLD_PAIRS.model] != model or r[WORLD_PAIRS.job] != mine[0][WORLD_CYCLES.job]:
                continue
            f = (num(r, WORLD_PAIRS.fx) ** 2 + num(r, WORLD_PAIRS.fy) ** 2 + num(r, WORLD_PAIRS.fz) ** 2) ** 0.5
            key = f"{r[WORLD_PAIRS.body_a]} on {r[WORLD_PAIRS.body_b]} ({r[WORLD_PAIRS.pair_model]})"
            by_pair[key][0].append(num(r, WORLD_PAIRS.t))
            by_pair[key][1].append(f)
        for key, (ts, fs) in by_pair.items():
            ax.plot(ts, fs, lw=1.1, label=key)
        net = [(num(r, WORLD_CYCLES.fx) ** 2 + num(r, WORLD_CYCLES.fy) ** 2 + num(r, WORLD_CYCLES.fz) ** 2) ** 0.5
               for r in mine]
        ax.plot(t, net, "k--", lw=1.0, label="net on the tool")
        ax.set_yscale("symlog", linthresh=0.05)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("|F| (N)")
        ax.set_title(f"{model}: force of each near pair on its B")
        ax.legend(fontsize=7)
        # (b) How far each hose gives way, and where the part is along them.
        ax = axes[i][1]
        by_body = defaultdict(lambda: ([], []))
        for r in bodies:
            if r[WORLD_BODIES.model] != model or r[WORLD_BODIES.job] != mine[0][WORLD_CYCLES.job]:
                continue
            by_body[r[WORLD_BODIES.body]][0].append(num(r, WORLD_BODIES.t))
            by_body[r[WORLD_BODIES.body]][1].append(1e3 * num(r, WORLD_BODIES.max_displacement))
        for body, (ts, us) in by_body.items():
            ax.plot(ts, us, lw=1.1, label=body)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("largest displacement (mm)")
        ax2 = ax.twinx()
        ax2.plot(t, [1e3 * num(r, WORLD_CYCLES.x) for r in mine], color="0.6", lw=0.8, ls=":", label="tool x")
        ax2.set_ylabel("tool x (mm)", color="0.4")
        ax.set_title("each deformable body after its step")
        ax.legend(fontsize=7, loc="upper left")
        # (c) The cycle's cost, and how many pairs reached their models.
        ax = axes[i][2]
        ax.plot(t, [num(r, WORLD_CYCLES.time_us) for r in mine], lw=0.6, color="C0")
        ax.set_xlabel("t (s)")
        ax.set_ylabel("world cycle (us)")
        ax3 = ax.twinx()
        ax3.step(t, [num(r, WORLD_CYCLES.pairs_near) for r in mine], color="C3", lw=0.9, where="post", label="near")
        ax3.step(t, [num(r, WORLD_CYCLES.pairs_touching) for r in mine], color="C2", lw=0.9, where="post",
                 label="touching")
        ax3.set_ylabel("pairs")
        ax3.set_ylim(0, max(num(r, WORLD_CYCLES.pairs_near) for r in mine) + 1)
        ax3.legend(fontsize=7, loc="upper right")
        ax.set_title("broad phase, every near pair and the steps")
    results.save(fig, "fig03_hoses.png")
    header = ["model", "bodies", "pairs", "cycles", "median us", "p99.9 us", "max us", "pairs near / cycle",
              "most touching", "max |F| on tool N", "max displacement mm", "faults"]
    lines = [[s[WORLD_SUMMARY.model], s[WORLD_SUMMARY.bodies], s[WORLD_SUMMARY.pairs], s[WORLD_SUMMARY.cycles],
              f"{num(s, WORLD_SUMMARY.median_us):.1f}", f"{num(s, WORLD_SUMMARY.p999_us):.1f}",
              f"{num(s, WORLD_SUMMARY.max_us):.1f}", f"{num(s, WORLD_SUMMARY.mean_pairs_near):.2f}",
              s[WORLD_SUMMARY.max_pairs_touching], f"{num(s, WORLD_SUMMARY.max_force_N):.3g}",
              f"{1e3 * num(s, WORLD_SUMMARY.max_displacement):.3g}", s[WORLD_SUMMARY.faults]] for s in summary]
    results.save_table(header, lines, "Fig. 3 setting: a part between two deformable hoses", "fig03_hoses_table")
    return True
