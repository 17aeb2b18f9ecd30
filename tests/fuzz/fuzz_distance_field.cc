// libFuzzer target: distance-field files (sdf/distance_field_io.cc), behind a valid container
// header and checksum unless the input brings its own; an accepted field is then queried inside,
// on and outside its box (trilinear value, gradient, the outside bound).
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "sdf/build_distance_field.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = contactlab::fuzz::WriteScratchFile(
      contactlab::fuzz::ContainerBytes(data, size, "CLSDF", 1), ".sdf");
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
  });
  return 0;
}
