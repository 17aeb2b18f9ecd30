"""A model written in Python (contactlab.register_model) queried through Model.query and
Model.query_many: what it returns is checked as a built-in model's result is, and it cannot
query itself."""

import numpy as np
import pytest

import contactlab
from conftest import SMALL_SCENE

POSE_A = np.array([0.001, 0, 0.048, 1, 0, 0, 0.0])
POSE_B = np.array([0, 0, -0.02, 1, 0, 0, 0.0])


@pytest.fixture(scope="module")
def scene():
    return contactlab.Scene.from_yaml(SMALL_SCENE)


@pytest.mark.parametrize("result", ["nan wrench", "inf K_B"])
def test_query_many_of_a_non_finite_result_raises_as_query_does(scene, result):
    """A non-finite wrench or K_B is an error on both paths, with the same message, never a row
    of NaN with no fault counted."""

    def law(X_WA, X_WB):
        w, K = np.zeros(6), np.zeros((6, 6))
        if result == "nan wrench":
            w[2] = np.nan
        else:
            K[2, 2] = np.inf
        return w, K

    contactlab.register_model("py-non-finite", law)
    model = scene.model("py-non-finite")
    message = r"py-non-finite: gave a non-finite wrench or stiffness at these poses"
    with pytest.raises(contactlab.Error, match=message):
        model.query(POSE_A, POSE_B)
    with pytest.raises(contactlab.Error, match=message):
        model.query_many(POSE_A, POSE_B)
    # The failing row of a batch is named.
    with pytest.raises(contactlab.Error, match=r"query_many\[0\]: " + message):
        model.query_many(np.tile(POSE_A, (3, 1)), POSE_B)
