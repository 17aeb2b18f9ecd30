// The data search path (util/data_path.h): order of the folders, the .gz fallback, the naming
// file's folder first, and errors that list every folder searched.
#include "util/data_path.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdlib>
#include <fstream>

#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

namespace fs = std::filesystem;

// Sets $CONTACTLAB_DATA for one scope.
class ScopedDataEnv {
 public:
  explicit ScopedDataEnv(const fs::path& dir) { ::setenv("CONTACTLAB_DATA", dir.c_str(), 1); }
  ~ScopedDataEnv() { ::unsetenv("CONTACTLAB_DATA"); }
};

fs::path Canonical(const fs::path& p) { return fs::weakly_canonical(p); }

TEST(DataPath, EnvironmentFolderIsSearchedForBareNamesUnderMeshes) {
  testing::TempDir dir;
  fs::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "only-here.obj") << "v 0 0 0\n";
  ScopedDataEnv env(dir.path());
  const auto found = FindDataFile("only-here.obj");
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(Canonical(*found), Canonical(dir / "meshes" / "only-here.obj"));
}

TEST(DataPath, NamingFileFolderComesBeforeTheEnvironment) {
  testing::TempDir scene_dir, env_dir;
  std::ofstream(scene_dir / "part.obj") << "v 0 0 0\n";
  fs::create_directories(env_dir / "meshes");
  std::ofstream(env_dir / "meshes" / "part.obj") << "v 1 1 1\n";
  ScopedDataEnv env(env_dir.path());
  const auto beside = FindDataFile("part.obj", FolderOf(scene_dir / "scene.yaml"));
  ASSERT_TRUE(beside.has_value());
  EXPECT_EQ(Canonical(*beside), Canonical(scene_dir / "part.obj"));
  const auto without_base = FindDataFile("part.obj");
  ASSERT_TRUE(without_base.has_value());
  EXPECT_EQ(Canonical(*without_base), Canonical(env_dir / "meshes" / "part.obj"));
}

TEST(DataPath, NameWithoutGzFindsTheCompressedFile) {
  testing::TempDir dir;
  std::ofstream(dir / "packed.obj.gz") << "x";
  const auto found = FindDataFile("packed.obj", dir.path());
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->filename(), "packed.obj.gz");
  // An absolute name also falls back to its .gz.
  const auto absolute = FindDataFile((fs::absolute(dir.path()) / "packed.obj").string());
  ASSERT_TRUE(absolute.has_value());
  EXPECT_EQ(absolute->filename(), "packed.obj.gz");
  EXPECT_EQ(FolderOf("bare.yaml"), fs::path("."));
}

TEST(DataPath, MissingFileErrorNamesTheFileAndTheFoldersSearched) {
  testing::TempDir base;
  try {
    RequireDataFile("no-such-mesh-4711.obj", base.path());
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no-such-mesh-4711.obj"), std::string::npos) << m;
    EXPECT_NE(m.find(base.path().string()), std::string::npos) << m;
    EXPECT_NE(m.find(Canonical(InstalledDataDir().value_or("?")).string()), std::string::npos) << m;
  }
}

TEST(DataPath, NamedPipeOrFolderIsNamedForWhatItIsNotAsMissing) {
  testing::TempDir base;
  ASSERT_EQ(::mkfifo((base / "pipe.sdf").c_str(), 0600), 0);
  fs::create_directory(base / "folder.yaml");
  for (const char* name : {"pipe.sdf", "folder.yaml"}) {
    try {
      RequireDataFile(name, base.path());
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(name), std::string::npos) << m;
      EXPECT_EQ(m.find("not found"), std::string::npos) << m;
      EXPECT_NE(m.find(name[0] == 'p' ? "is a named pipe, not a file" : "is a folder, not a file"), std::string::npos) << m;
    }
  }
}

// The repository's data/ is found beside the program (build/share/contactlab/data), with
// every mesh, scene and experiment of the default suite, and no part of the path comes from
// $CONTACTLAB_DATA or ../shared.
TEST(DataPath, RepositoryDataIsFoundBesideTheProgram) {
  const auto data = InstalledDataDir();
  ASSERT_TRUE(data.has_value()) << "no share/contactlab/data beside the test program";
  EXPECT_TRUE(fs::is_regular_file(*data / "meshes" / "SOURCES.md"));
  for (const char* name : {"dragon.obj", "bunny-watertight.obj", "knight.off", "screwdriver.off", "block.obj",
                           "joint.obj", "bumpy-cube.obj"}) {
    const auto found = FindDataFile(name);
    ASSERT_TRUE(found.has_value()) << name;
    EXPECT_EQ(Canonical(found->parent_path()), Canonical(*data / "meshes")) << name;
  }
  EXPECT_TRUE(FindDataFile("scenes/dragon-bunny.yaml").has_value());
  EXPECT_TRUE(FindDataFile("trajectories/sim-session-circle.csv").has_value());
  EXPECT_TRUE(FindDataFile("experiments/fig05b-convergence.yaml").has_value());
  EXPECT_TRUE(FindDataFile("meshes/knight.off").has_value());
}

}  // namespace
}  // namespace contactlab
