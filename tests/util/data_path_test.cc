#include "util/data_path.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

TEST(DataPath, EnvironmentFolderIsSearchedFirst) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "only-here.obj") << "v 0 0 0\n";
  ::setenv("CONTACTLAB_DATA", dir.path().c_str(), 1);
  const auto found = FindDataFile("only-here.obj");
  ::unsetenv("CONTACTLAB_DATA");
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(std::filesystem::weakly_canonical(*found),
            std::filesystem::weakly_canonical(dir / "meshes" / "only-here.obj"));
}

TEST(DataPath, MissingFileErrorNamesTheFile) {
  try {
    RequireDataFile("no-such-mesh-4711.obj");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-mesh-4711.obj"), std::string::npos);
  }
}

TEST(DataPath, SharedMeshesAreFoundWhenPresent) {
  if (!SharedMeshDir()) GTEST_SKIP() << "../shared/data/meshes is absent";
  EXPECT_TRUE(FindDataFile("dragon.obj").has_value());
  EXPECT_TRUE(FindDataFile("meshes/knight.off").has_value());
}

}  // namespace
}  // namespace contactlab
