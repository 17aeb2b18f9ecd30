"""The Python example of docs/python.md runs as written (its results folder moved to a temporary one)."""

import os
import re
import subprocess
import sys

from conftest import SOURCE_DIR


def test_docs_python_example_runs(tmp_path):
    text = (SOURCE_DIR / "docs" / "python.md").read_text()
    example = re.search(r"```python\n(# PYTHONPATH=build/python python3\n.*?)```", text, re.S).group(1)
    assert '"/tmp/contactlab-run"' in example
    example = example.replace('"/tmp/contactlab-run"', repr(str(tmp_path / "run")))
    p = subprocess.run([sys.executable, "-c", example], capture_output=True, text=True, cwd=tmp_path,
                       env=dict(os.environ), timeout=120)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "run" / "summary.csv").exists()
    assert "pointshell" in p.stdout and "vps" in p.stdout


def test_docs_scenes_from_arrays_example_runs(tmp_path):
    """The example of "Scenes from arrays": a NumPy plate 1 cm below the point, pushed down."""
    text = (SOURCE_DIR / "docs" / "python.md").read_text().split("## Scenes from arrays", 1)[1]
    example = re.search(r"```python\n(# PYTHONPATH=build/python python3\n.*?)```", text, re.S).group(1)
    assert "contactlab.Mesh(" in example and "Scene.from_dict(" in example
    p = subprocess.run([sys.executable, "-c", example], capture_output=True, text=True, cwd=tmp_path,
                       env=dict(os.environ), timeout=120)
    assert p.returncode == 0, p.stderr
    distance, force = p.stdout.strip().split("\n")
    assert abs(float(distance) - 0.01) < 1e-6
    force = [float(v) for v in force.strip("[]").split()]
    assert force[2] < 0 and abs(force[0]) < 0.05 * abs(force[2])


def test_docs_many_bodies_example_runs(tmp_path):
    """The example of "Scenes of many bodies": the ball pushed up (+z) and away from the wall (-x)."""
    text = (SOURCE_DIR / "docs" / "python.md").read_text().split("## Scenes of many bodies", 1)[1]
    example = re.search(r"```python\n(# PYTHONPATH=build/python python3\n.*?)```", text, re.S).group(1)
    example += "\nassert r['force'][2] > 1 and r['force'][0] < -1 and r['near'].sum() == 3\n"
    p = subprocess.run([sys.executable, "-c", example], capture_output=True, text=True, cwd=tmp_path,
                       env=dict(os.environ), timeout=120)
    assert p.returncode == 0, p.stderr
    assert "('bracket-a', 'bracket-b')" in p.stdout
