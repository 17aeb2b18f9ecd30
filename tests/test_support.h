// Shared helpers for the test suites.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "util/data_path.h"
#include "util/error.h"

namespace contactlab::testing {

// The message of the Error F throws, or "(no error)" when it throws none.
inline std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Path of a mesh the repository ships in data/meshes (SOURCES.md), found as the program
// finds it: in the data folder beside the test executable (build/share/contactlab/data is the
// checkout's data/). Throws Error, failing the test, when it is absent: tests never skip for data.
inline std::filesystem::path TestMesh(const std::string& name) {
  const auto data = InstalledDataDir();
  if (!data) {
    throw Error("test data: no data folder beside the test program (expected <build>/share/contactlab/data, "
                "made by CMake's configure step); " + name + " is needed");
  }
  for (const std::string& file : {name + ".gz", name}) {
    if (std::filesystem::is_regular_file(*data / "meshes" / file)) return *data / "meshes" / file;
  }
  throw Error((*data / "meshes" / name).string() + "(.gz): test mesh absent from the repository's data/meshes");
}

// A fresh temporary folder under the system temp dir, removed at destruction.
class TempDir {
 public:
  // mkdtemp makes the name unique across processes: tests run in parallel, and a name made from
  // the seed and an address collides under ASan (same millisecond seed, same heap address).
  TempDir() {
    std::string name = (std::filesystem::temp_directory_path() / "contactlab-test-XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) throw Error(name + ": cannot create a temporary folder");
    path_ = name;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// What a shell command printed (stdout and stderr together) and its exit code (-1 when it
// did not exit normally).
struct CommandOutcome {
  int exit_code = -1;
  std::string output;
};

// Runs COMMAND through the shell with stderr joined to stdout.
inline CommandOutcome RunShellCommand(const std::string& command) {
  CommandOutcome o;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return o;
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), int(buf.size()), pipe)) o.output += buf.data();
  const int status = ::pclose(pipe);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

}  // namespace contactlab::testing
