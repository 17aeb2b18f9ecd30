// libFuzzer target: experiment configs (experiment/experiment_config.cc through
// util/config_node.cc): the reader, the sweep's bounds and expansion, and every study's checks of
// every job must refuse anything malformed with an Error, never a yaml-cpp exception, a
// std::bad_alloc or a crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "experiment/experiment_config.h"
#include "fuzz_support.h"
#include "util/config_node.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  contactlab::fuzz::ExpectOnlyError([&] {
    const contactlab::ExperimentConfig config =
        contactlab::ParseExperimentConfig(contactlab::ConfigNode::LoadString(text, "fuzz.yaml"), text, text);
    // What --list-jobs prints, from the config alone.
    for (std::size_t j = 0, n = contactlab::JobCount(config); j < n; ++j) (void)contactlab::JobLabel(config, j);
  });
  return 0;
}
