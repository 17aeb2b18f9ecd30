"""Generated arguments (Hypothesis) for every call that converts arrays: Model.query (X_WA, X_WB,
q_A), Model.query_many (poses_A, poses_B), Body.distance (points), Mesh (vertices, triangles) and
what a Python model's function returns. Poses, batches and points of every dtype, shape, order
and stride, contiguous or not, with NaN, inf and huge values, empty batches, wrong shapes, Python lists and tuples,
scalars, None and strings. The property, for each: the call either answers exactly what it
answers for the same numbers given in the canonical form, a float64 C-contiguous array made by
NumPy itself (the independent reference), or raises a ValueError (contactlab.ArgumentError) or
TypeError naming the argument; never a crash, another exception, or an answer for input that is
not real numbers. Deterministic (derandomize, no example database): a failure reproduces."""

import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, example, given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import contactlab
from conftest import SMALL_SCENE
from rotation_helpers import quaternion_to_matrix

# Few examples per call, the same ones every run: the whole file takes seconds.
GENERATED = settings(max_examples=100, derandomize=True, database=None, deadline=None, print_blob=False,
                     suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                            HealthCheck.filter_too_much])

# The small scene's poses (conftest.SMALL_SCENE): the ring resting in the block, in contact.
POSE_A = np.array([0.001, -0.002, 0.0113, 0.9659258262890683, 0.0, 0.25881904510283985, 0.0])
POSE_B = np.array([0.0, 0.0, -0.01, 1.0, 0.0, 0.0, 0.0])

SPECIAL = [np.nan, np.inf, -np.inf, 1e308, -1e308, 1e200, 5e-324, -0.0, 1e30, 2.0**63]


@pytest.fixture(scope="module")
def scene():
    return contactlab.Scene.from_yaml(SMALL_SCENE)


@pytest.fixture(scope="module")
def model(scene):
    return scene.model("pointshell")


# --- the canonical form and the outcome of a call ------------------------------------------------

def canonical(obj):
    """OBJ as NumPy reads it, float64 and C-contiguous; None when it is not an array of real
    numbers (bool, integer, floating): complex, strings, datetimes, objects, ragged lists."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            a = np.asarray(obj)
    except (ValueError, TypeError):
        return None
    if a.dtype.kind not in "biuf":
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a longdouble beyond float64 becomes inf, as it should
        return np.array(a, dtype=np.float64, order="C")  # (ascontiguousarray makes a scalar 1-D)


def flat(result):
    """A result (dict of arrays and a stats dict, or a float, or an array) as comparable leaves."""
    if isinstance(result, dict):
        return {k: flat(v) for k, v in result.items()}
    return np.array(result, copy=True)


def outcome(call, *args, **kwargs):
    """('ok', result) or ('raised', type, message) for a ValueError or TypeError; any other
    exception fails the test where it is raised."""
    try:
        return ("ok", flat(call(*args, **kwargs)))
    except (ValueError, TypeError) as e:
        return ("raised", type(e), str(e))


def assert_same(a, b):
    assert a[0] == b[0], (a, b)
    if a[0] == "raised":
        assert a[1:] == b[1:]
        return
    x, y = a[1], b[1]
    if isinstance(x, dict):
        assert x.keys() == y.keys()
        for k in x:
            assert_same(("ok", x[k]), ("ok", y[k]))
    else:
        assert x.shape == y.shape and x.dtype == y.dtype and np.array_equal(x, y), (x, y)


def check_conversion(call, obj, name, **kwargs):
    """The property: OBJ answers as its canonical form does, or raises ValueError / TypeError
    naming the argument NAME; OBJ that is not real numbers always raises."""
    got = outcome(call, obj, **kwargs)
    if got[0] == "raised":
        assert name in got[2], got
    ref = canonical(obj)
    if ref is None:
        assert got[0] == "raised", (obj, got)
        return got
    assert_same(got, outcome(call, ref, **kwargs))
    return got


# --- strategies ----------------------------------------------------------------------------------

def pose7(base):
    """7-vectors near BASE (touching): small moves, the quaternion at any scale or sign, and
    now and then a special value in any component."""
    return st.builds(
        lambda d, q, scale, special: _with_special(
            np.concatenate([base[:3] + d, (base[3:] + q) * scale]), special),
        hnp.arrays(np.float64, 3, elements=st.floats(-5e-4, 5e-4)),
        hnp.arrays(np.float64, 4, elements=st.floats(-0.05, 0.05)),
        st.sampled_from([1.0, -1.0, 2.0**-30, 1e-13, 3.0, 2.0**600, 1e300]),
        st.one_of(st.none(), st.tuples(st.integers(0, 6), st.sampled_from(SPECIAL))))


def matrix(base):
    """4x4 matrices of the poses near BASE, now and then scaled or with a special value."""
    def build(p, scale, special):
        X = np.eye(4)
        X[:3, :3] = quaternion_to_matrix(p[3:]) * scale
        X[:3, 3] = p[:3]
        if special is not None:
            X.flat[special[0]] = special[1]
        return X
    finite = pose7(base).filter(lambda p: np.isfinite(p).all() and 1e-12 < np.linalg.norm(p[3:]) < 1e150)
    return st.builds(build, finite, st.sampled_from([1.0, 1.0, 1.0, 1e200, -1.0, 1 + 1e-9]),
                     st.one_of(st.none(), st.tuples(st.integers(0, 15), st.sampled_from(SPECIAL))))


def _with_special(v, special):
    if special is not None:
        v[special[0]] = special[1]
    return v


def batch(one, shape):
    """(N, *SHAPE) arrays of N = 0 to 3 rows drawn from ONE."""
    return st.lists(one, min_size=0, max_size=3).map(
        lambda rows: np.array(rows, dtype=np.float64).reshape((len(rows),) + shape))


# Every form the same numbers may come in: dtypes, orders, strides, containers.
DTYPES = [np.float64, np.float32, np.float16, np.longdouble, ">f8", np.int64, np.int8, np.uint16, np.bool_,
          np.complex128, object, "U24", "datetime64[s]"]


def _as_dtype(c, dtype):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if dtype == "datetime64[s]":
            return np.zeros(c.shape, dtype=np.int64).astype(dtype)
        if np.dtype(dtype).kind in "iub":
            return np.nan_to_num(c, posinf=0, neginf=0).clip(-100, 100).astype(dtype)
        return c.astype(dtype)


def _strided(c):
    big = np.zeros(c.shape[:-1] + (2 * c.shape[-1],)) if c.ndim else np.zeros(2)
    if not c.ndim:
        return c
    big[..., ::2] = c
    return big[..., ::2]


def _unaligned(c):
    raw = np.zeros(c.nbytes + 1, dtype=np.uint8)
    a = raw[1:].view(np.float64).reshape(c.shape) if c.nbytes else c
    a[...] = c
    return a


def _read_only(c):
    c = c.copy()
    c.setflags(write=False)
    return c


FORMS = {
    "float64": lambda c: c,
    "fortran": np.asfortranarray,
    "strided": _strided,
    "reversed": lambda c: np.flip(np.flip(c).copy()),
    "broadcast": lambda c: np.broadcast_to(c[:1], c.shape) if c.ndim >= 2 and len(c) else c,  # stride 0
    "unaligned": _unaligned,
    "read-only": _read_only,
    "list": lambda c: c.tolist(),
    "tuple": lambda c: tuple(map(tuple, c)) if c.ndim == 2 else tuple(c.tolist()) if c.ndim == 1 else c.tolist(),
    "memoryview": lambda c: memoryview(np.ascontiguousarray(c)),
}


def forms(values):
    """VALUES (float64 arrays) in every form and dtype."""
    return st.one_of(
        st.builds(lambda c, f: FORMS[f](c), values, st.sampled_from(sorted(FORMS))),
        st.builds(_as_dtype, values, st.sampled_from(DTYPES)))


# Not arrays of numbers at all, and arrays of every shape.
JUNK = st.one_of(
    st.none(), st.just(object()), st.booleans(), st.integers(), st.floats(), st.complex_numbers(),
    st.text(max_size=4), st.binary(max_size=8),
    st.lists(st.one_of(st.floats(), st.none(), st.text(max_size=2)), max_size=8),
    st.lists(st.lists(st.floats(), max_size=8), max_size=3),  # ragged
    hnp.arrays(np.float64, hnp.array_shapes(min_dims=0, max_dims=4, min_side=0, max_side=8),
               elements=st.floats(allow_nan=True, allow_infinity=True)))

POSES = st.one_of(forms(pose7(POSE_A)), forms(matrix(POSE_A)), JUNK)
BATCHES = st.one_of(forms(batch(pose7(POSE_A), (7,))), forms(batch(matrix(POSE_A), (4, 4))), POSES)
POINTS = st.one_of(
    forms(hnp.arrays(np.float64, st.sampled_from([(3,), (0, 3), (1, 3), (4, 3)]),
                     elements=st.one_of(st.floats(-0.05, 0.05), st.sampled_from(SPECIAL)))),
    JUNK)


# --- the properties, one per converting call -----------------------------------------------------

@GENERATED
@given(pose=POSES, side=st.sampled_from(["X_WA", "X_WB"]))
@example(pose=POSE_A.astype(np.float32), side="X_WA")
@example(pose=np.array(["0", "0", "0.01", "1", "0", "0", "0"]), side="X_WB")
def test_query_takes_a_pose_in_any_form_or_names_it(model, pose, side):
    if side == "X_WA":
        got = check_conversion(lambda p: model.query(p, POSE_B), pose, "X_WA")
    else:
        got = check_conversion(lambda p: model.query(POSE_A, p), pose, "X_WB")
    if got[0] == "ok":
        assert np.isfinite(got[1]["wrench"]).all()


@GENERATED
@given(poses=BATCHES, other=st.sampled_from(["one", "same", "two"]), side=st.sampled_from(["poses_A", "poses_B"]))
def test_query_many_takes_batches_in_any_form_or_names_them(model, poses, other, side):
    ref = canonical(poses)
    n = ref.shape[0] if ref is not None and ref.ndim in (2, 3) and ref.shape[-1] in (4, 7) else 1
    fixed = {"one": POSE_B if side == "poses_A" else POSE_A,
             "same": np.tile(POSE_B if side == "poses_A" else POSE_A, (n, 1)),
             "two": np.tile(POSE_B if side == "poses_A" else POSE_A, (2, 1))}[other]
    if side == "poses_A":
        got = check_conversion(lambda p: model.query_many(p, fixed), poses, "poses_")
    else:
        got = check_conversion(lambda p: model.query_many(fixed, p), poses, "poses_")
    if got[0] == "ok":
        # Each row is the single query at the canonical row's poses.
        rows = got[1]["wrench"].shape[0]
        P = ref.reshape((-1, 4, 4) if ref.shape[-1] == 4 else (-1, 7))
        F = np.asarray(fixed).reshape(-1, 7)
        for i in range(rows):
            a = P[i if len(P) > 1 else 0]
            b = F[i if len(F) > 1 else 0]
            single = model.query(a, b) if side == "poses_A" else model.query(b, a)
            assert np.array_equal(single["wrench"], got[1]["wrench"][i]), i


@GENERATED
@given(points=POINTS, body=st.sampled_from(["A", "B"]))
def test_distance_takes_points_in_any_form_or_names_them(scene, points, body):
    b = scene.A if body == "A" else scene.B
    got = check_conversion(b.distance, points, "distance(points)")
    if got[0] == "ok":
        assert np.isfinite(got[1]).all()


@GENERATED
@given(q=st.one_of(forms(hnp.arrays(np.float64, st.integers(0, 4), elements=st.floats(-1e-3, 1e-3))),
                   JUNK.filter(lambda q: q is not None)))
def test_reduced_coordinates_of_a_rigid_body_raise_naming_them(model, q):
    """The small scene's bodies are rigid: any q_A is refused, as a ValueError or TypeError."""
    got = outcome(model.query, POSE_A, POSE_B, q_A=q)
    assert got[0] == "raised" and "q_A" in got[2], got


@pytest.fixture(scope="module")
def deformable_model(data_dir):
    scene = contactlab.Scene.load(str(data_dir / "scenes" / "cantilever-probe.yaml"))
    assert scene.A.deformable
    return scene.model(), scene.A.pose, scene.B.pose


@settings(GENERATED, max_examples=40)
@given(q=st.one_of(
    forms(hnp.arrays(np.float64, st.sampled_from([(10,), (10,), (3,), (0,), (2, 5)]),
                     elements=st.one_of(st.floats(-1e-3, 1e-3), st.sampled_from(SPECIAL)))),
    JUNK.filter(lambda q: q is not None)))
def test_reduced_coordinates_of_a_deformable_body_in_any_form_or_named(deformable_model, q):
    """The cantilever's ten coordinates answer as their float64 form does, or raise naming q_A."""
    model, X_WA, X_WB = deformable_model
    got = check_conversion(lambda v: model.query(X_WA, X_WB, q_A=v), q, "q_A")
    if got[0] == "ok":
        assert np.isfinite(got[1]["reduced_force_A"]).all()


@GENERATED
@given(returned=st.one_of(
    forms(hnp.arrays(np.float64, st.sampled_from([(6,), (5,), (2, 3)]), elements=st.floats(-10, 10))), JUNK))
def test_a_python_models_return_is_converted_as_an_argument_is(scene, returned):
    """What a Python model's function returns answers as its canonical form does, or raises
    contactlab.Error naming the model; values that are not real numbers always raise."""
    assume(not (isinstance(returned, tuple) and len(returned) == 2))  # that is (wrench, K_B)
    contactlab.register_model("py-generated-return", lambda X_WA, X_WB: returned)
    model = scene.model("py-generated-return")
    ref = canonical(returned)
    try:
        r = model.query(POSE_A, POSE_B)
    except contactlab.Error as e:
        assert "py-generated-return" in str(e)
        r = None
    if ref is None or ref.size != 6 or not np.isfinite(ref).all():
        assert r is None, (returned, r)
    else:
        assert r is not None
        assert np.array_equal(r["wrench"], ref.reshape(6))


# A tetrahedron, outward counter-clockwise: the arrays contactlab.Mesh's are varied around.
TET_VERTICES = np.array([[0, 0, 0], [0.05, 0, 0], [0, 0.05, 0], [0, 0, 0.05]])
TET_TRIANGLES = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
VERTICES = st.one_of(
    forms(hnp.arrays(np.float64, st.sampled_from([(4, 3), (6, 3), (0, 3), (3,), (4, 2)]),
                     elements=st.one_of(st.floats(-0.05, 0.05), st.sampled_from(SPECIAL)))),
    JUNK)
TRIANGLES = st.one_of(
    forms(hnp.arrays(np.float64, st.sampled_from([(4, 3), (1, 3), (0, 3), (3,), (4, 4)]),
                     elements=st.one_of(st.integers(0, 3).map(float), st.sampled_from([-1.0, 4.0, 0.5, 2.0**63])))),
    JUNK)


def mesh_arrays(vertices, triangles):
    m = contactlab.Mesh(vertices, triangles, name="tet")
    return {"vertices": m.vertices, "triangles": m.triangles}


@GENERATED
@given(vertices=VERTICES)
def test_mesh_takes_vertices_in_any_form_or_names_them(vertices):
    got = check_conversion(lambda v: mesh_arrays(v, TET_TRIANGLES), vertices, "contactlab.Mesh 'tet'")
    if got[0] == "ok":
        assert np.isfinite(got[1]["vertices"]).all()


@GENERATED
@given(triangles=TRIANGLES)
def test_mesh_takes_indices_of_any_integer_form_or_names_them(triangles):
    """Indices of an integer dtype, or floating with whole values, give the mesh of their int64
    values; anything else raises ValueError or TypeError naming the mesh."""
    got = outcome(lambda t: mesh_arrays(TET_VERTICES, t), triangles)
    if got[0] == "raised":
        assert "contactlab.Mesh 'tet'" in got[2], got
        return
    a = np.asarray(triangles)
    assert a.dtype.kind in "iuf" and np.all(a == np.trunc(a)), (triangles, got)
    assert np.array_equal(got[1]["triangles"], a.astype(np.int64))
    assert ((got[1]["triangles"] >= 0) & (got[1]["triangles"] < 4)).all()


# --- regressions the generated inputs found ------------------------------------------------------

def test_reduced_coordinates_that_do_not_fit_raise_argument_error(model):
    """q_A of a rigid body was a contactlab.Error that is no ValueError, unlike every other bad
    argument; it is an ArgumentError naming q_A now."""
    with pytest.raises(contactlab.ArgumentError, match=r"q_A \(body 'ring'\): the body is rigid"):
        model.query(POSE_A, POSE_B, q_A=np.zeros(3))
    with pytest.raises(TypeError, match=r"q_A: expected real numbers"):
        model.query(POSE_A, POSE_B, q_A=["a", "b"])


@pytest.mark.parametrize("bad", [
    np.array(["0.001", "0", "0.0113", "1", "0", "0", "0"]),       # was parsed as numbers
    POSE_A.astype(np.complex128) + 1j,                             # the imaginary part was dropped
    np.zeros(7, dtype="datetime64[s]"),                            # seconds since 1970 as metres
    np.array(list(POSE_A), dtype=object),                          # objects: refused, not called
    [0.001, 0, 0.0113, 1, 0, 0, None],                             # None was read as NaN
])
def test_poses_that_are_not_real_numbers_raise_type_error_naming_the_argument(model, bad):
    with pytest.raises(TypeError, match=r"X_WA: expected real numbers"):
        model.query(bad, POSE_B)
    with pytest.raises(TypeError, match=r"poses_B: expected real numbers"):
        model.query_many(POSE_A, bad)


def test_points_that_are_not_real_numbers_raise_type_error_naming_the_argument(scene):
    with pytest.raises(TypeError, match=r"block: distance\(points\): expected real numbers"):
        scene.B.distance(np.array(["0", "0", "0.01"]))
    with pytest.raises(TypeError, match=r"distance\(points\): expected real numbers"):
        scene.B.distance(np.array([0, 0, 0.01]) + 0j)


def test_distance_of_a_far_point_is_refused_not_infinite(scene):
    """A point 1e30 m away had distance +inf (the field's float arithmetic overflows); points
    beyond the bound of every coordinate, 1e9 m, are refused, and those within it are finite."""
    with pytest.raises(contactlab.ArgumentError, match=r"block: distance\(points\): points\[1\] has a coordinate "
                                                       r"beyond the limit of \+-1e9 m"):
        scene.B.distance(np.array([[0, 0, 0.0], [1e30, 0, 0]]))
    far = scene.B.distance(np.array([[1e9, -1e9, 1e9]]))
    assert np.isfinite(far).all() and far[0] > 1.7e9


def test_ragged_list_raises_argument_error_naming_the_argument(model):
    with pytest.raises(contactlab.ArgumentError, match=r"poses_A: not an array of numbers"):
        model.query_many([[0, 0, 0, 1, 0, 0, 0], [0, 0]], POSE_B)


# --- forms that were answered right before, kept so ---------------------------------------------

def test_matrix_whose_rotation_check_overflows_is_refused(model):
    """A 4x4 whose rotation block is huge: R^T R overflows (inf, and inf - inf = NaN), which the
    orthonormality check refuses, not passes."""
    X = np.eye(4)
    X[:3, :3] = quaternion_to_matrix(POSE_A[3:]) * 1e200
    X[:3, 3] = POSE_A[:3]
    with pytest.raises(contactlab.ArgumentError, match=r"X_WA: pose matrix: .* not a rotation"):
        model.query(X, POSE_B)
    with pytest.raises(contactlab.ArgumentError, match=r"poses_A\[0\]: pose matrix: .* not a rotation"):
        model.query_many(X[np.newaxis], POSE_B)


def test_lists_and_other_dtypes_answer_as_float64(model):
    """The same numbers as a list, float32 values, Fortran order or a strided view answer exactly
    as the float64 array NumPy makes of them."""
    ref = model.query(POSE_A, POSE_B)
    assert ref["stats"]["points_in_contact"] > 0  # the comparisons are of forces, not of zeros
    assert np.array_equal(model.query(POSE_A.tolist(), tuple(POSE_B))["wrench"], ref["wrench"])
    f32 = POSE_A.astype(np.float32)
    assert np.array_equal(model.query(f32, POSE_B)["wrench"], model.query(f32.astype(np.float64), POSE_B)["wrench"])
    assert np.array_equal(model.query(_strided(POSE_A), _unaligned(POSE_B))["wrench"], ref["wrench"])
