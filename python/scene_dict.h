// Scene.from_dict: a scene given as Python dicts, lists and scalars in the structure of a scene
// YAML file (scene/scene.h), a body's mesh optionally a contactlab.Mesh held in memory.
#pragma once

#include <pybind11/pybind11.h>

#include "scene/scene.h"

namespace contactlab::python {

// The scene D describes, parsed as a scene file is (every key known, every value checked), its
// errors naming the key path under the source "<dict>" ("<dict>: bodies[1].field.resolution:
// ..."). A body's mesh may be a file name, a procedural shape or a contactlab.Mesh, which the
// body then takes as its mesh (BodySpec::mesh_data). Values: dicts (string keys), lists, tuples,
// NumPy arrays, str, bool, int, float, NumPy scalars and None. Raises ArgumentError for what the
// scene parser refuses, TypeError naming the key path for a value of another type, a
// contactlab.Mesh anywhere but a body's mesh, or a D that is no mapping.
Scene SceneFromDict(pybind11::handle d);

}  // namespace contactlab::python
