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


# Run in a child interpreter, so that a model waiting for itself fails the test on a timeout
# instead of hanging the suite: each way a model's function may call its own Model.
SELF_QUERY = """
import sys
import numpy as np
import contactlab
sys.path.insert(0, {tests!r})
from conftest import SMALL_SCENE

scene = contactlab.Scene.from_yaml(SMALL_SCENE)
pose_A, pose_B = np.array({pose_A!r}), np.array({pose_B!r})
models = {{}}
calls = {{
    "query": lambda: models["self"].query(pose_A, pose_B),
    "query_many": lambda: models["self"].query_many(pose_A, pose_B),
    "reset": lambda: models["self"].reset(),
}}
reenter = [True]
for name, call in calls.items():
    def law(X_WA, X_WB, call=call):
        if reenter[0]:
            call()
        return np.zeros(6)
    reenter[0] = True
    contactlab.register_model("py-self-" + name, law)
    models["self"] = scene.model("py-self-" + name)
    for outer in ("query", "query_many"):
        try:
            getattr(models["self"], outer)(pose_A, pose_B)
            print(name, outer, "returned")
        except contactlab.Error as e:
            print(name, outer, "raised", type(e).__name__, str(e).replace("\\n", " "))
    # The same Model still answers once its function no longer calls it.
    reenter[0] = False
    assert np.array_equal(models["self"].query(pose_A, pose_B)["wrench"], np.zeros(6))
    assert models["self"].query_many(pose_A, pose_B)["wrench"].shape == (1, 6)
"""


def test_model_queried_from_its_own_python_function_raises():
    import subprocess
    import sys
    from pathlib import Path

    code = SELF_QUERY.format(tests=str(Path(__file__).parent), pose_A=POSE_A.tolist(), pose_B=POSE_B.tolist())
    try:
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("a Python model calling its own Model waited for itself (no answer in 60 s)")
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert len(lines) == 6, p.stdout
    for line in lines:
        inner, outer, what = line.split(" ", 3)[:3]
        assert what == "raised", line
        # The error names the model and the call made from inside its own evaluation.
        assert f"py-self-{inner}: {inner}() called from inside this model's own evaluation" in line, line
