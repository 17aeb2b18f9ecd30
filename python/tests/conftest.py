"""Fixtures of the contactlab Python suite: the command line it is checked against, the
repository's data and small scenes. ctest sets CONTACTLAB_BIN, CONTACTLAB_DATA and
CONTACTLAB_SOURCE_DIR (python/CMakeLists.txt); run by hand, they default to this checkout's
build folder."""

import os
import subprocess
import json
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("CONTACTLAB_SOURCE_DIR", Path(__file__).resolve().parents[2]))
os.environ.setdefault("CONTACTLAB_DATA", str(SOURCE_DIR / "data"))

# A small scene of procedural shapes: a torus (pointshell) against a box (field), few points.
SMALL_SCENE = """\
name: torus-on-box
bodies:
  - name: ring
    mesh: "torus:0.04,0.0125"
    pose: [0.001, -0.002, 0.0113, 0.9659258262890683, 0.0, 0.25881904510283985, 0.0]
    role: pointshell
    pointshell: {points: 1500, levels: 3, method: repulsion, seed: 3}
    field: {resolution: 32}
  - name: block
    mesh: "box:0.0833333,0.0666667,0.01"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 48}
model: {k_C: 1500, L: 10, node_budget: 0, coherence: false}
"""


@pytest.fixture(scope="session")
def cli():
    """Runs `contactlab ARGS...` and returns its stdout; fails the test on a non-zero exit."""
    exe = os.environ.get("CONTACTLAB_BIN", str(SOURCE_DIR / "build" / "bin" / "contactlab"))
    if not Path(exe).exists():
        pytest.skip(f"no contactlab command at {exe}")

    def run(*args, check=True):
        p = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and p.returncode != 0:
            raise AssertionError(f"contactlab {' '.join(map(str, args))} failed:\n{p.stderr}")
        return p

    run.exe = exe
    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    def run(*args):
        return json.loads(cli(*args).stdout)

    return run


@pytest.fixture(scope="session")
def data_dir():
    return Path(os.environ["CONTACTLAB_DATA"])


@pytest.fixture(scope="session")
def small_scene_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("scenes") / "torus-on-box.yaml"
    path.write_text(SMALL_SCENE)
    return path


@pytest.fixture(scope="session")
def plate_scene_file(data_dir):
    return data_dir / "scenes" / "sphere-on-plate.yaml"


def pose_arg(pose):
    """A 7-vector as the command line's --pose-a takes it, every digit kept (repr round-trips)."""
    return ",".join(repr(float(v)) for v in pose)
