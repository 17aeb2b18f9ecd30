"""Scenes, meshes, distance fields and pointshells as NumPy arrays, against analytic shapes."""

import numpy as np
import pytest

import contactlab
from conftest import SMALL_SCENE

BALL = """\
name: ball-and-box
bodies:
  - {name: ball, mesh: "sphere:0.05", role: pointshell, pose: [0, 0, 0.05, 1, 0, 0, 0],
     pointshell: {points: 1000, levels: 3, seed: 2}, field: {resolution: 40}}
  - {name: box, mesh: "box:0.1,0.1,0.02", role: field, pose: [0, 0, -0.02, 1, 0, 0, 0], field: {resolution: 40}}
models: [pointshell, vps]
"""


@pytest.fixture(scope="module")
def ball_scene():
    return contactlab.Scene.from_yaml(BALL)


def test_scene_attributes(ball_scene):
    A, B = ball_scene.bodies
    assert (A.name, A.role, B.name, B.role) == ("ball", "pointshell", "box", "field")
    assert ball_scene.name == "ball-and-box"
    assert ball_scene.models == ["pointshell", "vps"]
    assert A.pose.tolist() == [0, 0, 0.05, 1, 0, 0, 0]
    assert not A.deformable
    assert ball_scene.model().name == "pointshell"


def test_mesh_arrays_view_the_mesh(ball_scene):
    mesh = ball_scene.A.mesh
    V, T = mesh.vertices, mesh.triangles
    assert V.ndim == 2 and V.shape[1] == 3 and V.dtype == np.float64
    assert T.ndim == 2 and T.shape[1] == 3 and T.dtype == np.int32
    assert T.min() >= 0 and T.max() < len(V)
    np.testing.assert_allclose(np.linalg.norm(V, axis=1), 0.05, rtol=1e-9)
    assert not V.flags.writeable
    box = ball_scene.B.mesh.vertices
    np.testing.assert_allclose(np.abs(box).max(axis=0), [0.1, 0.1, 0.02])


def test_distance_matches_the_analytic_sphere(ball_scene):
    rng = np.random.default_rng(1)
    directions = rng.normal(size=(200, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    radii = rng.uniform(0.0, 0.055, size=200)  # inside the field box (0.06 half-width)
    points = directions * radii[:, None]
    d = ball_scene.A.distance(points)
    assert d.shape == (200,)
    # Trilinear interpolation of a 40-cell field of a faceted sphere: within about a cell.
    spacing = 0.1 * 1.2 / 40
    np.testing.assert_allclose(d, radii - 0.05, atol=spacing)
    assert ball_scene.A.distance(np.array([0.0, 0.0, 0.0])) < -0.04


def test_pointshell_levels(ball_scene):
    shell = ball_scene.A.pointshell()
    points, normals = shell
    assert shell.level == shell.num_levels - 1 == 2
    assert points.shape == normals.shape and points.shape[1] == 3
    assert len(shell) >= 900
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1, atol=1e-5)
    # Inward normals on a sphere point to its centre; points lie near its surface.
    assert np.all(np.einsum("ij,ij->i", normals, points) < 0)
    np.testing.assert_allclose(np.linalg.norm(points, axis=1), 0.05, atol=0.005)
    coarse = ball_scene.A.pointshell(level=0)
    assert len(coarse) < len(shell)
    # Nested levels: the coarse level's points are the first of the finest.
    assert np.array_equal(coarse.points, points[:len(coarse)])


def test_small_scene_round_trip(small_scene_file):
    from_file = contactlab.Scene.load(str(small_scene_file))
    from_text = contactlab.Scene.from_yaml(SMALL_SCENE)
    pose_A, pose_B = from_file.A.pose, from_file.B.pose
    a = from_file.model("pointshell").query(pose_A, pose_B)
    b = from_text.model("pointshell").query(pose_A, pose_B)
    assert np.array_equal(a["wrench"], b["wrench"])
