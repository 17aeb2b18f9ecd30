// libFuzzer target: reduced-model files (deform/reduced_model.cc), behind a valid header and
// checksum unless the input brings its own; an accepted model is described and its reduced
// forces evaluated at a small deformation.
#include <cstddef>
#include <cstdint>

#include "deform/reduced_model.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = contactlab::fuzz::WriteScratchFile(
      contactlab::fuzz::ContainerBytes(data, size, "CLRM", 1), ".rm");
  contactlab::fuzz::ExpectOnlyError([&] {
    const contactlab::ReducedModel model = contactlab::LoadReducedModel(path);
    contactlab::DescribeReducedModel(model);
    auto workspace = model.forces.MakeWorkspace();
    const contactlab::ReducedVector q = contactlab::ReducedVector::Constant(model.r(), 1e-3);
    contactlab::ReducedVector f(model.r());
    contactlab::ReducedMatrix K(model.r(), model.r());
    model.forces.Evaluate(q, &f, &K, &workspace);
  });
  return 0;
}
