"""Model.query(..., contacts=True): the model's contacts as NumPy arrays, shaped and typed as
documented, one per point in contact for the pointshell models, at the closed-form depth of a
ball pressed into a plate, and equal to what `contactlab contact --contacts --json` prints."""

import numpy as np
import pytest

import contactlab
from conftest import pose_arg

# data/scenes/sphere-on-plate.yaml at its own poses: a 5 cm ball 2 mm into the plate, whose
# top face is z = 0.
POSE_A = [0.0, 0.0, 0.048, 1.0, 0.0, 0.0, 0.0]
POSE_B = [0.0, 0.0, -0.02, 1.0, 0.0, 0.0, 0.0]
POINTSHELL_MODELS = ["pointshell", "pointshell-linear", "vps", "vps-repulsion"]


@pytest.fixture(scope="module")
def plate(plate_scene_file):
    return contactlab.Scene.load(str(plate_scene_file))


def test_contacts_are_none_unless_asked(plate):
    r = plate.model("pointshell").query(np.array(POSE_A), np.array(POSE_B))
    assert r["contacts"] is None


@pytest.mark.parametrize("name", POINTSHELL_MODELS)
def test_pointshell_contacts_are_the_points_in_contact(plate, name):
    r = plate.model(name).query(np.array(POSE_A), np.array(POSE_B), contacts=True)
    c = r["contacts"]
    n = r["stats"]["points_in_contact"]
    assert n > 0
    assert c["points"].shape == (n, 3) and c["points"].dtype == np.float64
    assert c["normals"].shape == (n, 3) and c["normals"].dtype == np.float64
    assert c["depths"].shape == (n,) and c["depths"].dtype == np.float64
    assert "areas" not in c and "pressures" not in c
    assert c["not_kept"] == 0
    np.testing.assert_allclose(np.linalg.norm(c["normals"], axis=1), 1.0, atol=1e-6)
    # Below the plate's top, at their distance below it (the plate's field is linear there:
    # within a tenth of its 2.5 mm cells), pushing the plate down.
    assert np.all(c["points"][:, 2] < 2.5e-4)
    np.testing.assert_allclose(c["depths"], -c["points"][:, 2], atol=2.5e-4)
    assert np.all(c["normals"][:, 2] < 0)
    # eq. (1): the force on B is k depth normal summed, k = k_C times the L / l scale.
    k = 2000 * r["stats"]["stiffness_scale"]
    force = k * (c["depths"][:, None] * c["normals"]).sum(axis=0)
    np.testing.assert_allclose(force, r["force"], rtol=0, atol=1e-5 * np.linalg.norm(r["force"]))


def test_pressure_field_contacts_have_areas_and_pressures(plate):
    r = plate.model("pressure-field").query(np.array(POSE_A), np.array(POSE_B), contacts=True)
    c = r["contacts"]
    n = len(c["depths"])
    assert n > 0
    assert c["areas"].shape == (n,) and c["pressures"].shape == (n,)
    assert c["areas"].dtype == np.float64 and c["pressures"].dtype == np.float64
    force = (c["areas"][:, None] * c["pressures"][:, None] * c["normals"]).sum(axis=0)
    np.testing.assert_allclose(force, r["force"], rtol=0, atol=1e-9 * np.linalg.norm(r["force"]))
    assert c["areas"].sum() == pytest.approx(r["stats"]["contact_area"], rel=1e-9)


def test_a_model_without_contacts_gives_none(plate):
    r = plate.model("eq2-halfspace").query(np.array(POSE_A), np.array(POSE_B), contacts=True)
    assert r["contacts"] is None
    assert np.linalg.norm(r["force"]) > 0


@pytest.mark.parametrize("name", ["pointshell", "fcl", "pressure-field"])
def test_contacts_equal_the_command_line(plate, plate_scene_file, cli_json, name):
    expected = cli_json("contact", plate_scene_file, "--model", name, "--pose-a", pose_arg(POSE_A),
                        "--pose-b", pose_arg(POSE_B), "--contacts", "--json")["contacts"]
    c = plate.model(name).query(np.array(POSE_A), np.array(POSE_B), contacts=True)["contacts"]
    assert sorted(expected) == sorted(c)
    for key, value in expected.items():
        assert np.asarray(c[key]).tolist() == value, key


@pytest.mark.parametrize("name", ["pointshell", "fcl"])
def test_friction_forces_are_returned_per_contact(data_dir, name):
    # data/scenes/block-on-plate.yaml (friction static 0.5, dynamic 0.4, stiffness 2000): the plate
    # slid under the block one cycle a micrometre (reset=False: the anchors carry over). After
    # 0.1 mm every contact sticks; after 1 mm they slide, holding 0.4 of the normal force.
    block = contactlab.Scene.load(str(data_dir / "scenes" / "block-on-plate.yaml"))
    model = block.model(name)
    pose_a = np.array([0.0, 0.0, 0.0095, 1.0, 0.0, 0.0, 0.0])
    for steps, sticks in [(100, True), (1000, False)]:
        for i in range(steps + 1):
            pose_b = np.array([1e-6 * i, 0.0, -0.02, 1.0, 0.0, 0.0, 0.0])
            r = model.query(pose_a, pose_b, reset=(i == 0), contacts=True)
        c = r["contacts"]
        n = len(c["depths"])
        assert n > 0
        assert c["tangential"].shape == (n, 3) and c["tangential"].dtype == np.float64
        assert c["sticking"].shape == (n,) and c["sticking"].dtype == np.bool_
        sliding = r["stats"]["contacts_sliding"]
        assert int(np.count_nonzero(~c["sticking"])) == sliding
        if sticks:
            assert sliding == 0
        else:  # all but the few that touch anew as the block's edge points graze the plate
            assert sliding >= 0.95 * n
        friction = c["tangential"].sum(axis=0)
        assert friction[0] < 0, "the plate moved +x: friction on it points -x"
        normal = -r["force"][2]
        if not sticks:
            np.testing.assert_allclose(-friction[0], 0.4 * normal, rtol=0.03)
