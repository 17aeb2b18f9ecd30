"""K_B, the model's d(wrench on B)/d(pose of B), against central finite differences of the
wrench through the Python API (the perturbation of contact_model.h: p_WB + dx, exp([dθ]) R_WB,
both in world coordinates). The pointshell model's K_B is the paper's sec. 5 halfspace rule, a
first-order model of the force, so the tolerance is loose."""

import numpy as np
import pytest
from rotation_helpers import quaternion_multiply, rotation_vector_to_quaternion

import contactlab


def finite_difference_K(model, pose_A, pose_B, h):
    K = np.zeros((6, 6))
    for j in range(6):
        plus, minus = np.array(pose_B, dtype=float), np.array(pose_B, dtype=float)
        if j < 3:
            plus[j] += h
            minus[j] -= h
        else:
            axis = np.eye(3)[j - 3]
            plus[3:] = quaternion_multiply(rotation_vector_to_quaternion(h * axis), pose_B[3:])
            minus[3:] = quaternion_multiply(rotation_vector_to_quaternion(-h * axis), pose_B[3:])
        w = model.query_many(np.array(pose_A), np.stack([plus, minus]))["wrench"]
        K[:, j] = (w[0] - w[1]) / (2 * h)
    return K


@pytest.mark.parametrize("pose_A", [
    [0.0, 0.0, 0.0482, 1.0, 0.0, 0.0, 0.0],
    [0.002 / 3, -0.001, 0.0478, 0.995007443, 0.0, 0.0998007465, 0.0],
])
def test_K_B_matches_finite_differences(plate_scene_file, pose_A):
    scene = contactlab.Scene.load(str(plate_scene_file))
    # L = 0: no L/l rescaling, whose steps as points enter would dominate the differences.
    model = scene.model("pointshell", L=0)
    pose_B = np.array([0.001, 0.0, -0.02, 0.999299335, 0.0200059927, -0.030008989, 0.0100029963])
    r = model.query(pose_A, pose_B)
    assert r["stats"]["points_in_contact"] > 20
    K_fd = finite_difference_K(model, pose_A, pose_B, h=2e-5)
    K = r["K_B"]
    # Force rows: d(force)/d(translation) and d(force)/d(rotation), each block to 25% of its size.
    for rows, cols in [(slice(0, 3), slice(0, 3)), (slice(0, 3), slice(3, 6))]:
        scale = np.abs(K_fd[rows, cols]).max()
        assert scale > 0
        err = np.abs(K[rows, cols] - K_fd[rows, cols]).max()
        assert err <= 0.25 * scale, f"block {rows},{cols}: K_B\n{K[rows, cols]}\nfinite differences\n{K_fd[rows, cols]}"
    # The dominant term: pressing B into A along the normal (z) stiffens the normal force.
    assert K[2, 2] < 0 and K_fd[2, 2] < 0
    np.testing.assert_allclose(K[2, 2], K_fd[2, 2], rtol=0.1)
