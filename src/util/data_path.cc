#include "util/data_path.h"

#include <cstdlib>
#include <string>

#include "util/error.h"

namespace contactlab {
namespace fs = std::filesystem;

std::vector<fs::path> DataSearchPath() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("CONTACTLAB_DATA"); env != nullptr && *env != '\0') {
    candidates.emplace_back(env);
  }
  const fs::path source_dir(CONTACTLAB_SOURCE_DIR);
  candidates.push_back(fs::current_path() / "data");
  candidates.push_back(source_dir / "data");
  candidates.push_back(fs::current_path() / ".." / "shared" / "data");
  candidates.push_back(source_dir / ".." / "shared" / "data");
  std::vector<fs::path> existing;
  for (const fs::path& c : candidates) {
    std::error_code ec;
    if (!fs::is_directory(c, ec)) continue;
    const fs::path canonical = fs::weakly_canonical(c, ec);
    bool seen = false;
    for (const fs::path& e : existing) seen = seen || (e == canonical);
    if (!seen) existing.push_back(canonical);
  }
  return existing;
}

std::optional<fs::path> FindDataFile(std::string_view name) {
  std::error_code ec;
  const fs::path given(name);
  if (fs::is_regular_file(given, ec)) return given;
  for (const fs::path& dir : DataSearchPath()) {
    for (const fs::path& candidate : {dir / given, dir / "meshes" / given}) {
      if (fs::is_regular_file(candidate, ec)) return candidate;
    }
  }
  return std::nullopt;
}

fs::path RequireDataFile(std::string_view name) {
  if (auto found = FindDataFile(name)) return *found;
  std::string searched;
  for (const fs::path& dir : DataSearchPath()) {
    if (!searched.empty()) searched += ", ";
    searched += dir.string();
  }
  if (searched.empty()) searched = "(no data folder exists)";
  Fail(name, "file not found as given nor on the data search path: " + searched);
}

std::optional<fs::path> SharedMeshDir() {
  std::error_code ec;
  for (const fs::path& dir : DataSearchPath()) {
    const fs::path meshes = dir / "meshes";
    if (fs::is_regular_file(meshes / "dragon.obj", ec)) return meshes;
  }
  return std::nullopt;
}

}  // namespace contactlab
