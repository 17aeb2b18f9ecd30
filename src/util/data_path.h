// The data search path of DESIGN.md: $CONTACTLAB_DATA, then the project's data/, then
// ../shared/data beside the project. Names may be bare ("dragon.obj") or relative
// ("meshes/dragon.obj"); a bare name is also looked for under meshes/.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace contactlab {

// The folders searched, in order (only those that exist).
std::vector<std::filesystem::path> DataSearchPath();

// Resolves NAME: an existing path as given, else the first hit on the search path.
// Returns nullopt when nothing is found.
std::optional<std::filesystem::path> FindDataFile(std::string_view name);

// As FindDataFile, but throws Error naming NAME and the folders searched.
std::filesystem::path RequireDataFile(std::string_view name);

// The shared mesh folder (../shared/data/meshes or $CONTACTLAB_DATA/meshes), if present;
// tests that need real meshes skip when this is nullopt.
std::optional<std::filesystem::path> SharedMeshDir();

}  // namespace contactlab
