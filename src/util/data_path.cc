// Data search path: the naming file's folder, $CONTACTLAB_DATA, the data folder installed
// beside the running program (found through /proc/self/exe), and ../shared/data.
#include "util/data_path.h"

#include <cstdlib>
#include <string>

#include "util/atomic_file.h"
#include "util/error.h"

#ifndef CONTACTLAB_DATA_FROM_BINDIR
#define CONTACTLAB_DATA_FROM_BINDIR "../share/contactlab"
#endif

namespace contactlab {
namespace fs = std::filesystem;

namespace {

bool IsFolder(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

bool IsFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

// SetInstalledRoot's folder, canonical (empty: none).
fs::path& HostInstalledRoot() {
  static fs::path root;
  return root;
}

// share/contactlab beside the running program (the build tree mirrors it), or the one a host
// program named (SetInstalledRoot), canonical.
std::optional<fs::path> InstalledRoot() {
  if (!HostInstalledRoot().empty()) return HostInstalledRoot();
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec || exe.empty()) return std::nullopt;
  const fs::path root = exe.parent_path() / CONTACTLAB_DATA_FROM_BINDIR;
  if (!IsFolder(root / "data")) return std::nullopt;
  return fs::weakly_canonical(root, ec);
}

// PATH when it is a file, else PATH.gz when that is.
std::optional<fs::path> FileOrGzip(const fs::path& path) {
  if (IsFile(path)) return path;
  fs::path gz = path;
  gz += ".gz";
  if (IsFile(gz)) return gz;
  return std::nullopt;
}

// NAME in data folder DIR: DIR/NAME, then DIR/meshes/NAME (each also as .gz).
std::optional<fs::path> FindIn(const fs::path& dir, const fs::path& name) {
  if (auto hit = FileOrGzip(dir / name)) return hit;
  return FileOrGzip(dir / "meshes" / name);
}

}  // namespace

void SetInstalledRoot(const fs::path& root) {
  std::error_code ec;
  if (IsFolder(root / "data")) HostInstalledRoot() = fs::weakly_canonical(root, ec);
}

std::optional<fs::path> InstalledDataDir() {
  if (auto root = InstalledRoot()) return *root / "data";
  return std::nullopt;
}

std::vector<fs::path> DataSearchPath() {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("CONTACTLAB_DATA"); env != nullptr && *env != '\0') {
    candidates.emplace_back(env);
  }
  const std::optional<fs::path> root = InstalledRoot();
  if (root) {
    candidates.push_back(*root / "data");
    candidates.push_back(*root);
  }
  std::error_code ec;
  candidates.push_back(fs::current_path(ec) / ".." / "shared" / "data");
  if (root) {
    // Beside the repository: in a build tree, data/ links to the checkout's data/.
    const fs::path data = fs::weakly_canonical(*root / "data", ec);
    candidates.push_back(data.parent_path().parent_path() / "shared" / "data");
  }
  std::vector<fs::path> existing;
  for (const fs::path& c : candidates) {
    if (!IsFolder(c)) continue;
    const fs::path canonical = fs::weakly_canonical(c, ec);
    bool seen = false;
    for (const fs::path& e : existing) seen = seen || (e == canonical);
    if (!seen) existing.push_back(canonical);
  }
  return existing;
}

fs::path FolderOf(const fs::path& file) {
  const fs::path parent = file.parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

std::optional<fs::path> FindDataFile(std::string_view name, const fs::path& base_dir) {
  const fs::path given(name);
  if (given.empty()) return std::nullopt;
  if (given.is_absolute()) return FileOrGzip(given);
  if (!base_dir.empty()) {
    if (auto hit = FileOrGzip(base_dir / given)) return hit;
  }
  if (auto hit = FileOrGzip(given)) return hit;
  for (const fs::path& dir : DataSearchPath()) {
    if (auto hit = FindIn(dir, given)) return hit;
  }
  return std::nullopt;
}

fs::path RequireDataFile(std::string_view name, const fs::path& base_dir) {
  if (auto found = FindDataFile(name, base_dir)) return *found;
  // Something that exists but is not a file is named for what it is, not "not found".
  for (const fs::path& p : {base_dir.empty() ? fs::path(name) : base_dir / fs::path(name), fs::path(name)}) {
    const std::string kind = NonRegularFileKind(p);
    if (!kind.empty()) Fail(p.string(), "is " + kind + ", not a file");
  }
  std::string searched = base_dir.empty() ? std::string("the working folder") : base_dir.string() + ", the working folder";
  for (const fs::path& dir : DataSearchPath()) searched += ", " + dir.string();
  if (!InstalledRoot()) searched += " (no installed data folder beside the program; set CONTACTLAB_DATA)";
  Fail(name, "file not found as given nor on the data search path: " + searched);
}

}  // namespace contactlab
