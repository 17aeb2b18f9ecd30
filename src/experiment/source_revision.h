// The source revision recorded in meta.json: which ContactLab commit produced a result.
#pragma once

#include <filesystem>
#include <string>

namespace contactlab {

// The git commit of the checkout holding CONFIG_FILE (with " (with uncommitted changes)" when
// its tracked files differ from the commit), found by running git in the config's folder;
// "unknown" when that folder is not in a git work tree or git is absent.
std::string ConfigRevision(const std::filesystem::path& config_file);

// The commit the running binary was built from (recorded at build time; same suffix), or
// "unknown" when the build was not made from a git checkout.
std::string BuildRevision();

}  // namespace contactlab
