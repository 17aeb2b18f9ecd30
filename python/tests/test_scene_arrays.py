"""Scenes from NumPy arrays: contactlab.Mesh(vertices, triangles) and Scene.from_dict, checked
against closed forms (a box's distance to its faces), against the same scene read from YAML and
an OBJ file (the file route), and for a cache keyed by the mesh content."""

import copy

import numpy as np
import pytest

import contactlab

# A 20 x 20 x 4 cm plate: vertex i at (+-hx, +-hy, +-hz) by the bits of i (x, y, z), triangles
# counter-clockwise seen from outside.
HALF = np.array([0.1, 0.1, 0.02])
PLATE_VERTICES = np.array([[x, y, z] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)], dtype=float) * HALF
PLATE_TRIANGLES = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                            [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]])

BALL = {"name": "ball", "mesh": "sphere:0.05", "pose": [0, 0, 0.048, 1, 0, 0, 0], "role": "pointshell",
        "pointshell": {"points": 1024, "levels": 3, "seed": 2}, "field": {"resolution": 24}}


def plate_scene_dict(mesh):
    """Sphere-on-plate with the plate MESH (a contactlab.Mesh or a file name): the ball 2 mm deep."""
    return {
        "name": "ball-on-array-plate",
        "bodies": [copy.deepcopy(BALL),
                   {"name": "plate", "mesh": mesh, "pose": [0, 0, -0.02, 1, 0, 0, 0], "role": "field",
                    "field": {"resolution": 40}}],
        "model": {"k_C": 2000, "L": 10, "node_budget": 0, "coherence": False},
    }


def write_obj(path, vertices, triangles):
    """An OBJ file of the arrays, every digit kept (repr round-trips a double)."""
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in vertices.tolist()]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in triangles.tolist()]
    path.write_text("\n".join(lines) + "\n")


def with_entry(array, index, value):
    """A copy of ARRAY with VALUE at INDEX."""
    out = array.copy()
    out[index] = value
    return out


def cache_files(folder):
    """The cache entries in FOLDER, without the records they are kept with (NAME.key)."""
    return sorted(p.name for p in folder.iterdir() if p.suffix != ".key") if folder.exists() else []


@pytest.fixture
def plate():
    return contactlab.Mesh(PLATE_VERTICES, PLATE_TRIANGLES, name="plate")


def test_mesh_views_give_back_the_arrays(plate):
    assert plate.name == "plate"
    np.testing.assert_array_equal(plate.vertices, PLATE_VERTICES)
    np.testing.assert_array_equal(plate.triangles, PLATE_TRIANGLES)
    assert plate.vertices.dtype == np.float64 and plate.triangles.dtype == np.int32
    assert not plate.vertices.flags.writeable and not plate.triangles.flags.writeable
    assert "plate: 8 vertices, 12 triangles" in repr(plate)
    # A box of the arrays: its volume by the divergence theorem is that of the box.
    v, t = plate.vertices, plate.triangles
    volume = np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6
    assert volume == pytest.approx(np.prod(2 * HALF), rel=1e-12)


@pytest.mark.parametrize("triangles", [
    PLATE_TRIANGLES.astype(np.int32), PLATE_TRIANGLES.astype(np.uint8), PLATE_TRIANGLES.astype(np.uint64),
    PLATE_TRIANGLES.astype(float),  # whole numbers, as np.loadtxt reads faces
    PLATE_TRIANGLES.tolist(), np.asfortranarray(PLATE_TRIANGLES)])
def test_mesh_takes_any_lossless_index_array(triangles):
    np.testing.assert_array_equal(contactlab.Mesh(PLATE_VERTICES.tolist(), triangles).triangles, PLATE_TRIANGLES)


def test_from_dict_field_distance_is_the_distance_to_the_box_faces(plate):
    scene = contactlab.Scene.from_dict(plate_scene_dict(plate), use_cache=False)
    A, B = scene.bodies
    assert (A.name, B.name, B.role) == ("ball", "plate", "field")
    np.testing.assert_array_equal(B.mesh.vertices, PLATE_VERTICES)
    # Near the middle of a face the signed distance is the distance to that face, a linear
    # function the field's trilinear interpolation reproduces.
    hx, hy, hz = HALF
    points = np.array([[0, 0, hz + 0.01], [0.013, -0.021, hz + 1 / 300], [0, 0, hz - 0.005], [0.02, 0.01, -hz - 0.004],
                       [hx + 0.007, 0.01, 0.0], [0.01, -hy - 1 / 300, 0.001], [0.0, 0.0, hz - 1 / 300]])
    expected = [0.01, 1 / 300, -0.005, 0.004, 0.007, 1 / 300, -1 / 300]
    np.testing.assert_allclose(B.distance(points), expected, atol=1e-7)


def test_from_dict_and_the_yaml_obj_route_give_the_same_force(plate, tmp_path):
    memory = contactlab.Scene.from_dict(plate_scene_dict(plate), cache_dir=str(tmp_path / "cache-a"))
    write_obj(tmp_path / "plate.obj", PLATE_VERTICES, PLATE_TRIANGLES)
    text = f"""\
name: ball-on-obj-plate
bodies:
  - {{name: ball, mesh: "sphere:0.05", pose: [0, 0, 0.048, 1, 0, 0, 0], role: pointshell,
     pointshell: {{points: 1024, levels: 3, seed: 2}}, field: {{resolution: 24}}}}
  - {{name: plate, mesh: plate.obj, pose: [0, 0, -0.02, 1, 0, 0, 0], role: field, field: {{resolution: 40}}}}
model: {{k_C: 2000, L: 10, node_budget: 0, coherence: false}}
"""
    (tmp_path / "scene.yaml").write_text(text)
    from_file = contactlab.Scene.load(str(tmp_path / "scene.yaml"), cache_dir=str(tmp_path / "cache-b"))
    r_memory = memory.model("pointshell").query(memory.A.pose, memory.B.pose)
    r_file = from_file.model("pointshell").query(from_file.A.pose, from_file.B.pose)
    assert r_memory["force"][2] < -1.0  # the ball, 2 mm deep, pushes the plate down
    np.testing.assert_array_equal(r_memory["wrench"], r_file["wrench"])
    np.testing.assert_array_equal(r_memory["K_B"], r_file["K_B"])
    # The two routes built the same entries: the key is the mesh content, not its name or file.
    assert cache_files(tmp_path / "cache-a") == cache_files(tmp_path / "cache-b")


def test_the_cache_is_keyed_by_the_mesh_content(tmp_path):
    cache = tmp_path / "cache"

    def build(vertices):
        scene = contactlab.Scene.from_dict(plate_scene_dict(contactlab.Mesh(vertices, PLATE_TRIANGLES)),
                                           cache_dir=str(cache))
        return scene.B.distance([0, 0, 0.03])

    d = build(PLATE_VERTICES)
    first = cache_files(cache)
    assert len([f for f in first if f.startswith("field-")]) == 1
    # Equal arrays, another Mesh object: read from the cache, nothing new written.
    assert build(PLATE_VERTICES.copy()) == d
    assert cache_files(cache) == first
    # One vertex moved: another key, another entry.
    moved = PLATE_VERTICES.copy()
    moved[0, 0] -= 1e-6
    build(moved)
    assert len([f for f in cache_files(cache) if f.startswith("field-")]) == 2


@pytest.mark.parametrize("vertices, triangles, message", [
    (with_entry(PLATE_VERTICES, (3, 1), np.nan), PLATE_TRIANGLES,
     r"contactlab.Mesh 'plate': vertex 3 is not finite: \(0.1, nan, -0.02\)"),
    (with_entry(PLATE_VERTICES, (0, 2), np.inf), PLATE_TRIANGLES,
     r"contactlab.Mesh 'plate': vertex 0 is not finite"),
    (PLATE_VERTICES * 2e10, PLATE_TRIANGLES,
     r"contactlab.Mesh 'plate': vertex 0: coordinates out of range: \|coordinate\| reaches 2e\+09 m"),
    (PLATE_VERTICES, with_entry(PLATE_TRIANGLES, (5, 1), 8),
     r"contactlab.Mesh 'plate': triangle 5: face vertex index 8 out of range \[0, 8\)"),
    (PLATE_VERTICES, with_entry(PLATE_TRIANGLES, (1, 1), -1),
     r"contactlab.Mesh 'plate': triangle 1: face vertex index -1 out of range \[0, 8\)"),
    (PLATE_VERTICES, with_entry(PLATE_TRIANGLES.astype(np.uint64), (1, 1), 2**64 - 1),
     r"triangle 1: face vertex index 18446744073709551615 out of range \[0, 8\)"),
    (PLATE_VERTICES[:, :2], PLATE_TRIANGLES,
     r"contactlab.Mesh 'plate': vertices must be a \(V, 3\) array .*; got shape \(8, 2\)"),
    (PLATE_VERTICES.ravel(), PLATE_TRIANGLES, r"vertices must be a \(V, 3\) array .*; got shape \(24,\)"),
    (PLATE_VERTICES, PLATE_TRIANGLES[:, :2], r"triangles must be a \(T, 3\) array .*; got shape \(12, 2\)"),
    (PLATE_VERTICES, np.zeros((0, 3), dtype=int), r"contactlab.Mesh 'plate': no faces: the mesh has no triangles"),
    (np.zeros((0, 3)), PLATE_TRIANGLES, r"triangle 0: face vertex index 0 out of range \[0, 0\)"),
    ([], [], r"vertices must be a \(V, 3\) array .*; got shape \(0,\)"),
    ([[0, 0, 0], [1, 0]], PLATE_TRIANGLES, r"contactlab.Mesh 'plate': vertices: not an array of numbers"),
])
def test_mesh_refuses_what_the_mesh_readers_refuse_naming_the_row(vertices, triangles, message):
    with pytest.raises(contactlab.ArgumentError, match=message) as e:
        contactlab.Mesh(vertices, triangles, name="plate")
    assert isinstance(e.value, ValueError)


def test_mesh_messages_are_those_of_the_obj_reader(tmp_path):
    """An index out of range and a NaN say what the OBJ reader says of the same file."""
    bad = PLATE_TRIANGLES.copy()
    bad[5, 1] = 8
    write_obj(tmp_path / "plate.obj", PLATE_VERTICES, bad)
    (tmp_path / "s.yaml").write_text("bodies:\n  - {mesh: plate.obj, role: field}\n  - {mesh: 'sphere:0.1', role: pointshell}\n")
    with pytest.raises(contactlab.Error, match=r"face vertex index 9 out of range") as file_error:
        contactlab.Scene.load(str(tmp_path / "s.yaml"), use_cache=False).B.mesh
    with pytest.raises(contactlab.ArgumentError, match=r"face vertex index 8 out of range \[0, 8\)"):
        contactlab.Mesh(PLATE_VERTICES, bad)
    assert "out of range" in str(file_error.value)


@pytest.mark.parametrize("vertices, triangles, message", [
    (PLATE_VERTICES + 0j, PLATE_TRIANGLES, r"vertices: expected real numbers"),
    (PLATE_VERTICES.astype(str), PLATE_TRIANGLES, r"vertices: expected real numbers"),
    ([[0, 0, None]] * 8, PLATE_TRIANGLES, r"vertices: expected real numbers"),
    (PLATE_VERTICES, PLATE_TRIANGLES + 0.5, r"triangles\[0\] holds 0.5, not a whole number"),
    (PLATE_VERTICES, with_entry(PLATE_TRIANGLES.astype(float), (2, 2), np.nan), r"triangles\[2\] holds nan"),
    (PLATE_VERTICES, PLATE_TRIANGLES > 3, r"triangles must be integer vertex indices .* got dtype bool"),
    (PLATE_VERTICES, PLATE_TRIANGLES.astype(complex), r"got dtype complex128"),
    (PLATE_VERTICES, PLATE_TRIANGLES.astype(str), r"triangles must be integer vertex indices"),
])
def test_mesh_refuses_arrays_that_are_not_numbers_with_type_error(vertices, triangles, message):
    with pytest.raises(TypeError, match=message):
        contactlab.Mesh(vertices, triangles, name="plate")


def test_mesh_name_must_not_be_empty():
    with pytest.raises(contactlab.ArgumentError, match="name must not be empty"):
        contactlab.Mesh(PLATE_VERTICES, PLATE_TRIANGLES, name="")


def test_from_dict_takes_what_a_yaml_file_takes(plate):
    """File names, procedural shapes, tuples, NumPy arrays and scalars, None as YAML's null."""
    d = plate_scene_dict("box:0.1,0.1,0.02")
    d["bodies"][0]["pose"] = np.array([0, 0, 0.048, 1, 0, 0, 0])
    d["bodies"][1]["field"]["resolution"] = np.int64(40)
    d["model"]["k_C"] = np.float32(2000)
    d["models"] = ("pointshell", "vps")
    scene = contactlab.Scene.from_dict(d, use_cache=False)
    assert scene.name == "ball-on-array-plate" and scene.models == ["pointshell", "vps"]
    assert scene.B.mesh.name == "box:0.1,0.1,0.02"
    # The body's default name is the mesh's, as for a file.
    d = plate_scene_dict(plate)
    del d["bodies"][1]["name"]
    assert contactlab.Scene.from_dict(d).B.name == "plate"


def test_from_dict_errors_name_the_key_path_as_yaml_errors_do(plate):
    d = plate_scene_dict(plate)
    d["bodies"][1]["colour"] = "red"
    with pytest.raises(contactlab.ArgumentError, match=r"^<dict>: bodies\[1\]\.colour: unknown key \(known keys here: "):
        contactlab.Scene.from_dict(d)
    d = plate_scene_dict(plate)
    d["bodies"][1]["field"]["resolutoin"] = 40
    with pytest.raises(ValueError, match=r"^<dict>: bodies\[1\]\.field\.resolutoin: unknown key"):
        contactlab.Scene.from_dict(d)
    d = plate_scene_dict(plate)
    d["scale"] = 2
    with pytest.raises(contactlab.Error, match=r"^<dict>: scale: unknown key"):
        contactlab.Scene.from_dict(d)
    d = plate_scene_dict(plate)
    d["bodies"][0]["pointshell"]["points"] = "many"
    with pytest.raises(contactlab.ArgumentError) as e:
        contactlab.Scene.from_dict(d)
    # The same message as the YAML route, the source "<dict>" for the file and its line.
    with pytest.raises(contactlab.Error) as yaml_error:
        contactlab.Scene.from_yaml("bodies:\n  - {mesh: 'sphere:0.05', role: pointshell, pointshell: {points: many}}\n"
                                   "  - {mesh: 'box:1,1,1', role: field}\n")
    assert str(e.value) == "<dict>: bodies[0].pointshell.points: expected an integer, got 'many'"
    assert str(yaml_error.value).endswith(str(e.value).removeprefix("<dict>"))
    d = plate_scene_dict(plate)
    d["model"]["k_C"] = float("nan")
    with pytest.raises(contactlab.ArgumentError, match=r"^<dict>: model\.k_C: expected a finite number, got 'nan'"):
        contactlab.Scene.from_dict(d)


@pytest.mark.parametrize("mesh", [5, 0.1, None, ["plate.obj"], b"plate.obj", PLATE_VERTICES])
def test_from_dict_refuses_a_mesh_that_is_neither_a_mesh_nor_a_name(mesh):
    with pytest.raises(TypeError, match=r"^<dict>: bodies\[1\]\.mesh: expected a mesh file name, a procedural shape "
                                        r"such as \"sphere:0.05\", or a contactlab.Mesh; got "):
        contactlab.Scene.from_dict(plate_scene_dict(mesh))


def test_from_dict_refuses_values_no_yaml_file_holds(plate):
    d = plate_scene_dict(plate)
    d["bodies"][0]["name"] = plate
    with pytest.raises(TypeError, match=r"^<dict>: bodies\[0\]\.name: a contactlab.Mesh is taken only as a body's mesh"):
        contactlab.Scene.from_dict(d)
    d = plate_scene_dict(plate)
    d["model"][3] = 1
    with pytest.raises(TypeError, match=r"^<dict>: model: keys are names \(str\); got the key 3"):
        contactlab.Scene.from_dict(d)
    d = plate_scene_dict(plate)
    d["bodies"][0]["pose"] = {0, 1}
    with pytest.raises(TypeError, match=r"^<dict>: bodies\[0\]\.pose: expected a dict, list, .*; got set"):
        contactlab.Scene.from_dict(d)
    loop = []
    loop.append(loop)
    d["bodies"][0]["pose"] = loop
    with pytest.raises(contactlab.ArgumentError, match=r"nested more than 32 levels deep"):
        contactlab.Scene.from_dict(d)
    with pytest.raises(TypeError, match=r"^Scene.from_dict: expected a dict .*; got list"):
        contactlab.Scene.from_dict([d])


def test_a_strangers_experiment_on_a_mesh_from_arrays_runs_from_python_and_the_command_line(cli, tmp_path):
    # A mesh made in NumPy, saved by Mesh.save, named by an experiment config the repository does
    # not ship: the run from Python equals the command line's, its tables load in pandas with no
    # renamed column, and make_figures draws it.
    import subprocess
    import sys

    from conftest import SOURCE_DIR

    mesh = contactlab.Mesh(PLATE_VERTICES, PLATE_TRIANGLES, name="my-plate")
    mesh.save(str(tmp_path / "my-plate.obj"))
    again = contactlab.Scene.from_dict(plate_scene_dict(str(tmp_path / "my-plate.obj")), use_cache=False)
    np.testing.assert_array_equal(again.B.mesh.vertices, PLATE_VERTICES)  # OBJ keeps every digit
    np.testing.assert_array_equal(again.B.mesh.triangles, PLATE_TRIANGLES)
    scene = plate_scene_dict("my-plate.obj")
    config = tmp_path / "my-press.yaml"
    config.write_text(
        "name: my-press\n"
        f"scene: {json_flow(scene)}\n"
        "models: [pointshell, fcl]\n"
        "trajectory: {type: approach-press, direction: [0, 0, -1], approach: 0.0, depth: 0.001, duration: 0.05}\n"
        "sweep: {points: [256, 1024]}\n")
    mine = contactlab.load_results(contactlab.run(config, out=tmp_path / "python"))
    cli("run", config, "--out", tmp_path / "cli")
    theirs = contactlab.load_results(tmp_path / "cli")
    for name, frame in mine.tables.items():
        assert len(set(frame.columns)) == len(frame.columns), name
        keep = [c for c in frame.columns if "_us" not in c and "wall" not in c]
        assert frame[keep].equals(theirs[name][keep]), name
    summary = mine.summary
    assert sorted(summary["sweep.points"]) == [256, 256, 1024, 1024]
    pressed = summary[summary["model"] == "pointshell"]["max_force_N"]
    assert (pressed > 0).all()  # the ball is 2 mm into the plate made of arrays, and pressed further
    draw = subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "make_figures.py"), "--results",
                           str(tmp_path / "python")], capture_output=True, text=True, timeout=300)
    assert draw.returncode == 0, draw.stderr
    assert (tmp_path / "python" / "figures" / "my-press.png").stat().st_size > 0


def json_flow(value):
    """VALUE as YAML flow text (JSON is YAML)."""
    import json

    return json.dumps(value)


def test_mesh_save_refuses_an_unknown_extension_and_writes_nothing(tmp_path):
    mesh = contactlab.Mesh(PLATE_VERTICES, PLATE_TRIANGLES, name="my-plate")
    with pytest.raises(contactlab.Error, match="my-plate.xyz"):
        mesh.save(str(tmp_path / "my-plate.xyz"))
    assert list(tmp_path.iterdir()) == []
