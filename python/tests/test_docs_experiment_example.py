"""The annotated config of docs/experiments.md, as a stranger would use it: it loads, lists its
jobs, runs from Python under its quick profile, its results load in pandas with every column
name unique and missing values empty, and make_figures draws a figure for it."""

import re
import subprocess
import sys

import pytest

import contactlab
from conftest import SOURCE_DIR


@pytest.fixture(scope="module")
def config_file(tmp_path_factory, cli):
    text = (SOURCE_DIR / "docs" / "experiments.md").read_text()
    block = re.search(r"<!-- the annotated config -->\n```yaml\n(.*?)```", text, re.S)
    assert block, "docs/experiments.md: no yaml block after <!-- the annotated config -->"
    if not re.search(r"^volume\s", cli("models").stdout, re.M):  # a reference, not in contactlab.models()
        pytest.skip("the volume reference is not built (CGAL off)")
    path = tmp_path_factory.mktemp("stranger") / "my-press-and-slide.yaml"
    path.write_text(block.group(1))
    return path


def test_every_top_level_key_of_the_annotated_config_is_documented_by_params(cli, config_file):
    import yaml

    keys = set(yaml.safe_load(config_file.read_text()))
    params = cli("params").stdout
    for key in keys:
        assert f"| `{key}` |" in params, key


def test_list_jobs_prints_the_four_jobs_the_page_promises(cli, config_file):
    out = cli("run", config_file, "--list-jobs").stdout
    jobs = [line for line in out.splitlines() if re.match(r"^\s*\d+\s", line)]
    assert len(jobs) == 4, out
    assert "k_C=3000" in out and "trajectory.depth=deep" in out


def test_the_config_runs_loads_cleanly_and_gets_a_figure(config_file, tmp_path):
    out = contactlab.run(config_file, out=tmp_path / "run", profile="quick")
    results = contactlab.load_results(out)
    summary = results.summary
    assert len(summary) == 2 * 2  # quick: k_C 1000 only, two depths, two models
    for frame in results.tables.values():
        assert len(set(frame.columns)) == len(frame.columns)
        assert not [c for c in frame.columns if re.search(r"\.\d+$", c)]
    assert set(summary["trajectory.depth"]) == {"shallow", "deep"}
    assert (summary["rms_rel_error"] >= 0).all()  # the volume reference was evaluated
    assert summary[summary["model"] == "pressure-field"]["points"].isna().all()
    deep = summary[summary["trajectory.depth"] == "deep"].set_index("model")["max_force_N"]
    shallow = summary[summary["trajectory.depth"] == "shallow"].set_index("model")["max_force_N"]
    assert (deep > shallow).all()  # pressed twice as far, every model pushes back harder
    draw = subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "make_figures.py"), "--results", str(out)],
                          capture_output=True, text=True, timeout=300)
    assert draw.returncode == 0, draw.stderr
    assert (out / "figures" / "my-press-and-slide.png").stat().st_size > 0
