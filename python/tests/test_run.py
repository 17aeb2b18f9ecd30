"""contactlab.run against `contactlab run` on the same short config, load_results, and a model
written in Python compared beside a built-in one."""

import json

import numpy as np
import pytest

import contactlab

CONFIG = """\
name: python-run-check
scene: scenes/sphere-on-plate.yaml
models: [pointshell, vps]
trajectory: {type: approach-press, direction: toward, approach: 0.0005, depth: 0.002, duration: 0.06,
             touch: true, touch_depth: 0.0001}
"""
# Columns that hold times (they differ from run to run).
TIMING = ("_us", "wall")


def deterministic(frame):
    return frame[[c for c in frame.columns if not any(t in c for t in TIMING)]]


@pytest.fixture(scope="module")
def config_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("configs") / "python-run-check.yaml"
    path.write_text(CONFIG)
    return path


def test_run_equals_command_line(cli, config_file, tmp_path):
    out = contactlab.run(config_file, out=tmp_path / "python", set={"trajectory.depth": 0.0015})
    assert out == tmp_path / "python"
    cli("run", config_file, "--out", tmp_path / "cli", "--set", "trajectory.depth=0.0015")
    mine, theirs = contactlab.load_results(out), contactlab.load_results(tmp_path / "cli")
    assert set(mine.tables) == set(theirs.tables) >= {"cycles", "summary"}
    for name in mine.tables:
        a, b = deterministic(mine[name]), deterministic(theirs[name])
        assert list(a.columns) == list(b.columns)
        assert a.equals(b), name
    assert sorted(mine.summary["model"]) == ["pointshell", "vps"]
    assert len(mine.cycles) == 2 * mine.summary["cycles"].iloc[0]
    assert mine.meta["study"] == theirs.meta["study"] == "contact"
    assert mine.meta == json.loads((out / "meta.json").read_text())


def test_sweep_of_k_C(config_file, tmp_path):
    out = contactlab.run(config_file, out=tmp_path / "sweep", set={"models": ["pointshell"], "sweep": {"k_C": [1000, 3000]}})
    summary = contactlab.load_results(out).summary
    assert len(summary) == 2
    assert sorted(summary["k_C"]) == [1000, 3000]
    soft, stiff = summary.sort_values("k_C")["max_force_N"]
    assert stiff > 1.5 * soft  # the penalty force grows with k_C


def test_a_points_sweep_loads_in_pandas_with_unique_columns_and_empty_missing_values(config_file, tmp_path):
    # The points axis is named like summary.csv's own points column: the axis is sweep.points,
    # nothing is renamed by pandas, and a model that reads no pointshell (fcl) or a run with no
    # reference leaves its cells empty (NaN), not -1.
    out = contactlab.run(config_file, out=tmp_path / "points",
                         set={"models": ["pointshell", "fcl"], "sweep": {"points": [256, 1024]}})
    results = contactlab.load_results(out)
    for name, frame in results.tables.items():
        assert not [c for c in frame.columns if c.endswith(".1")], name
    summary = results.summary
    assert "sweep.points" in summary.columns and "points" in summary.columns
    assert sorted(summary["sweep.points"]) == [256, 256, 1024, 1024]
    mine = summary[summary["model"] == "pointshell"]
    assert list(mine["points"]) == list(mine["sweep.points"])
    assert summary[summary["model"] == "fcl"]["points"].isna().all()
    assert summary["rms_rel_error"].isna().all()  # the config names no reference
    cycles = results.cycles
    assert "points" in cycles.columns  # cycles.csv declares no points column: the axis keeps its name
    assert cycles[cycles["model"] == "fcl"]["level"].isna().all()
    assert (cycles[cycles["model"] == "pointshell"]["level"] >= 0).all()
    assert not (summary.select_dtypes("number") == -1).any().any()


def halfspace_ball(k):
    """A Python model for sphere-on-plate: the ball (radius 5 cm, origin at X_WA) against the
    plate's top face (2 cm above B's origin, B kept level), force k * depth along -z on B."""

    def wrench(X_WA, X_WB):
        depth = (X_WB[2] + 0.02) - (X_WA[2] - 0.05)
        w = np.zeros(6)
        if depth > 0:
            w[2] = -k * depth
            w[3:] = np.cross([X_WA[0] - X_WB[0], X_WA[1] - X_WB[1], 0.02], w[:3])
        K = np.zeros((6, 6))
        K[2, 2] = -k if depth > 0 else 0.0
        return w, K

    return wrench


def test_python_model_is_made_by_name(plate_scene_file):
    contactlab.register_model("py-halfspace", halfspace_ball(4000.0), description="ball on a plane")
    assert "py-halfspace" in contactlab.models()
    assert "not real time" in contactlab.model_description("py-halfspace")
    scene = contactlab.Scene.load(str(plate_scene_file))
    model = scene.model("py-halfspace")
    r = model.query([0.001, 0, 0.048, 1, 0, 0, 0], scene.B.pose)
    np.testing.assert_allclose(r["force"], [0, 0, -4000.0 * 0.002], rtol=1e-9)
    assert r["K_B"][2, 2] == -4000.0
    poses_A = np.tile([0.0, 0, 0.048, 1, 0, 0, 0], (5, 1))
    poses_A[:, 2] -= np.linspace(0, 0.001, 5)
    batch = model.query_many(poses_A, scene.B.pose)
    np.testing.assert_allclose(batch["force"][:, 2], -4000.0 * (0.002 + np.linspace(0, 0.001, 5)), rtol=1e-9)


def test_python_model_beside_built_in_models(config_file, tmp_path):
    contactlab.register_model("py-halfspace", halfspace_ball(2000.0 * 10))
    out = contactlab.run(config_file, out=tmp_path / "compare", set={"models": ["pointshell", "py-halfspace"]})
    summary = contactlab.load_results(out).summary.set_index("model")
    assert set(summary.index) == {"pointshell", "py-halfspace"}
    assert summary.loc["py-halfspace", "max_force_N"] > 0
    # The pointshell force on the same motion is of the same order (k_C L over the contact patch).
    ratio = summary.loc["pointshell", "max_force_N"] / summary.loc["py-halfspace", "max_force_N"]
    assert 0.1 < ratio < 10


def test_python_model_errors_fail_the_run(config_file, tmp_path):
    def broken(X_WA, X_WB):
        raise ValueError("no force law here")

    contactlab.register_model("py-broken", broken)
    with pytest.raises(contactlab.Error, match="py-broken: its Python function raised ValueError: no force law here"):
        contactlab.run(config_file, out=tmp_path / "broken", set={"models": ["py-broken"]})
    with pytest.raises(contactlab.Error, match="'pointshell' is a built-in contact model"):
        contactlab.register_model("pointshell", broken)


def test_comma_or_quote_in_the_experiment_or_python_model_name_stays_in_its_column(config_file, tmp_path):
    name, model = 'check, "quoted"', 'py,half "space"'
    contactlab.register_model(model, halfspace_ball(20000.0))
    out = contactlab.run(config_file, out=tmp_path / "comma", set={"name": name, "models": ["pointshell", model]})
    results = contactlab.load_results(out)
    for table in ("summary", "cycles"):
        frame = results[table]
        assert set(frame["experiment"]) == {name}, table
        assert set(frame["model"]) == {"pointshell", model}, table
        assert frame["job"].dtype.kind == "i", table
    assert (results.summary["max_force_N"] > 0).all()
    assert results.cycles["fz"].dtype.kind == "f"


def test_load_results_refuses_a_row_with_the_wrong_number_of_cells_naming_file_and_line(tmp_path):
    (tmp_path / "meta.json").write_text("{}")
    # Every row one cell longer than the header: pandas alone takes the first cell as an index
    # and shifts every column by one.
    (tmp_path / "summary.csv").write_text("experiment,model,max_force_N\na,b,pointshell,1.5\na,b,vps,2.5\n")
    with pytest.raises(contactlab.Error, match=r"summary\.csv:2: 4 cells, the header \(line 1\) has 3"):
        contactlab.load_results(tmp_path)
    (tmp_path / "summary.csv").write_text('experiment,model,max_force_N\n"a,b",pointshell,1.5\n"a,b",vps\n')
    with pytest.raises(contactlab.Error, match=r"summary\.csv:3: 2 cells, the header \(line 1\) has 3"):
        contactlab.load_results(tmp_path)
