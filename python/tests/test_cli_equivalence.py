"""The binding gives what the command line gives: `contactlab contact SCENE --json` at the same
poses, every number equal (the same code, the same cached fields and pointshells)."""

import numpy as np
import pytest

import contactlab
from conftest import pose_arg

# (scene fixture, pose of A, pose of B): non-trivial poses, translations not exact in binary.
CASES = [
    ("plate_scene_file", [0.001 / 3, -0.002, 0.0475, 0.9998, 0.0, 0.02, 0.0], [0.0, 0.0, -0.02, 1.0, 0.0, 0.0, 0.0]),
    ("plate_scene_file", [0.01, 0.004, 0.0483, 1.0, 0.0, 0.0, 0.0], [0.002, 0.0, -0.0201, 0.993683456, 0.100372066, 0.0, 0.0501860331]),
    ("small_scene_file", [0.001, -0.002, 0.0113, 0.9659258262890683, 0.0, 0.25881904510283985, 0.0],
     [0.0, 0.001 / 3, -0.0099, 1.0, 0.0, 0.0, 0.0]),
]
# Every built-in model of the module's registry, the reference-only ones included (not a list
# kept by hand: a new model is compared the day it is registered). Models written in Python,
# which the command does not know, are left out should one be registered before collection.
MODELS = [m for m in contactlab.models(references=True)
          if not contactlab.model_description(m).endswith("(Python, not real time)")]


def test_every_model_the_command_lists_is_compared(cli):
    listed = [line.split()[0] for line in cli("models").stdout.splitlines() if line.strip()]
    assert len(MODELS) == len(set(MODELS))
    assert set(MODELS) == set(listed)


@pytest.mark.parametrize("model_name", MODELS)
@pytest.mark.parametrize("case", range(len(CASES)))
def test_query_equals_command_line(request, cli_json, model_name, case):
    scene_fixture, pose_A, pose_B = CASES[case]
    scene_file = request.getfixturevalue(scene_fixture)
    expected = cli_json("contact", scene_file, "--model", model_name, "--pose-a", pose_arg(pose_A),
                        "--pose-b", pose_arg(pose_B), "--json")

    scene = contactlab.Scene.load(str(scene_file))
    r = scene.model(model_name).query(np.array(pose_A), np.array(pose_B))

    assert expected["model"] == model_name
    assert r["force"].tolist() == expected["force"]
    assert r["torque"].tolist() == expected["torque"]
    assert r["K_B"].tolist() == expected["K_B"]
    # Every stats field, the command's and the module's from one list (contact_stats_fields.h).
    assert set(r["stats"]) <= set(expected), set(r["stats"]) - set(expected)
    for key in ("points_in_contact", "nodes_visited", "level_rendered", "max_penetration", "stiffness_scale"):
        assert r["stats"][key] == expected[key], key
    for key in r["stats"]:
        assert r["stats"][key] == expected[key], key
    assert r["wrench"].tolist() == expected["force"] + expected["torque"]
    # Each model touches at each case: the equality is of forces, not of two zeros.
    assert r["stats"]["points_in_contact"] > 0, model_name
    assert np.linalg.norm(r["force"]) > 0, model_name


def test_cases_touch(plate_scene_file, small_scene_file):
    """The poses above press the bodies together: the comparison is of forces, not of zeros."""
    for scene_fixture, pose_A, pose_B in CASES:
        scene = contactlab.Scene.load(str(plate_scene_file if scene_fixture == "plate_scene_file" else small_scene_file))
        r = scene.model("pointshell").query(pose_A, pose_B)
        assert r["stats"]["points_in_contact"] > 0
        assert np.linalg.norm(r["force"]) > 0


def test_scene_model_override_equals_edited_scene(cli_json, plate_scene_file, tmp_path):
    """Scene.model(k_C=...) equals the command line on a copy of the scene with that k_C."""
    edited = tmp_path / "plate-k3000.yaml"
    edited.write_text(plate_scene_file.read_text().replace("k_C: 2000", "k_C: 3000"))
    assert "k_C: 3000" in edited.read_text()
    pose_A = [0.0, 0.001, 0.0478, 1.0, 0.0, 0.0, 0.0]
    expected = cli_json("contact", edited, "--model", "pointshell", "--pose-a", pose_arg(pose_A), "--json")
    scene = contactlab.Scene.load(str(plate_scene_file))
    r = scene.model("pointshell", k_C=3000).query(pose_A, scene.B.pose)
    assert r["force"].tolist() == expected["force"]
    assert r["K_B"].tolist() == expected["K_B"]
    base = scene.model("pointshell").query(pose_A, scene.B.pose)
    assert not np.array_equal(base["force"], r["force"])


def test_models_lists_the_command_line_models(cli):
    listed = [line.split()[0] for line in cli("models").stdout.splitlines() if line.strip()]
    assert set(contactlab.models()) <= set(listed)
    assert set(contactlab.models(references=True)) == set(listed)
    assert "pointshell" in contactlab.models()


def test_deformable_query_equals_command_line(cli_json, data_dir):
    """A deformable pointshell body held at reduced coordinates q_A, as `contact --q-a`."""
    scene_file = data_dir / "scenes" / "cantilever-probe.yaml"
    q_A = [0.001, -0.0002 / 3, 0, 0.0001, 0, 0, 0, 0, 0, 0]
    expected = cli_json("contact", scene_file, "--q-a", ",".join(repr(q) for q in q_A), "--json")
    scene = contactlab.Scene.load(str(scene_file))
    assert scene.A.deformable
    r = scene.model().query(scene.A.pose, scene.B.pose, q_A=np.array(q_A))
    assert r["stats"]["points_in_contact"] > 0
    assert r["force"].tolist() == expected["force"]
    assert r["K_B"].tolist() == expected["K_B"]
    assert r["reduced_force_A"].tolist() == expected["reduced_force_A"]
    with pytest.raises(contactlab.Error, match="q_A"):
        scene.model().query(scene.A.pose, scene.B.pose, q_A=np.zeros(3))
