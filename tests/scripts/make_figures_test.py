#!/usr/bin/python3
"""Tests of scripts/make_figures.py and its figures/ package: discovery, the columns the figures
name against those the studies declare (`contactlab columns --json`), the outputs of a run on
tiny synthetic results written with the declared columns, docs/experiments.md's example of
adding a figure, tables sized to their text, and the per-model style table.

Usage: make_figures_test.py [PATH/TO/scripts/make_figures.py [PATH/TO/contactlab]]
       (exit 77: matplotlib missing)
"""
import ast
import csv
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.abspath(sys.argv.pop(1) if len(sys.argv) > 1 else
                         os.path.join(os.path.dirname(__file__), "..", "..", "scripts", "make_figures.py"))
CONTACTLAB = os.path.abspath(sys.argv.pop(1) if len(sys.argv) > 1 else
                             os.path.join(os.path.dirname(SCRIPT), "..", "build", "bin", "contactlab"))
try:
    import matplotlib  # noqa: F401
except ImportError:
    print("make_figures_test: skipped: no matplotlib (python3-matplotlib, scripts/install-deps.sh)")
    sys.exit(77)
sys.path.insert(0, os.path.dirname(SCRIPT))
import figures  # noqa: E402
from figures import common  # noqa: E402


# Every study's declared columns, {study: {file: [{name, unit, meaning}, ...]}}, as the program
# prints them.
def declared_columns():
    run = subprocess.run([CONTACTLAB, "columns", "--json"], capture_output=True, text=True, timeout=60)
    if run.returncode != 0:
        raise RuntimeError(f"{CONTACTLAB} columns --json failed: {run.stderr}")
    return json.loads(run.stdout)


DECLARED = None


# The declared column names of each table file, {file: [name, ...]}.
def columns_by_file():
    global DECLARED
    if DECLARED is None:
        DECLARED = {}
        for tables in declared_columns().values():
            for file, columns in tables.items():
                DECLARED[file] = [c["name"] for c in columns]
    return DECLARED


def write_csv(path, rows):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


# Writes ROWS (dicts naming declared columns and the sweep AXES) as results/EXPERIMENT/TABLE
# with the header the program writes: the table's declared columns, the sweep axes after the
# job's keys (experiment, job), every declared column present (0 where a row gives none). A key
# that is neither a declared column nor an axis fails the test.
def write_table(root, experiment, table, axes, rows):
    declared = columns_by_file()[table.file]
    keyed = declared[:2] == ["experiment", "job"]
    header = declared[:2] + list(axes) + declared[2:] if keyed else list(declared)
    for row in rows:
        unknown = set(row) - set(header)
        if unknown:
            raise AssertionError(f"{table.file} declares no column {sorted(unknown)} (axes: {list(axes)})")
    full = []
    for row in rows:
        cells = {c: 0 for c in header}
        if keyed:
            cells.update(experiment=experiment, job=0)
        cells.update(row)
        full.append(cells)
    write_csv(os.path.join(root, experiment, table.file), full)


# Tiny results for three experiments: a table, a per-model curve plot and a log-log plot.
def write_synthetic_results(root):
    C, S = common.CYCLES, common.SUMMARY
    summary, cycles = [], []
    for scene in ("data/scenes/block-joint.yaml", "data/scenes/dragon-bunny.yaml"):
        for model, coherence in (("pointshell", "false"), ("pointshell", "true"), ("pointshell-linear", "false")):
            summary.append({"scene": scene, "coherence": coherence, S.model: model, S.points: 4096,
                            S.mean_nodes: 321.0, S.median_us: 12.5})
            cycles += [{"scene": scene, "coherence": coherence, C.model: model, C.level: lv} for lv in (3, 4, 4)]
    write_table(root, "table1-statistics", S, ["scene", "coherence"], summary)
    write_table(root, "table1-statistics", C, ["scene", "coherence"], cycles)
    rows = []
    for roles in ("normal", "swapped"):
        for model in ("pointshell", "pointshell-linear", "vps", "some-new-model"):
            for i in range(40):
                z = 0.012 - 0.0005 * i
                rows.append({"roles": roles, C.model: model, C.cycle: i, C.z: z, C.fz: max(0.0, 0.012 - z) * 1000})
    write_table(root, "hard-cases-medial-axis", C, ["roles"], rows)
    write_table(root, "fig05b-convergence", S, [],
                [{S.model: "pointshell-linear", S.points: n, S.rms_rel_error: 1.0 / n}
                 for n in (256, 1024, 4096)])
    write_table(root, "fig05b-convergence", common.CONVERGENCE, [],
                [{common.CONVERGENCE.group: "pointshell-linear", common.CONVERGENCE.fitted_order: 1.0}])
    return {"table1_statistics", "hard_cases_medial_axis", "fig05b_convergence"}


# The columns a source names through a table of figures/common.py ({file: {column: [line, ...]}}),
# and the string literals it uses as a row's key (subscript, .get, num, in_order), with lines.
def named_columns(source):
    tree = ast.parse(source)
    tables = {name: t.file for name, t in vars(common).items() if isinstance(t, common.Table)}
    named, literal_keys = {}, []
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in tables
                and isinstance(node.ctx, ast.Load)):
            named.setdefault(tables[node.value.id], {}).setdefault(node.attr, []).append(node.lineno)
        keys = []
        if isinstance(node, ast.Subscript):
            keys.append(node.slice)
        elif isinstance(node, ast.Call):
            f = node.func
            if isinstance(f, ast.Name) and f.id in ("num", "in_order") and len(node.args) >= 2:
                keys.append(node.args[1])
            if isinstance(f, ast.Attribute) and f.attr == "get" and node.args:
                keys.append(node.args[0])
        literal_keys += [(k.value, k.lineno) for k in keys if isinstance(k, ast.Constant) and isinstance(k.value, str)]
    return named, literal_keys


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path} is not a PNG")
    return struct.unpack(">II", head[16:24])


class Discovery(unittest.TestCase):
    def test_every_figure_module_declares_an_experiment(self):
        modules = figures.figure_modules()
        self.assertGreater(len(modules), 10)
        for module in modules:
            declared = figures.figures_of(module)
            self.assertTrue(declared, f"{module.__name__} declares no @figure")
            for draw in declared:
                self.assertTrue(draw.experiments and all(isinstance(e, str) and e for e in draw.experiments),
                                f"{module.__name__}.{draw.__name__} names no experiment")
                self.assertTrue(draw.outputs, f"{module.__name__}.{draw.__name__} names no output")

    def test_no_two_figures_write_the_same_file(self):
        writer = {}
        for module, draw in figures.all_figures():
            for out in draw.outputs:
                self.assertNotIn(out, writer, f"{out} is written by {writer.get(out)} and {module.__name__}")
                writer[out] = module.__name__
        names = [draw.__name__ for _, draw in figures.all_figures()]
        self.assertEqual(len(names), len(set(names)), "two figures share a name")


class MissingMatplotlib(unittest.TestCase):
    def test_the_interpreter_and_the_package_to_install_are_named(self):
        # A matplotlib that cannot be imported, first on the path, as in an interpreter without it.
        with tempfile.TemporaryDirectory() as tmp:
            os.makedirs(os.path.join(tmp, "matplotlib"))
            with open(os.path.join(tmp, "matplotlib", "__init__.py"), "w") as f:
                f.write("raise ModuleNotFoundError(\"No module named 'matplotlib'\", name='matplotlib')\n")
            env = dict(os.environ, PYTHONPATH=tmp)
            run = subprocess.run([sys.executable, SCRIPT, "--results", tmp], capture_output=True, text=True,
                                 env=env, timeout=60)
        self.assertEqual(run.returncode, 1, run.stderr)
        self.assertIn(f"make_figures: {sys.executable} (Python {sys.version_info.major}.{sys.version_info.minor}) "
                      "cannot import matplotlib", run.stderr)
        self.assertIn("apt install python3-matplotlib", run.stderr)
        self.assertNotIn("Traceback", run.stderr)


class Columns(unittest.TestCase):
    def test_every_table_of_figures_common_is_declared_by_a_study(self):
        for table in common.TABLES.values():
            self.assertIn(table.file, columns_by_file(), f"no study declares {table.file}")
        self.assertEqual(set(common.TABLES), set(columns_by_file()), "a declared table has no Table in common.py")

    def test_figure_modules_read_only_declared_columns(self):
        paths = [os.path.join(os.path.dirname(SCRIPT), "figures", "common.py")]
        paths += [m.__file__ for m in figures.figure_modules()]
        for path in paths:
            with open(path) as f:
                named, _ = named_columns(f.read())
            for file, columns in named.items():
                for column, lines in columns.items():
                    if column == "file":
                        continue
                    if column not in columns_by_file()[file]:
                        self.fail(f"{os.path.basename(path)}:{lines[0]} reads {file} column '{column}', which no "
                                  f"study declares (contactlab columns)")

    # A column named by a string of the module's own would escape the check above.
    def test_figure_modules_name_no_declared_column_by_a_literal(self):
        every = {c for columns in columns_by_file().values() for c in columns}
        for module in figures.figure_modules():
            with open(module.__file__) as f:
                _, literal_keys = named_columns(f.read())
            for key, line in literal_keys:
                if key in every:
                    self.fail(f"{os.path.basename(module.__file__)}:{line} names column '{key}' by a literal; name "
                              f"it through its table (common.CYCLES.{key}, ...)")

    def test_a_renamed_column_is_caught(self):
        named, _ = named_columns("from .common import SUMMARY\nx = r[SUMMARY.max_jump]\n")
        self.assertNotIn("max_jump", columns_by_file()["summary.csv"])
        self.assertEqual(named, {"summary.csv": {"max_jump": [2]}})

    def test_every_declared_column_has_a_meaning(self):
        for study, tables in declared_columns().items():
            for file, columns in tables.items():
                names = [c["name"] for c in columns]
                self.assertEqual(len(names), len(set(names)), f"{study} {file} declares a column twice")
                for c in columns:
                    self.assertTrue(c["meaning"], f"{study} {file} column {c['name']} has no meaning")
                    self.assertIn("unit", c)


class Run(unittest.TestCase):
    def test_synthetic_results_make_exactly_their_figures(self):
        with tempfile.TemporaryDirectory() as root:
            present = write_synthetic_results(root)
            run = subprocess.run([sys.executable, SCRIPT, "--results", root], capture_output=True, text=True,
                                 timeout=120)
            self.assertEqual(run.returncode, 0, run.stderr)
            expected = {out for _, draw in figures.all_figures() if draw.__name__ in present for out in draw.outputs}
            made = set(os.listdir(os.path.join(root, "figures")))
            self.assertEqual(made, expected)
            for name in made:
                path = os.path.join(root, "figures", name)
                self.assertGreater(os.path.getsize(path), 0, name)
                self.assertIn(path, run.stdout.splitlines())
                if name.endswith(".png"):
                    png_size(path)
            with open(os.path.join(root, "figures", "table1_statistics.md")) as f:
                self.assertIn("| block-joint | 4096 |", f.read())
            # Every other figure is skipped with a note naming its experiments.
            self.assertIn("make_figures: tessellation: no results yet (run tessellation first)", run.stderr)
            self.assertNotIn("table1_statistics: no results", run.stderr)


    # docs/experiments.md's example: adding one file to figures/ adds a figure, with no other change.
    def test_docs_example_figure_is_found_and_drawn(self):
        with open(os.path.join(os.path.dirname(SCRIPT), "..", "docs", "experiments.md")) as f:
            example = re.search(r"```python\n(# scripts/figures/my_figure.py\n.*?)```", f.read(), re.S).group(1)
        with tempfile.TemporaryDirectory() as root:
            scripts = os.path.join(root, "scripts")
            shutil.copytree(os.path.dirname(SCRIPT), scripts, ignore=shutil.ignore_patterns("__pycache__"))
            with open(os.path.join(scripts, "figures", "my_figure.py"), "w") as f:
                f.write(example)
            C = common.CYCLES
            write_table(os.path.join(root, "results"), "my-experiment", C, [],
                        [{C.model: m, C.t: 0.1 * i, C.fz: i} for m in ("pointshell", "bullet") for i in range(20)])
            run = subprocess.run([sys.executable, os.path.join(scripts, os.path.basename(SCRIPT)),
                                  "--results", os.path.join(root, "results")], capture_output=True, text=True, timeout=120)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(os.listdir(os.path.join(root, "results", "figures")), ["my_figure.png"])


# A stranger's experiment: a config the repository does not ship, swept over k_C, two models,
# written as `contactlab run --out` writes it (meta.json beside the tables).
def write_stranger_run(folder, experiment="my-slide"):
    C, S = common.CYCLES, common.SUMMARY
    cycles, summary = [], []
    for k in (1000, 3000):
        for model in ("pointshell", "my-own-model"):
            for i in range(20):
                cycles.append({"k_C": k, C.model: model, C.cycle: i, C.t: 1e-3 * i, C.fz: k * 1e-3 * i})
            summary.append({"k_C": k, S.model: model, S.max_force_N: k * 19e-3, S.median_us: 4.5,
                            S.rms_rel_error: ""})
    root, name = os.path.split(folder)
    write_table(root, name, C, ["k_C"], [dict(r, job=j) for j in (0,) for r in cycles])
    write_table(root, name, S, ["k_C"], summary)
    with open(os.path.join(folder, "meta.json"), "w") as f:
        json.dump({"experiment": experiment, "study": "contact"}, f)


class AnyResults(unittest.TestCase):
    def run_script(self, *args):
        return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True, timeout=120)

    # An experiment no figure module declares gets the generic figure: the forces per job and
    # model, and its summary table with the swept values (the empty "no reference" column left out).
    def test_an_experiment_no_module_declares_gets_the_generic_figure(self):
        with tempfile.TemporaryDirectory() as root:
            write_stranger_run(os.path.join(root, "my-slide"))
            run = self.run_script("--results", root)
            self.assertEqual(run.returncode, 0, run.stderr)
            made = set(os.listdir(os.path.join(root, "figures")))
            self.assertEqual(made, {"my-slide.png", "my-slide_summary.png", "my-slide_summary.md"})
            png_size(os.path.join(root, "figures", "my-slide.png"))
            with open(os.path.join(root, "figures", "my-slide_summary.md")) as f:
                md = f.read()
            self.assertIn("| job 0 (k_C=1000) | my-own-model |", md)
            self.assertIn("max_force_N", md)
            self.assertNotIn("| rms_rel_error |", md)  # empty in every row: no reference

    # One run's folder (`contactlab run --out DIR`, Python's out=DIR) is drawn into DIR/figures,
    # with no note about the shipped experiments it does not hold.
    def test_one_runs_folder_is_drawn_into_its_own_figures_folder(self):
        with tempfile.TemporaryDirectory() as root:
            run_dir = os.path.join(root, "contactlab-run")
            write_stranger_run(run_dir)
            run = self.run_script("--results", run_dir)
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(run.stderr, "")
            self.assertEqual(set(os.listdir(os.path.join(run_dir, "figures"))),
                             {"my-slide.png", "my-slide_summary.png", "my-slide_summary.md"})

    # --only draws one figure (by its name or an output's), or one experiment; a name that is
    # neither is refused, listing the figures.
    def test_only_draws_one_figure_and_refuses_an_unknown_name(self):
        with tempfile.TemporaryDirectory() as root:
            write_synthetic_results(root)
            write_stranger_run(os.path.join(root, "my-slide"))
            run = self.run_script("--results", root, "--only", "table1_statistics")
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertEqual(set(os.listdir(os.path.join(root, "figures"))),
                             {"table1_statistics.png", "table1_statistics.md"})
            run = self.run_script("--results", root, "--only", "my-slide")
            self.assertEqual(run.returncode, 0, run.stderr)
            self.assertIn("my-slide_summary.md", os.listdir(os.path.join(root, "figures")))
            self.assertNotIn("fig05b_convergence.png", os.listdir(os.path.join(root, "figures")))
            run = self.run_script("--results", root, "--only", "no-such-figure")
            self.assertNotEqual(run.returncode, 0)
            self.assertIn("--only no-such-figure", run.stderr)
            self.assertIn("table1_statistics", run.stderr)


class Continuity(unittest.TestCase):
    # Two models whose forces differ 150x (the pressure field's default modulus against a penalty
    # model): the bars are relative jumps, so the soft model's larger relative jump is the taller
    # bar, though its absolute jump is smaller; |F| is on a log axis and the legend sits outside
    # every panel.
    def test_bars_are_relative_jumps_and_the_legend_covers_no_trace(self):
        from figures import continuity_models
        C, S = common.CYCLES, common.SUMMARY
        scene = "data/scenes/block-joint.yaml"
        cycles, summary = [], []
        for model, force, jump in (("pointshell", 15.0, 0.3), ("pressure-field", 0.1, 0.05)):
            cycles += [{"scene": scene, C.model: model, C.t: 1e-3 * i, C.fz: force} for i in range(10)]
            summary.append({"scene": scene, S.model: model, S.max_jump_N: jump, S.max_jump_rel: jump / force})
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "continuity-models", C, ["scene"], cycles)
            write_table(root, "continuity-models", S, ["scene"], summary)
            results = common.Results(root)
            drawn = {}
            results.save = lambda fig, name, **kw: drawn.setdefault(name, fig)
            self.assertTrue(continuity_models.continuity_models(results))
            fig = drawn["continuity_models.png"]
            fig.canvas.draw()
            traces, bars = fig.axes[0], fig.axes[1]
            heights = {t.get_text(): p.get_height() for t, p in zip(bars.get_xticklabels(), bars.patches)}
            self.assertAlmostEqual(heights["pointshell"], 2.0)       # 0.3 N of 15 N
            self.assertAlmostEqual(heights["pressure-field"], 50.0)  # 0.05 N of 0.1 N
            self.assertEqual(traces.get_yscale(), "log")
            self.assertIsNone(traces.get_legend())
            self.assertEqual(len(fig.legends), 1)
            self.assertEqual({t.get_text() for t in fig.legends[0].get_texts()}, {"pointshell", "pressure-field"})


class PackingFill(unittest.TestCase):
    # x is the coverage the two packings reached, sqrt(fill_A fill_B), not the target asked (a
    # mesh stops short of 95 %); the first panel is the force magnitude ratio 1 / ref_scale, the
    # third the p99 cycle time with the 1 ms budget line, and the table lists every job.
    def test_x_is_the_coverage_reached_and_the_ratio_is_the_inverse_scale(self):
        from figures import packing_fill
        S = common.SUMMARY
        coverage = "scene.bodies[*].inner_spheres.coverage"
        scene = "data/scenes/block-joint.yaml"
        summary = [{"scene": scene, coverage: target, S.model: "inner-spheres", S.fill_A: a, S.fill_B: b,
                    S.ref_scale: scale, S.rms_rel_error_calibrated: 0.3, S.median_dir_error_deg: 5.0,
                    S.p99_us: p99}
                   for target, a, b, scale, p99 in ((0.5, 0.5, 0.5, 4.0, 50.0), (0.95, 0.81, 0.9, 2.0, 3000.0))]
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "packing-fill", S, ["scene", coverage], summary)
            results = common.Results(root)
            drawn, tables = {}, {}
            results.save = lambda fig, name, **kw: drawn.setdefault(name, fig)
            results.save_table = lambda header, lines, title, name: tables.setdefault(name, lines)
            self.assertTrue(packing_fill.packing_fill(results))
            ratio, _, times = drawn["packing_fill.png"].axes
            x, y = ratio.lines[0].get_data()
            self.assertAlmostEqual(x[0], 50.0)
            self.assertAlmostEqual(x[1], 100 * math.sqrt(0.81 * 0.9))
            self.assertEqual(list(y), [0.25, 0.5])
            budget = [l for l in times.lines if l.get_label() == "1 kHz budget"]
            self.assertEqual(list(budget[0].get_ydata()), [1000, 1000])
            self.assertEqual([line[1] for line in tables["packing_fill_table"]], ["50", "95"])
            self.assertEqual(tables["packing_fill_table"][1][7], "3000")


class BudgetModels(unittest.TestCase):
    # Each budgeted run is measured against the same model without a budget on the same cycles:
    # the relative RMS of the force difference. Forces of 10 N against 9 N and 12 N give 10 % and
    # 20 %; the p99 on the twin axis and the table's degraded share come from summary.csv.
    def test_error_is_against_the_unbudgeted_run_of_the_same_model(self):
        from figures import budget_models
        C, S = common.CYCLES, common.SUMMARY
        scene = "data/scenes/knight-screwdriver.yaml"
        cycles, summary = [], []
        for budget, fz, p99, share in ((0, 10.0, 2500.0, 0.0), (1000, 9.0, 800.0, 0.5), (300, 12.0, 200.0, 1.0)):
            for k in range(3):
                cycles.append({"scene": scene, "node_budget": budget, C.model: "vps", C.cycle: k, C.fz: fz})
            summary.append({"scene": scene, "node_budget": budget, S.model: "vps", S.p99_us: p99,
                            S.degraded_share: share})
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "budget-models", C, ["scene", "node_budget"], cycles)
            write_table(root, "budget-models", S, ["scene", "node_budget"], summary)
            results = common.Results(root)
            drawn, tables = {}, {}
            results.save = lambda fig, name, **kw: drawn.setdefault(name, fig)
            results.save_table = lambda header, lines, title, name: tables.setdefault(name, lines)
            self.assertTrue(budget_models.budget_models(results))
            panel = drawn["budget_models.png"].axes[0]
            x, y = panel.lines[0].get_data()
            self.assertEqual(list(x), [300, 1000])
            self.assertAlmostEqual(y[0], 20.0)
            self.assertAlmostEqual(y[1], 10.0)
            rows = tables["budget_models_table"]
            self.assertEqual([r[2] for r in rows], ["none", "300", "1000"])
            self.assertEqual([r[3] for r in rows], ["0", "100", "50"])
            self.assertEqual([r[5] for r in rows], ["2500", "200", "800"])


class BaselineSettings(unittest.TestCase):
    # Each job of baseline-settings sets one FCL and one Bullet key; its label reads "FCL setting /
    # Bullet setting": each model's rows are listed under its own part of the label, with the
    # four properties of its summary row, per scene.
    def test_each_model_is_listed_under_its_own_part_of_the_label(self):
        from figures import baseline_settings
        S = common.SUMMARY
        rows = []
        for scene in ("data/scenes/block-joint.yaml", "data/scenes/bumpy-cube-plate.yaml"):
            for label, fcl, bullet in (("default / default", (3.0, 0.13, 0.39, 600), (1.1, 0.09, 0.34, 390)),
                                       ("bv obb / margin 0.1 mm", (3.0, 0.13, 0.39, 520), (2.2, 0.08, 0.27, 210))):
                for model, (angle, error, jump, us) in (("fcl", fcl), ("bullet", bullet)):
                    rows.append({"scene": scene, "scene.model": label, S.model: model, S.median_dir_error_deg: angle,
                                 S.rms_rel_error_calibrated: error, S.max_jump_rel: jump, S.median_us: us})
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "baseline-settings", S, ["scene", "scene.model"], rows)
            results = common.Results(root)
            tables = {}
            results.save = lambda fig, name, **kw: None
            results.save_table = lambda header, lines, title, name: tables.setdefault(name, (header, lines))
            self.assertTrue(baseline_settings.baseline_settings(results))
            header, lines = tables["baseline_settings_table"]
            self.assertEqual(header[:3], ["model", "setting", "scene"])
            got = {(l[0], l[1], l[2]): l[3:] for l in lines}
            self.assertEqual(len(got), 8)
            self.assertEqual(got[("fcl", "bv obb", "block-joint")], ["3.00", "0.130", "0.390", "520"])
            self.assertEqual(got[("bullet", "margin 0.1 mm", "bumpy-cube-plate")], ["2.20", "0.080", "0.270", "210"])
            self.assertEqual(got[("bullet", "default", "block-joint")], ["1.10", "0.090", "0.340", "390"])
            self.assertEqual([l[0] for l in lines], ["fcl"] * 4 + ["bullet"] * 4)
        self.assertEqual(baseline_settings.setting_of("bullet", "convex hull / convex hull"), "convex hull")
        self.assertEqual(baseline_settings.setting_of("fcl", "default"), "default")


class SpeedVsError(unittest.TestCase):
    # The headline figure scores every model by the model-neutral overlap-volume law after its
    # fitted scale (compare-volume's rms_rel_error_calibrated) in its first panel and by the
    # paper's eq. (2) law in its second, each panel reading its own experiment's column; a model
    # with no value (empty cell) has no point.
    def test_first_panel_is_the_neutral_calibrated_error_and_the_second_the_papers_law(self):
        from figures import speed_vs_error
        S = common.SUMMARY
        scene = "data/scenes/block-joint.yaml"
        neutral = [{"scene": scene, S.model: "pointshell", S.median_us: 5, S.p99_us: 9, S.rms_rel_error: 0.9,
                    S.rms_rel_error_calibrated: 0.2},
                   {"scene": scene, S.model: "pressure-field", S.median_us: 500, S.p99_us: 700, S.rms_rel_error: 0.99,
                    S.rms_rel_error_calibrated: 0.1},
                   {"scene": scene, S.model: "fcl", S.median_us: 50, S.p99_us: 70, S.rms_rel_error: "",
                    S.rms_rel_error_calibrated: ""}]
        paper = [{"scene": scene, "offset": "0", S.model: "pointshell", S.median_us: 5, S.p99_us: 9,
                  S.rms_rel_error: 0.03},
                 {"scene": scene, "offset": "0", S.model: "pressure-field", S.median_us: 500, S.p99_us: 700,
                  S.rms_rel_error: 0.95}]
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "compare-volume", S, ["scene"], neutral)
            write_table(root, "speed-vs-error", S, ["scene", "offset"], paper)
            results = common.Results(root)
            drawn = {}
            results.save = lambda fig, name, **kw: drawn.setdefault(name, fig)
            self.assertTrue(speed_vs_error.speed_vs_error(results))
            fig = drawn["speed_vs_error.png"]
            first, second = fig.axes[0], fig.axes[1]
            self.assertIn("overlap-volume", first.get_ylabel())
            self.assertIn("eq. (2)", second.get_ylabel())
            points = lambda ax: sorted(tuple(o.get_offsets()[0]) for o in ax.collections)
            self.assertEqual(points(first), [(5.0, 0.2), (500.0, 0.1)])  # fcl: no value, no point
            self.assertEqual(points(second), [(5.0, 0.03), (500.0, 0.95)])

    # Swept over node_budget, a budgeted run is drawn only where its budget bound (degraded_share
    # > 0), joined by a dotted line to the same model's unbudgeted point on the same scene.
    def test_a_budget_that_bound_is_drawn_from_the_unbudgeted_point(self):
        from figures import speed_vs_error
        S = common.SUMMARY
        scene = "data/scenes/block-joint.yaml"
        rows = []
        for budget, pf, ps, shares in (("0", (500, 0.95), (5, 0.03), (0, 0)), ("1000", (90, 0.97), (4, 0.03), (0.8, 0))):
            rows.append({"scene": scene, "offset": "0", "node_budget": budget, S.model: "pressure-field",
                         S.median_us: pf[0], S.p99_us: pf[0] + 1, S.rms_rel_error: pf[1], S.degraded_share: shares[0]})
            rows.append({"scene": scene, "offset": "0", "node_budget": budget, S.model: "pointshell",
                         S.median_us: ps[0], S.p99_us: ps[0] + 1, S.rms_rel_error: ps[1], S.degraded_share: shares[1]})
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "speed-vs-error", S, ["scene", "offset", "node_budget"], rows)
            results = common.Results(root)
            drawn = {}
            results.save = lambda fig, name, **kw: drawn.setdefault(name, fig)
            self.assertTrue(speed_vs_error.speed_vs_error(results))
            ax = drawn["speed_vs_error.png"].axes[0]
            points = sorted(tuple(o.get_offsets()[0]) for o in ax.collections)
            self.assertEqual(points, [(5.0, 0.03), (90.0, 0.97), (500.0, 0.95)])  # pointshell's 1000: never bound
            dotted = [tuple(map(tuple, line.get_xydata())) for line in ax.lines if line.get_linestyle() == ":"]
            self.assertEqual(dotted, [((500.0, 0.95), (90.0, 0.97))])


class ClosedLoop(unittest.TestCase):
    # Swept over the stiffness rule (closed-loop-matched), a model is one line per rule, with the
    # factor on its wrench, and its largest stable k_VC is the largest before its first unstable
    # one, per rule.
    def test_each_stiffness_rule_is_its_own_line_with_its_wrench_scale(self):
        from figures import closed_loop
        L = common.STABILITY
        scene = "data/scenes/block-joint.yaml"
        rows = []
        for rule, scale, unstable_from in (("own", 1.0, None), ("matched", 120.0, 2000.0)):
            for k in (1000.0, 2000.0, 5000.0):
                for motion in ("push", "slide"):
                    bad = unstable_from is not None and k >= unstable_from and motion == "slide"
                    rows.append({"scene": scene, "stiffness": rule, L.model: "pressure-field", L.motion: motion,
                                 L.k_vc: k, L.wrench_scale: scale, L.stable: 0 if bad else 1,
                                 L.verdict: "active" if bad else "ok"})
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "closed-loop-matched", L, ["scene", "stiffness"], rows)
            results = common.Results(root)
            results.save = lambda fig, name, **kw: None
            self.assertTrue(closed_loop.closed_loop_matched(results))
            with open(os.path.join(results.out, "closed_loop_matched.md")) as f:
                table = [line.strip("|\n ").split(" | ") for line in f if line.startswith("| ")]
            header, body = table[0], table[1:]
            self.assertEqual(header[:4], ["scene", "model", "stiffness", "wrench scale"])
            by_rule = {line[2]: line for line in body}
            self.assertEqual(set(by_rule), {"own", "matched"})
            self.assertEqual(by_rule["own"][3], "1")
            self.assertEqual(by_rule["matched"][3], "120")
            self.assertEqual(by_rule["own"][-1], "5000")
            self.assertEqual(by_rule["matched"][-1], "1000")
            self.assertIn("active (slide)", by_rule["matched"][header.index("2000 N/m")])

    # Swept over the friction block (closed-loop-friction), a model is one line per friction label,
    # each with its own largest stable k_VC.
    def test_each_friction_is_its_own_line(self):
        from figures import closed_loop
        L = common.STABILITY
        rows = []
        for friction, unstable_from in (("none", 2000.0), ("0.5 / 0.4", None)):
            for k in (1000.0, 2000.0, 5000.0):
                bad = unstable_from is not None and k >= unstable_from
                rows.append({"scene": "data/scenes/block-joint.yaml", "scene.model.friction": friction,
                             L.model: "fcl", L.motion: "corner", L.k_vc: k, L.wrench_scale: 1.0,
                             L.stable: 0 if bad else 1, L.verdict: "oscillates" if bad else "ok"})
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "closed-loop-friction", L, ["scene", "scene.model.friction"], rows)
            results = common.Results(root)
            results.save = lambda fig, name, **kw: None
            self.assertTrue(closed_loop.closed_loop_friction(results))
            with open(os.path.join(results.out, "closed_loop_friction.md")) as f:
                table = [line.strip("|\n ").split(" | ") for line in f if line.startswith("| ")]
            header, body = table[0], table[1:]
            self.assertEqual(header[:3], ["scene", "model", "friction"])
            by_friction = {line[2]: line for line in body}
            self.assertEqual(by_friction["none"][-1], "1000")
            self.assertEqual(by_friction["0.5 / 0.4"][-1], "5000")


class Extraction(unittest.TestCase):
    """extraction_friction: the closed form of a preloaded peg, and the table's errors against it."""

    # The mean distance from the axis over a regular polygon's sides, against a brute-force
    # average of points spread evenly along one side.
    def test_mean_radius_is_the_average_over_a_side(self):
        from figures import extraction
        for radius, segments in ((0.004, 64), (1.0, 3), (0.0039, 192)):
            a, b = radius * math.cos(math.pi / segments), radius * math.sin(math.pi / segments)
            n = 200000
            brute = sum(math.hypot(a, -b + 2 * b * (i + 0.5) / n) for i in range(n)) / n
            self.assertAlmostEqual(extraction.mean_radius(radius, segments) / brute, 1.0, places=9)
            self.assertLess(extraction.mean_radius(radius, segments), radius)

    def test_overlap(self):
        from figures import extraction as e
        self.assertAlmostEqual(e.overlap(0.0), 2 * e.HOLE_H)
        self.assertAlmostEqual(e.overlap(e.PEG_H - e.HOLE_H + 0.001), 2 * e.HOLE_H - 0.001)
        self.assertEqual(e.overlap(e.PEG_H + e.HOLE_H + 0.001), 0.0)

    # A per-point model whose friction is 3 % above the closed form everywhere (plus an end push
    # the frictionless run also has, which the figure subtracts) reads +3.0 % in every column; a
    # model without the closed form reads "-"; a run without its frictionless twin is refused.
    def test_errors_against_the_closed_form(self):
        from figures import extraction as e
        C = common.CYCLES
        mu_s, mu_d, kappa = 0.5, 0.4, 1000.0
        rows = []
        for model in ("pointshell", "fcl"):
            for label in ("none", "0.5 / 0.4"):
                for i in range(1400):
                    s = 1e-5 * i
                    whole = e.load_per_length("normal") * e.overlap(s)
                    # Sticks up to mu_s / kappa of travel, then slides at mu_d.
                    friction = whole * (kappa * s if s <= mu_s / kappa else mu_d)
                    push = -0.7 if s > 0.003 else 0.0
                    force = push + (1.03 * friction if label != "none" else 0.0)
                    rows.append({"roles": "normal", "scene.model.friction": label, C.model: model, C.cycle: i,
                                 C.z: s, C.fz: -force})
        with tempfile.TemporaryDirectory() as root:
            write_table(root, "extraction-friction", C, ["roles", "scene.model.friction"], rows)
            results = common.Results(root)
            results.save = lambda fig, name, **kw: None
            self.assertTrue(e.extraction_friction(results))
            with open(os.path.join(results.out, "extraction_friction.md")) as f:
                table = [line.strip("|\n ").split(" | ") for line in f if line.startswith("| ")]
            header, body = table[0], table[1:]
            by_model = {line[1]: dict(zip(header, line)) for line in body}
            for column in ("vs mu_s load", "vs mu_d load", "vs closed form"):
                self.assertEqual(by_model["pointshell"][column], "+3.0 %", column)
                self.assertEqual(by_model["fcl"][column], "-", column)
            kept = [r for r in rows if not (r[C.model] == "fcl" and r["scene.model.friction"] == "none")]
            write_table(root, "extraction-friction", C, ["roles", "scene.model.friction"], kept)
            with self.assertRaisesRegex(ValueError, "fcl .* no frictionless run"):
                e.extraction_friction(common.Results(root))


class Reading(unittest.TestCase):
    """figures.common.read_csv reads the tables as the program writes them (RFC 4180 quoting)."""

    def setUp(self):
        self.dir = tempfile.mkdtemp()
        self.addCleanup(shutil.rmtree, self.dir)

    def write(self, text):
        path = os.path.join(self.dir, "summary.csv")
        with open(path, "w", newline="") as f:
            f.write(text)
        return path

    def test_a_quoted_comma_in_a_scene_path_or_model_name_stays_in_its_column(self):
        path = self.write('experiment,job,scene,model,max_force_N\n'
                          '"a,b",0,"scenes/plate,thin.yaml","py ""x,y""",2.5\n')
        rows = common.read_csv(path)
        self.assertEqual(rows, [{"experiment": "a,b", "job": "0", "scene": "scenes/plate,thin.yaml",
                                 "model": 'py "x,y"', "max_force_N": "2.5"}])

    def test_a_row_with_a_comma_unquoted_in_a_name_is_refused_naming_file_and_line(self):
        path = self.write("experiment,job,model,max_force_N\nok,0,pointshell,2.5\na,b,1,pointshell,3.5\n")
        with self.assertRaisesRegex(ValueError, re.escape(path) + r":3: 5 cells, the header \(line 1\) has 4"):
            common.read_csv(path)


class Tables(unittest.TestCase):
    header = ["scene", "points", "tree µs (median)", "StVK µs (A / B)", "max jump N"]

    def line(self, scene):
        return [scene, "65536", "355.8", "11.8 / 5.1", "0.532"]

    def test_table_png_width_grows_with_its_longest_cell(self):
        widths = []
        with tempfile.TemporaryDirectory() as root:
            results = common.Results(root)
            for i, scene in enumerate(["a", "armadillo-dragon", "armadillo-dragon-with-a-much-longer-scene-name"]):
                results.save_table(self.header, [self.line(scene)], "T", f"t{i}")
                widths.append(png_size(os.path.join(root, "figures", f"t{i}.png"))[0])
        self.assertLess(widths[1], widths[2])
        self.assertLessEqual(widths[0], widths[1])

    def test_table_text_stays_inside_its_cell_and_never_overlaps(self):
        lines = [self.line("armadillo-dragon-rooted-deep"), self.line("x")]
        fig = common.table_figure(self.header + ["a header much wider than its numbers"],
                                  [line + ["1.0"] for line in lines], "A title")
        renderer = fig.canvas.get_renderer()
        frame = fig.bbox
        boxes = [t.get_window_extent(renderer) for t in fig.texts if t.get_text()]
        for box in boxes:
            self.assertTrue(frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1,
                            f"text at {box} leaves the figure {frame}")
        for i, a in enumerate(boxes):
            for b in boxes[i + 1:]:
                self.assertFalse(a.overlaps(b), f"texts at {a} and {b} overlap")
        # Every text but the title (the first) inside one cell.
        cells = [p.get_window_extent(renderer) for p in fig.artists]
        self.assertEqual(len(cells), (len(lines) + 1) * (len(self.header) + 1))
        for box in boxes[1:]:
            self.assertTrue(any(c.x0 <= box.x0 and box.x1 <= c.x1 and c.y0 <= box.y0 and box.y1 <= c.y1 for c in cells),
                            f"text at {box} crosses its cell's border")
        common.plt.close(fig)


class ModelStyles(unittest.TestCase):
    def test_named_models_have_distinct_colours(self):
        colours = [s["color"] for s in common.MODEL_STYLES.values()]
        self.assertEqual(len(colours), len(set(colours)))

    def test_coinciding_pairs_differ_in_colour_line_and_marker(self):
        for a, b in (("pointshell", "pointshell-linear"), ("vps", "vps-repulsion"), ("fcl", "bullet")):
            sa, sb = common.model_style(a), common.model_style(b)
            for key in ("color", "marker"):
                self.assertNotEqual(sa[key], sb[key], f"{a} and {b} share {key}")
            self.assertTrue(sa["ls"] != sb["ls"] or sa["lw"] != sb["lw"], f"{a} and {b} share their line")

    def test_unknown_model_gets_the_same_fallback_every_time(self):
        self.assertEqual(common.model_style("some-new-model"), common.model_style("some-new-model"))
        self.assertNotIn(common.model_style("some-new-model")["color"],
                         [s["color"] for s in common.MODEL_STYLES.values()])


if __name__ == "__main__":
    unittest.main(verbosity=2)
