// libFuzzer target: the PLY mesh reader (geometry/ply_reader.cc) on arbitrary bytes, then the
// validation report of whatever mesh it accepts.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_support.h"
#include "geometry/mesh_readers.h"
#include "geometry/mesh_validation.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  contactlab::fuzz::ExpectOnlyError([&] {
    const contactlab::TriangleMesh mesh = contactlab::internal::ReadPly(bytes, "fuzz.ply");
    contactlab::ValidateMesh(mesh);
  });
  return 0;
}
