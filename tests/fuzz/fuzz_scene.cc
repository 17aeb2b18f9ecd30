// libFuzzer target: scene YAML (scene/scene.cc through util/config_node.cc): the strict
// reader must refuse anything malformed with an Error, never a yaml-cpp exception or a crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene.h"
#include "fuzz_support.h"
#include "util/config_node.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  contactlab::fuzz::ExpectOnlyError([&] {
    contactlab::ParseScene(contactlab::ConfigNode::LoadString(text, "fuzz.yaml"));
  });
  return 0;
}
