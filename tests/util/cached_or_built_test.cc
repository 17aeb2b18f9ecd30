// The cache serves speed only: a cache folder that cannot take an entry never fails the command.
#include "util/cached_or_built.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "test_support.h"
#include "util/atomic_file.h"

namespace contactlab {
namespace {

int BuildCount(const std::filesystem::path& cached, int* builds) {
  const auto value = CachedOrBuilt<int>(
      cached, false, "a number", [](const std::filesystem::path& f) { return std::stoi(ReadWholeFile(f)); },
      [](int v, const std::filesystem::path& f) { WriteFileAtomically(f, std::to_string(v)); },
      [builds] { ++*builds; return 42; });
  return *value;
}

TEST(CachedOrBuilt, BuiltOnceThenReadFromTheCache) {
  testing::TempDir dir;
  int builds = 0;
  EXPECT_EQ(BuildCount(dir / "cache" / "entry", &builds), 42);
  EXPECT_EQ(BuildCount(dir / "cache" / "entry", &builds), 42);
  EXPECT_EQ(builds, 1);
  EXPECT_EQ(ReadWholeFile(dir / "cache" / "entry"), "42");
}

// A cache "folder" that is a file, or an entry that is a folder, cannot take the entry (as a
// read-only or full cache cannot, which root's tests cannot make): the value is built and
// returned, with a warning, instead of failing the command that asked for it.
TEST(CachedOrBuilt, ACacheThatCannotTakeTheEntryIsPassedOverNotAFailure) {
  testing::TempDir dir;
  std::ofstream(dir / "file") << "not a folder";
  std::filesystem::create_directories(dir / "folder-entry");
  for (const std::filesystem::path& cached : {dir / "file" / "entry", dir / "folder-entry"}) {
    SCOPED_TRACE(cached.string());
    int builds = 0;
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(BuildCount(cached, &builds), 42);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(builds, 1);
    EXPECT_NE(err.find("not cached"), std::string::npos) << err;
  }
  EXPECT_EQ(ReadWholeFile(dir / "file"), "not a folder");
}

}  // namespace
}  // namespace contactlab
