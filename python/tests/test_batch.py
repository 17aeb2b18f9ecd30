"""query_many equals a loop of single queries bit for bit, whatever form the poses take."""

import numpy as np
import pytest
from rotation_helpers import quaternion_to_matrix, random_poses

import contactlab


@pytest.fixture(scope="module")
def plate_scene(plate_scene_file):
    return contactlab.Scene.load(str(plate_scene_file))


@pytest.mark.parametrize("model_name", ["pointshell", "pointshell-linear", "vps"])
def test_batch_equals_single_queries(plate_scene, model_name):
    model = plate_scene.model(model_name)
    poses_A = random_poses(np.random.default_rng(7), 40, center=[0, 0, 0.0478], spread=0.004, tilt=0.1)
    poses_B = random_poses(np.random.default_rng(8), 40, center=[0, 0, -0.02], spread=0.002, tilt=0.05)
    batch = model.query_many(poses_A, poses_B)
    assert batch["wrench"].shape == (40, 6)
    assert batch["K_B"].shape == (40, 6, 6)
    touching = 0
    for i in range(40):
        r = model.query(poses_A[i], poses_B[i])
        assert np.array_equal(batch["wrench"][i], r["wrench"]), i
        assert np.array_equal(batch["K_B"][i], r["K_B"]), i
        for key, value in r["stats"].items():
            assert batch["stats"][key][i] == value, (i, key)
        touching += r["stats"]["points_in_contact"] > 0
    assert touching >= 10  # the batch is mostly in contact
    assert np.array_equal(batch["force"], batch["wrench"][:, :3])
    assert np.array_equal(batch["torque"], batch["wrench"][:, 3:])


def test_one_pose_is_used_for_every_query(plate_scene):
    model = plate_scene.model("pointshell")
    poses_A = random_poses(np.random.default_rng(3), 12, center=[0, 0, 0.0478], spread=0.003, tilt=0.1)
    pose_B = plate_scene.B.pose
    batch = model.query_many(poses_A, pose_B)
    full = model.query_many(poses_A, np.tile(pose_B, (12, 1)))
    assert np.array_equal(batch["wrench"], full["wrench"])
    assert np.array_equal(batch["K_B"], full["K_B"])


def test_matrices_give_the_poses_of_their_quaternions(plate_scene):
    model = plate_scene.model("pointshell")
    poses_A = random_poses(np.random.default_rng(5), 10, center=[0, 0, 0.0478], spread=0.003, tilt=0.2)
    X = np.zeros((10, 4, 4))
    X[:, 3, 3] = 1
    for i, p in enumerate(poses_A):
        X[i, :3, :3] = quaternion_to_matrix(p[3:])
        X[i, :3, 3] = p[:3]
    from_quaternions = model.query_many(poses_A, plate_scene.B.pose)["wrench"]
    from_matrices = model.query_many(X, plate_scene.B.pose)["wrench"]
    scale = np.abs(from_quaternions).max()
    assert scale > 0
    np.testing.assert_allclose(from_matrices, from_quaternions, rtol=0, atol=1e-6 * scale)
    single = model.query(X[0], plate_scene.B.pose)
    np.testing.assert_allclose(single["wrench"], from_quaternions[0], rtol=0, atol=1e-6 * scale)


def test_two_threads_querying_two_models_get_what_each_gets_alone(plate_scene):
    import threading

    models = [plate_scene.model("pointshell"), plate_scene.model("pointshell-linear")]
    poses_A = random_poses(np.random.default_rng(11), 200, center=[0, 0, 0.0478], spread=0.003, tilt=0.1)
    alone = [m.query_many(poses_A, plate_scene.B.pose)["wrench"] for m in models]
    together = [None, None]

    def work(i):
        together[i] = models[i].query_many(poses_A, plate_scene.B.pose)["wrench"]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(alone, together):
        assert np.array_equal(a, b)


def ran_while_the_gil_was_free(call):
    """Whether another Python thread ran while CALL() ran, seen by the calling thread the moment
    CALL returns. The interpreter's switch interval is made huge, so no thread is ever made to
    give up the GIL: the other thread, woken before CALL starts, can run only when the calling
    thread lets the GIL go of its own accord, and between waking it and reading its flag this
    thread does so nowhere but inside CALL. A CALL that holds the GIL therefore always reads
    False; one that releases it reads True unless CALL ends before the woken thread is scheduled
    at all (the callers repeat with longer calls)."""
    import sys
    import threading

    wake, ran, done = threading.Event(), threading.Event(), threading.Event()
    seen = []

    def other():
        wake.wait()
        ran.set()
        done.wait()

    def caller():
        wake.set()
        call()
        seen.append(ran.is_set())  # before this thread could give the GIL away
        done.set()

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        threads = [threading.Thread(target=other), threading.Thread(target=caller)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    finally:
        sys.setswitchinterval(interval)
    return seen == [True]


def test_query_many_releases_the_gil(plate_scene):
    """Another Python thread runs while a batch is evaluated (a held GIL fails every attempt)."""
    model = plate_scene.model("pointshell")
    for n in (2000, 8000, 32000):
        poses_A = np.tile(plate_scene.A.pose, (n, 1))
        if ran_while_the_gil_was_free(lambda: model.query_many(poses_A, plate_scene.B.pose)):
            return
    pytest.fail("no other thread ran during query_many of up to 32,000 queries: the GIL was held")


def test_distance_releases_the_gil(plate_scene):
    """Another Python thread runs while Body.distance evaluates many points."""
    plate_scene.B.distance(np.zeros(3))  # the field is built (holding the GIL) before
    for n in (100000, 400000, 1600000):
        points = np.random.default_rng(1).uniform(-0.05, 0.05, size=(n, 3))
        if ran_while_the_gil_was_free(lambda: plate_scene.B.distance(points)):
            return
    pytest.fail("no other thread ran during distance() of up to 1,600,000 points: the GIL was held")


@pytest.mark.parametrize("model_name", ["pointshell", "vps"])
def test_query_many_of_an_empty_batch_returns_empty_arrays(plate_scene, model_name):
    """An empty batch, against one pose or another empty batch, gives N = 0 rows of every array
    (NumPy's broadcasting: a single pose is used for every one of no queries)."""
    model = plate_scene.model(model_name)
    A, B = plate_scene.A.pose, plate_scene.B.pose
    cases = [
        (np.zeros((0, 7)), B),
        (A, np.zeros((0, 7))),
        (np.zeros((0, 4, 4)), np.eye(4)),
        (np.eye(4), np.zeros((0, 4, 4))),
        (np.zeros((0, 7)), np.zeros((0, 4, 4))),
        (A[np.newaxis], np.zeros((0, 7))),
    ]
    for poses_A, poses_B in cases:
        batch = model.query_many(poses_A, poses_B)
        assert batch["wrench"].shape == (0, 6)
        assert batch["force"].shape == (0, 3)
        assert batch["torque"].shape == (0, 3)
        assert batch["K_B"].shape == (0, 6, 6)
        assert set(batch["stats"]) == set(model.query(A, B)["stats"])
        for key, values in batch["stats"].items():
            assert values.shape == (0,), key
    # An empty batch beside a batch of two is no broadcast: the counts must agree.
    with pytest.raises(contactlab.Error, match=r"poses_A has 0 poses and poses_B 2"):
        model.query_many(np.zeros((0, 7)), np.tile(B, (2, 1)))
    # The model still answers afterwards.
    assert model.query_many(A, B)["wrench"].shape == (1, 6)
