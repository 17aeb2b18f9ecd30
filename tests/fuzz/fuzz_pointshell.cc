// libFuzzer target: pointshell files (pointshell/pointshell_io.cc: container, then the structural
// validation of every loaded tree), behind a valid header and checksum unless the input brings
// its own.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.h"
#include "pointshell/pointshell_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = contactlab::fuzz::WriteScratchFile(
      contactlab::fuzz::ContainerBytes(data, size, "CLPS", 1), ".ps");
  contactlab::fuzz::ExpectOnlyError([&] { contactlab::LoadPointshell(path); });
  return 0;
}
