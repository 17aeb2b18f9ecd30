"""Bad input raises contactlab.Error (a RuntimeError) whose message names what is wrong: the
file, line and key of a scene, the argument of a call."""

import numpy as np
import pytest

import contactlab
from conftest import SMALL_SCENE


def test_error_is_a_runtime_error():
    assert issubclass(contactlab.Error, RuntimeError)


def test_unknown_scene_key_names_line_and_key():
    text = SMALL_SCENE.replace("model: {k_C: 1500,", "model: {k_C: 1500, stiffnes: 3,")
    with pytest.raises(contactlab.Error) as e:
        contactlab.Scene.from_yaml(text)
    assert e.match(r"<yaml text>:14: model.*stiffnes")


def test_bad_value_names_the_key():
    text = SMALL_SCENE.replace("points: 1500", "points: many")
    with pytest.raises(contactlab.Error, match=r"<yaml text>:7: .*bodies\[0\]\.pointshell\.points.*many"):
        contactlab.Scene.from_yaml(text)


def test_scene_file_errors_name_the_file(tmp_path):
    path = tmp_path / "broken.yaml"
    path.write_text(SMALL_SCENE.replace("role: field", "role: pointshell"))
    with pytest.raises(contactlab.Error, match=r"broken\.yaml:\d+: .*role.*different roles"):
        contactlab.Scene.load(str(path))
    with pytest.raises(contactlab.Error, match="no-such-scene.yaml"):
        contactlab.Scene.load(str(tmp_path / "no-such-scene.yaml"))


def test_unknown_model_lists_the_known_ones(small_scene_file):
    scene = contactlab.Scene.load(str(small_scene_file))
    with pytest.raises(contactlab.Error, match=r"unknown contact model 'pointshel'.*pointshell"):
        scene.model("pointshel")


def test_bad_model_parameter_names_the_key(small_scene_file):
    scene = contactlab.Scene.load(str(small_scene_file))
    with pytest.raises(contactlab.Error, match=r"keyword arguments:\d+: model\.k_C"):
        scene.model("pointshell", k_C=-5)
    with pytest.raises(contactlab.Error, match=r"keyword arguments:\d+: .*stiffness"):
        scene.model("pointshell", stiffness=1)
    with pytest.raises(TypeError):
        scene.model("pointshell", k_C=object())


def test_bad_poses_name_the_argument_and_shape(small_scene_file):
    model = contactlab.Scene.load(str(small_scene_file)).model("pointshell")
    good = np.array([0, 0, 0.01, 1, 0, 0, 0.0])
    with pytest.raises(contactlab.Error, match=r"X_WA: a pose is a 7-vector .* got shape \(6,\)"):
        model.query(np.zeros(6), good)
    with pytest.raises(contactlab.Error, match="X_WB: the quaternion is zero"):
        model.query(good, np.zeros(7))
    with pytest.raises(contactlab.Error, match="X_WB: pose component 2 is not finite"):
        model.query(good, np.array([0, 0, np.nan, 1, 0, 0, 0]))
    # A quaternion not of unit length (within 1e-6) is refused naming the order, as the command
    # line and scene files refuse it; one unit to nine digits passes.
    with pytest.raises(contactlab.ArgumentError,
                       match=r"X_WB: the quaternion \(qw, qx, qy, qz\) = \(0\.99, 0\.1, 0, 0\) has length .* "
                             r"x, y, z, qw, qx, qy, qz"):
        model.query(good, np.array([0, 0, 0, 0.99, 0.1, 0, 0]))
    with pytest.raises(contactlab.ArgumentError, match=r"poses_B\[1\]: the quaternion .* has length 2,"):
        model.query_many(good, np.array([good, [0, 0, 0, 2, 0, 0, 0]]))
    model.query(good, np.array([0, 0, 0, 0.965925826, 0, 0.258819045, 0]))
    not_rigid = np.eye(4)
    not_rigid[0, 0] = 2
    with pytest.raises(contactlab.Error, match="X_WA: pose matrix: .* not a rotation"):
        model.query(not_rigid, good)
    with pytest.raises(contactlab.Error, match=r"poses_A\[1\]: the quaternion is zero"):
        model.query_many(np.array([good, np.zeros(7)]), good)
    with pytest.raises(contactlab.Error, match=r"poses_A has 3 poses and poses_B 2"):
        model.query_many(np.tile(good, (3, 1)), np.tile(good, (2, 1)))
    with pytest.raises(contactlab.Error, match=r"poses_B: poses are an \(N, 7\) array .* got shape \(2, 5\)"):
        model.query_many(good, np.zeros((2, 5)))


def test_bad_points_and_levels(small_scene_file):
    scene = contactlab.Scene.load(str(small_scene_file))
    with pytest.raises(contactlab.Error, match=r"block: distance\(points\): points must be an \(N, 3\) array"):
        scene.B.distance(np.zeros((4, 2)))
    with pytest.raises(contactlab.Error, match="ring: pointshell level: 7 is outside -1"):
        scene.A.pointshell(level=7)


def test_reduced_coordinates_of_a_rigid_body_are_refused(small_scene_file):
    model = contactlab.Scene.load(str(small_scene_file)).model("pointshell")
    with pytest.raises(contactlab.Error, match="q_A"):
        model.query(np.array([0, 0, 0.01, 1, 0, 0, 0.0]), np.array([0, 0, -0.01, 1, 0, 0, 0.0]), q_A=np.zeros(3))


def test_run_errors_name_the_config(tmp_path, plate_scene_file):
    config = tmp_path / "bad.yaml"
    config.write_text(f"name: bad\nscene: {plate_scene_file}\nmodels: [pointshell]\n"
                      "trajectory: {type: approach-press, direction: toward, depht: 0.001, duration: 0.01}\n")
    with pytest.raises(contactlab.Error, match=r"bad\.yaml:\d+: .*depht"):
        contactlab.run(config, out=tmp_path / "out")
    assert not (tmp_path / "out").exists()
    with pytest.raises(contactlab.Error, match="no-such-results"):
        contactlab.load_results(tmp_path / "no-such-results")


def test_distance_of_a_nan_point_raises_value_error_naming_the_argument(small_scene_file):
    """No non-finite number passes the argument conversion as a point or a pose: it raises
    contactlab.ArgumentError, a ValueError (and a contactlab.Error), naming the argument."""
    scene = contactlab.Scene.load(str(small_scene_file))
    with pytest.raises(ValueError, match=r"block: distance\(points\): points has a coordinate that is not finite"):
        scene.B.distance(np.array([0, np.nan, 0.0]))
    assert issubclass(contactlab.ArgumentError, ValueError)
    assert issubclass(contactlab.ArgumentError, contactlab.Error)
    with pytest.raises(ValueError, match=r"ring: distance\(points\): points\[1\] has a coordinate that is not finite"):
        scene.A.distance(np.array([[0, 0, 0.01], [0, 0, np.inf]]))
    # Finite points are answered as before, a (3,) point as a float.
    assert np.isfinite(scene.B.distance(np.array([0, 0, 0.01])))
    assert scene.B.distance(np.zeros((0, 3))).shape == (0,)
    # Poses, one or a batch, 7-vectors or matrices.
    model = scene.model("pointshell")
    good = np.array([0, 0, 0.01, 1, 0, 0, 0.0])
    with pytest.raises(ValueError, match="X_WB: pose component 2 is not finite"):
        model.query(good, np.array([0, 0, np.nan, 1, 0, 0, 0]))
    X = np.eye(4)
    X[1, 3] = np.nan
    with pytest.raises(ValueError, match="X_WA: pose matrix has a value that is not finite"):
        model.query(X, good)
    with pytest.raises(ValueError, match=r"poses_A\[1\]: pose component 4 is not finite"):
        model.query_many(np.array([good, [0, 0, 0, 1, np.nan, 0, 0]]), good)
    with pytest.raises(ValueError, match=r"poses_B\[0\]: pose matrix has a value that is not finite"):
        model.query_many(good, X[np.newaxis])
    with pytest.raises(ValueError, match=r"q_A: value 2 is not a finite number"):
        model.query(good, good, q_A=np.array([0, np.nan]))
    # Other bad arguments of the same conversion are ValueErrors too.
    with pytest.raises(ValueError, match=r"points must be an \(N, 3\) array"):
        scene.B.distance(np.zeros((4, 2)))
    with pytest.raises(ValueError, match=r"poses_A has 3 poses and poses_B 2"):
        model.query_many(np.tile(good, (3, 1)), np.tile(good, (2, 1)))
