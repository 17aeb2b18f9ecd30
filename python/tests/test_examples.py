"""The example programs in examples/python run, on short settings."""

import os
import subprocess
import sys
from pathlib import Path

from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples" / "python"


def run_example(script, *args, cwd):
    env = dict(os.environ, MPLBACKEND="Agg")
    p = subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)], capture_output=True, text=True,
                       cwd=cwd, env=env, timeout=120)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_compare_models_along_a_path(tmp_path, plate_scene_file):
    png = tmp_path / "compare.png"
    out = run_example("compare_models_path.py", "--scene", plate_scene_file, "--models", "pointshell", "vps",
                      "--steps", "60", "--out", png, cwd=tmp_path)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "pointshell" in out and "vps" in out


def test_sweep_stiffness(tmp_path):
    out = run_example("sweep_stiffness.py", SOURCE_DIR / "experiments" / "continuity-models.yaml",
                      "--k-C", "1000", "2000", "--out", tmp_path / "sweep",
                      "--set", "models=[pointshell]", "--set", "trajectory.duration=0.05", cwd=tmp_path)
    # The example's table follows the line "continuity-models: N rows in DIR" (the run prints its own before).
    lines = out.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("continuity-models: 2 rows in"))
    rows = [line.split() for line in lines[start + 1:]]
    rows = [r for r in rows if len(r) == 6 and r[1] == "pointshell"]
    assert [float(r[0]) for r in rows] == [1000, 2000]
    assert float(rows[1][3]) > float(rows[0][3])  # max_force_N grows with k_C
    assert (tmp_path / "sweep" / "summary.csv").exists()
