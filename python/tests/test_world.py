"""Scenes of many bodies from Python: contactlab.World against the same scene's pairs made apart."""

import numpy as np
import pytest

import contactlab

TOOL_AMONG_PLATES = """\
name: tool-among-plates
tool: ball
bodies:
  - {name: ball, mesh: "sphere:0.02,3", role: pointshell, pose: [0, 0, 0.018, 1, 0, 0, 0],
     pointshell: {points: 512, levels: 3, seed: 2}, field: {resolution: 24}}
  - {name: floor, mesh: "box:0.04,0.04,0.01,2", role: field, pose: [0, 0, -0.01, 1, 0, 0, 0], field: {resolution: 24}}
  - {name: wall, mesh: "box:0.01,0.04,0.04,2", role: field, pose: [0.028, 0, 0.03, 1, 0, 0, 0], field: {resolution: 24}}
  - {name: far, mesh: "box:0.01,0.01,0.01,1", role: field, pose: [0.5, 0.5, 0, 1, 0, 0, 0], field: {resolution: 16}}
model: {k_C: 1000, L: 0}
"""

TWO_BODY = """\
bodies:
  - {name: ball, mesh: "sphere:0.02,3", role: pointshell, pose: [0, 0, 0.018, 1, 0, 0, 0],
     pointshell: {points: 512, levels: 3, seed: 2}, field: {resolution: 24}}
  - {name: %s, mesh: "%s", role: field, pose: %s, field: {resolution: 24}}
model: {k_C: 1000, L: 0}
"""


@pytest.fixture(scope="module")
def world(tmp_path_factory):
    return contactlab.World.from_yaml(TOOL_AMONG_PLATES, cache_dir=str(tmp_path_factory.mktemp("cache")))


def test_world_pairs_and_what_was_built(world):
    assert world.tool == "ball"
    assert world.bodies == ["ball", "floor", "wall", "far"]
    assert world.pairs == [("ball", "floor"), ("ball", "wall"), ("ball", "far")]
    assert world.pair_models == ["pointshell"] * 3
    assert world.built["floor"] == ["mesh", "field"]
    assert "pointshell" in world.built["ball"]


def test_every_pair_in_one_call_equals_each_pair_made_apart(world, tmp_path):
    r = world.query(np.array([0.0, 0.0, 0.018, 1, 0, 0, 0]))
    assert r["pair_force"].shape == (3, 3) and r["near"].dtype == bool
    assert r["near"].tolist() == [True, True, False]
    assert r["pairs_touching"] == 2
    np.testing.assert_array_equal(r["pair_force"][2], 0)
    # Each pair as a two-body scene of its own: the force on its field body is the same.
    for row, (name, mesh, pose) in enumerate([("floor", "box:0.04,0.04,0.01,2", "[0, 0, -0.01, 1, 0, 0, 0]"),
                                              ("wall", "box:0.01,0.04,0.04,2", "[0.028, 0, 0.03, 1, 0, 0, 0]")]):
        scene = contactlab.Scene.from_yaml(TWO_BODY % (name, mesh, pose), cache_dir=str(tmp_path))
        alone = scene.model("pointshell").query(scene.A.pose, scene.B.pose)
        np.testing.assert_allclose(r["pair_force"][row], alone["wrench"][:3], rtol=1e-12, atol=1e-12)
    # The tool is every pair's A: minus the sum of the forces on the Bs.
    np.testing.assert_allclose(r["force"], -r["pair_force"].sum(axis=0), rtol=1e-12)
    assert r["K_tool"].shape == (6, 6)


def test_a_tool_in_the_air_touches_nothing(world):
    r = world.query(np.array([0.2, 0.2, 0.3, 1, 0, 0, 0]))
    assert not r["near"].any()
    np.testing.assert_array_equal(r["force"], 0)


def test_bad_scenes_and_arguments_raise(world, tmp_path):
    with pytest.raises(contactlab.Error, match=r"<yaml text>:2: .*'hammer' is none of the scene's bodies"):
        contactlab.World.from_yaml(TOOL_AMONG_PLATES.replace("tool: ball", "tool: hammer"))
    with pytest.raises(contactlab.ArgumentError, match="tool_pose"):
        world.query(np.zeros(5))
    with pytest.raises(contactlab.ArgumentError, match="a World holds a scene of many bodies"):
        contactlab.World.from_yaml(TWO_BODY % ("floor", "box:0.04,0.04,0.01,2", "[0, 0, -0.01, 1, 0, 0, 0]"))
    with pytest.raises(contactlab.Error, match="the Python module's Scene takes a scene of two bodies"):
        contactlab.Scene.from_yaml(TOOL_AMONG_PLATES, cache_dir=str(tmp_path))


def test_a_world_from_dicts_takes_meshes_as_arrays(tmp_path):
    slab = contactlab.Scene.from_yaml(TWO_BODY % ("floor", "box:0.04,0.04,0.01,2", "[0, 0, -0.01, 1, 0, 0, 0]"),
                                      cache_dir=str(tmp_path)).B.mesh
    d = {
        "tool": "ball",
        "bodies": [
            {"name": "ball", "mesh": "sphere:0.02,3", "role": "pointshell", "pose": [0, 0, 0.018, 1, 0, 0, 0],
             "pointshell": {"points": 512, "levels": 3, "seed": 2}, "field": {"resolution": 24}},
            {"name": "floor", "mesh": contactlab.Mesh(slab.vertices, slab.triangles, name="slab"), "role": "field",
             "pose": [0, 0, -0.01, 1, 0, 0, 0], "field": {"resolution": 24}},
            {"name": "floor2", "mesh": "box:0.04,0.04,0.01,2", "role": "field", "pose": [0, 0, -0.01, 1, 0, 0, 0],
             "field": {"resolution": 24}},
        ],
        "model": {"k_C": 1000, "L": 0},
    }
    w = contactlab.World.from_dict(d, cache_dir=str(tmp_path))
    r = w.query()
    # The same slab from arrays and from its procedural shape: the same force.
    np.testing.assert_allclose(r["pair_force"][0], r["pair_force"][1], rtol=1e-9)
    assert r["pairs_touching"] == 2
