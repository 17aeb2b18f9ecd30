"""Small rotation helpers for the tests (NumPy only)."""

import numpy as np


def quaternion_to_matrix(q):
    """The rotation matrix of the quaternion (qw, qx, qy, qz), normalised first."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def rotation_vector_to_quaternion(w):
    """The unit quaternion (qw, qx, qy, qz) of the rotation by |w| radians about w."""
    w = np.asarray(w, dtype=float)
    angle = np.linalg.norm(w)
    if angle == 0:
        return np.array([1.0, 0.0, 0.0, 0.0])
    return np.concatenate([[np.cos(angle / 2)], np.sin(angle / 2) * w / angle])


def quaternion_multiply(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return np.array([aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw])


def random_poses(rng, n, center, spread, tilt):
    """N poses (x, y, z, qw, qx, qy, qz): positions uniform within SPREAD of CENTER, rotations by
    up to TILT radians about random axes."""
    poses = np.zeros((n, 7))
    poses[:, :3] = np.asarray(center) + rng.uniform(-spread, spread, size=(n, 3))
    for i in range(n):
        poses[i, 3:] = rotation_vector_to_quaternion(rng.uniform(-tilt, tilt, size=3))
    return poses
