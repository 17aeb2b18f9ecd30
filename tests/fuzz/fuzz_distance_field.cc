// libFuzzer target: distance-field files (sdf/distance_field_io.cc), behind a valid container
// header and checksum unless the input brings its own; an accepted field is then queried inside,
// on and outside its box (trilinear value, gradient, the outside bound, a vectorised batch).
// Built twice: fuzz_distance_field wraps payloads as version 1 (dense samples),
// fuzz_sparse_field (CONTACTLAB_FUZZ_FIELD_VERSION=2) as version 2 (sparse storage).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "sdf/batch_distance.h"
#include "sdf/build_distance_field.h"

#ifndef CONTACTLAB_FUZZ_FIELD_VERSION
#define CONTACTLAB_FUZZ_FIELD_VERSION 1
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = contactlab::fuzz::WriteScratchFile(
      contactlab::fuzz::ContainerBytes(data, size, "CLSDF", CONTACTLAB_FUZZ_FIELD_VERSION), ".sdf");
  contactlab::fuzz::ExpectOnlyError([&] {
    const contactlab::DistanceField field = contactlab::LoadDistanceField(path);
    const contactlab::Aabb box = field.box();
    const Eigen::Vector3d c = 0.5 * (box.min + box.max), e = box.max - box.min;
    for (const Eigen::Vector3d& p : {Eigen::Vector3d(c), Eigen::Vector3d(box.min), Eigen::Vector3d(box.max),
                                     Eigen::Vector3d(c + 0.37 * e), Eigen::Vector3d(c + 2.0 * e)}) {
      Eigen::Vector3d gradient;
      field.Distance(p);
      field.DistanceAndGradient(p, &gradient);
    }
    const float x[5] = {float(c.x()), float(box.min.x()), float(box.max.x()), float(c.x() + 0.37 * e.x()), 1e30f};
    const float y[5] = {float(c.y()), float(box.min.y()), float(box.max.y()), float(c.y() + 0.37 * e.y()), 0.f};
    const float z[5] = {float(c.z()), float(box.min.z()), float(box.max.z()), float(c.z() + 0.37 * e.z()), 0.f};
    float d[5];
    contactlab::BatchDistances(field, contactlab::kIdentityTransform, x, y, z, nullptr, 5, d);
  });
  return 0;
}
