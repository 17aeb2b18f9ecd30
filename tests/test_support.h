// Shared helpers for the test suites.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>

#include "util/data_path.h"

namespace contactlab::testing {

// Path of a shared mesh, or nullopt (the caller skips) when ../shared/data is absent.
inline std::optional<std::filesystem::path> SharedMesh(const std::string& name) {
  auto dir = SharedMeshDir();
  if (!dir) return std::nullopt;
  return *dir / name;
}

// A fresh temporary folder under the system temp dir, removed at destruction.
class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("contactlab-test-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "-" +
             std::to_string(reinterpret_cast<std::uintptr_t>(this)) + "-" + std::to_string(counter_++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
  static inline int counter_ = 0;
};

}  // namespace contactlab::testing

// Skips the current test with a stated reason when a shared mesh is absent.
#define CONTACTLAB_REQUIRE_SHARED_MESH(var, name)                                          \
  const auto var##_opt = ::contactlab::testing::SharedMesh(name);                          \
  if (!var##_opt) GTEST_SKIP() << "../shared/data/meshes is absent; " name " is needed";   \
  const std::filesystem::path var = *var##_opt
