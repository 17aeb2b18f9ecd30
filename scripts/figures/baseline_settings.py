"""Issue 46: FCL and Bullet at other settings against the exact overlap volume. Each job of
baseline-settings changes one FCL key and one Bullet key at once; its `scene.model` label reads
"FCL setting / Bullet setting". Per model, setting and scene: the median angle to -grad V, the
relative RMS error after the fitted stiffness scale, the largest per-cycle force jump over the
median |F| and the median cycle time (a table, printed, and one panel per property)."""
from .common import SUMMARY, axis, figure, in_order, model_color, num, plt, scene_name

EXPERIMENT = "baseline-settings"
SETTING = axis("scene.model")
# The label's part for each model: "FCL setting / Bullet setting"; a label without " / " is one
# setting of both.
PART = {"fcl": 0, "bullet": 1}
PROPERTIES = [  # (column, axis label, table header, format)
    (SUMMARY.median_dir_error_deg, "median angle to −∇V (°)", "angle to −∇V, median (°)", "{:.2f}"),
    (SUMMARY.rms_rel_error_calibrated, "rel. RMS error after fitted scale", "calibrated error", "{:.3f}"),
    (SUMMARY.max_jump_rel, "largest jump / median |F|", "largest jump / median force", "{:.3f}"),
    (SUMMARY.median_us, "median cycle (µs, log)", "median cycle (µs)", "{:.0f}"),
]


def setting_of(model, label):
    """MODEL's own setting in a job's LABEL ("FCL setting / Bullet setting")."""
    parts = [p.strip() for p in label.split(" / ")]
    if len(parts) == 1:
        return parts[0]
    return parts[PART.get(model, 0)] if PART.get(model, 0) < len(parts) else label


@figure(experiments=[EXPERIMENT],
        outputs=["baseline_settings.png", "baseline_settings_table.png", "baseline_settings_table.md"])
def baseline_settings(results):
    rows = results.load(EXPERIMENT, SUMMARY)
    if not rows:
        return False
    scenes = in_order(rows, axis("scene"))
    models = [m for m in PART if any(r[SUMMARY.model] == m for r in rows)]
    # (model, setting) in the order the config gives them, each with its row per scene.
    keys, by = [], {}
    for r in rows:
        model = r[SUMMARY.model]
        if model not in PART:
            continue
        key = (model, setting_of(model, r[SETTING]))
        if key not in by:
            keys.append(key)
            by[key] = {}
        by[key][r[axis("scene")]] = r
    keys.sort(key=lambda k: models.index(k[0]))
    table = []
    for model, setting in keys:
        for scene in scenes:
            r = by[(model, setting)].get(scene)
            if r is None:
                continue
            values = [fmt.format(num(r, col)) for col, _, _, fmt in PROPERTIES]
            table.append([model, setting, scene_name(scene)] + values)
            print(f"baseline-settings {model} [{setting}] {scene_name(scene)}: " +
                  ", ".join(f"{head} {v}" for (_, _, head, _), v in zip(PROPERTIES, values)))
    results.save_table(["model", "setting", "scene"] + [head for _, _, head, _ in PROPERTIES], table,
                       "FCL and Bullet at other settings, against the overlap volume", "baseline_settings_table")
    # One panel per property: a group of bars per (model, setting), one bar per scene.
    fig, axes = plt.subplots(len(PROPERTIES), 1, figsize=(max(8.0, 0.75 * len(keys) + 2), 2.6 * len(PROPERTIES)),
                             squeeze=False)
    width = 0.8 / max(1, len(scenes))
    shades = [0.35, 0.65, 0.9, 0.5, 0.75]
    for p, (col, label, _, _) in enumerate(PROPERTIES):
        ax = axes[p][0]
        for i, (model, setting) in enumerate(keys):
            for j, scene in enumerate(scenes):
                r = by[(model, setting)].get(scene)
                if r is None:
                    continue
                x = i + (j - (len(scenes) - 1) / 2) * width
                ax.bar(x, num(r, col), width, color=model_color(model), alpha=shades[j % len(shades)],
                       edgecolor="black", linewidth=0.4,
                       label=scene_name(scene) if (p == 0 and i == 0) else None)
        ax.set_ylabel(label, fontsize=8)
        ax.set_xticks(range(len(keys)))
        ax.set_xticklabels([f"{m}: {s}" for m, s in keys] if p == len(PROPERTIES) - 1 else [], fontsize=7,
                           rotation=30, ha="right")
        if col == SUMMARY.median_us:
            ax.set_yscale("log")
        ax.grid(True, axis="y", alpha=0.3)
    axes[0][0].legend(fontsize=7, title="scene (shade)", title_fontsize=7)
    fig.suptitle("FCL and Bullet at other settings, against the exact overlap volume", fontsize=10)
    results.save(fig, "baseline_settings.png")
    return True
