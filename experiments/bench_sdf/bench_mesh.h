// The mesh of the distance-field build benchmarks: dragon.obj (100k triangles), or in quick
// mode (CONTACTLAB_BENCH_QUICK=1) a small procedural sphere.
#pragma once

#include <iostream>

#include "bench_common.h"
#include "geometry/mesh_io.h"
#include "geometry/procedural_shapes.h"
#include "util/data_path.h"

namespace contactlab::bench {

inline const TriangleMesh& BenchMesh() {
  static const TriangleMesh mesh = [] {
    if (QuickRun()) return MakeSphere(0.1, 3);
    const auto path = FindDataFile("dragon.obj");
    if (!path) {
      std::cerr << "dragon.obj not found on the data search path; using a procedural sphere\n";
      return MakeSphere(0.1, 7);
    }
    return LoadMesh(*path);
  }();
  return mesh;
}

}  // namespace contactlab::bench
