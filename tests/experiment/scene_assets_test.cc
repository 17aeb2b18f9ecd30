#include "scene/scene_assets.h"
#include "util/atomic_file.h"
#include "util/cache_record.h"

#include <gtest/gtest.h>

#include <fstream>

#include "scene/scene.h"
#include "geometry/mesh_io.h"
#include "geometry/procedural_shapes.h"
#include "pointshell/pointshell_io.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

BodySpec Ball(int points, std::uint64_t seed = 1) {
  BodySpec b;
  b.name = "ball";
  b.mesh = "sphere:0.02,3";
  b.role = "pointshell";
  b.field.resolution = 24;
  b.pointshell.points = points;
  b.pointshell.levels = 2;
  b.pointshell.seed = seed;
  return b;
}

// Cache entries whose name starts with PREFIX (not their records, util/cache_record.h).
int CountFiles(const std::filesystem::path& dir, const std::string& prefix) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    n += name.rfind(prefix, 0) == 0 && e.path().extension() != ".key";
  }
  return n;
}

TEST(SceneAssets, ASecondRunReadsFieldsAndPointshellsFromTheCache) {
  testing::TempDir dir;
  AssetOptions options{.cache_dir = dir / "cache", .use_cache = true, .verbose = false};
  BodyAssets first(Ball(256), options);
  const auto shell = first.pointshell();
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 1);
  EXPECT_EQ(CountFiles(dir / "cache", "pointshell-"), 1);
  // A second run reads both from the cache (it says so), with the same points.
  AssetOptions verbose = options;
  verbose.verbose = true;
  ::testing::internal::CaptureStderr();
  BodyAssets second(Ball(256), verbose);
  EXPECT_EQ(second.pointshell()->x, shell->x);
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("reusing the 256-point pointshell of ball"), std::string::npos) << said;
  EXPECT_NE(said.find("reusing the"), said.rfind("reusing the")) << said;  // the field too
  EXPECT_EQ(said.find("building"), std::string::npos) << said;
  // Another size is another key.
  BodyAssets bigger(Ball(512), options);
  bigger.pointshell();
  EXPECT_EQ(CountFiles(dir / "cache", "pointshell-"), 2);
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 1);  // same mesh, same field
}

// A valid pointshell of another seed saved under this entry's name was read as this entry's: the
// cache entries did not record their key. Each entry now has a record of its name, size and
// hash (util/cache_record.h): the foreign file is reported and this body's pointshell rebuilt,
// and so is an entry whose record is missing.
TEST(SceneAssets, AValidEntryOfAnotherKeyUnderThisEntrysNameIsNotUsed) {
  testing::TempDir dir;
  AssetOptions options{.cache_dir = dir / "cache", .use_cache = true, .verbose = false};
  BodyAssets first(Ball(256), options);
  const auto shell = first.pointshell();
  BodyAssets other(Ball(256, 7), AssetOptions{.cache_dir = dir / "other", .use_cache = true, .verbose = false});
  ASSERT_NE(other.pointshell()->x, shell->x);
  std::filesystem::path cached;
  for (const auto& e : std::filesystem::directory_iterator(dir / "cache")) {
    const std::string name = e.path().filename().string();
    if (name.rfind("pointshell-", 0) == 0 && name.find(".key") == std::string::npos) cached = e.path();
  }
  ASSERT_FALSE(cached.empty());
  EXPECT_TRUE(std::filesystem::exists(CacheRecordPath(cached)));
  SavePointshell(*other.pointshell(), cached);
  ::testing::internal::CaptureStderr();
  BodyAssets second(Ball(256), options);
  EXPECT_EQ(second.pointshell()->x, shell->x);
  std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("differ from its record"), std::string::npos) << said;
  // Rebuilt and saved with a new record: read back from the cache the next time.
  EXPECT_EQ(CacheRecordMismatch(cached), "");
  std::filesystem::remove(CacheRecordPath(cached));
  ::testing::internal::CaptureStderr();
  BodyAssets third(Ball(256), options);
  EXPECT_EQ(third.pointshell()->x, shell->x);
  said = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("no record of its key"), std::string::npos) << said;
}

// A unit cube of side 2 cm, its top face (two triangles) left out when HOLED.
std::filesystem::path WriteCube(const std::filesystem::path& file, bool holed) {
  std::ofstream out(file);
  out << "v 0 0 0\nv 0.02 0 0\nv 0.02 0.02 0\nv 0 0.02 0\nv 0 0 0.02\nv 0.02 0 0.02\nv 0.02 0.02 0.02\nv 0 0.02 0.02\n"
         "f 1 3 2\nf 1 4 3\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
  if (!holed) out << "f 5 6 7\nf 5 7 8\n";
  return file;
}

// A mesh with holes in field.mode auto takes the polygon-soup pipeline: said on stderr, naming
// the body and the mesh, every time the field is used (cached or built). A closed mesh, or a
// soup asked for by field.mode: soup, says nothing.
TEST(SceneAssets, AMeshWithHolesInModeAutoIsReportedAsASoup) {
  testing::TempDir dir;
  AssetOptions options{.cache_dir = dir / "cache", .use_cache = true, .verbose = false};
  auto stderr_of = [&](const std::filesystem::path& mesh, const std::string& mode) {
    BodySpec b;
    b.name = "lid-less";
    b.mesh = mesh.string();
    b.role = "field";
    b.field.resolution = 16;
    b.field.mode = mode;
    ::testing::internal::CaptureStderr();
    BodyAssets assets(b, options);
    const auto field = assets.field();
    return std::pair(::testing::internal::GetCapturedStderr(), field->info().mode);
  };
  const auto holed = WriteCube(dir / "holed.obj", true);
  for (int pass = 0; pass < 2; ++pass) {  // built, then read from the cache
    const auto [text, mode] = stderr_of(holed, "auto");
    EXPECT_EQ(mode, "soup");
    EXPECT_NE(text.find("warning: body 'lid-less'"), std::string::npos) << text;
    EXPECT_NE(text.find("holed.obj"), std::string::npos) << text;
    EXPECT_NE(text.find("not watertight"), std::string::npos) << text;
  }
  const auto [chosen, chosen_mode] = stderr_of(holed, "soup");
  EXPECT_EQ(chosen_mode, "soup");
  EXPECT_EQ(chosen.find("warning"), std::string::npos) << chosen;
  const auto [closed, closed_mode] = stderr_of(WriteCube(dir / "closed.obj", false), "auto");
  EXPECT_EQ(closed_mode, "closed");
  EXPECT_EQ(closed.find("warning"), std::string::npos) << closed;
}

TEST(SceneAssets, ASparseFieldIsBuiltCachedUnderItsOwnKeyAndReadBackSparse) {
  testing::TempDir dir;
  AssetOptions options{.cache_dir = dir / "cache", .use_cache = true, .verbose = false};
  BodySpec dense = Ball(256);
  dense.role = "field";
  BodySpec sparse = dense;
  sparse.field.resolution = 64;
  sparse.field.storage = "sparse";
  BodyAssets a(sparse, options);
  ASSERT_NE(a.field()->sparse(), nullptr);
  EXPECT_EQ(a.field()->dims().maxCoeff(), 65);
  BodyAssets b(sparse, options);  // from the cache
  ASSERT_NE(b.field()->sparse(), nullptr);
  EXPECT_EQ(b.field()->memory_bytes(), a.field()->memory_bytes());
  // The dense field of the same resolution is another file; another band another again.
  dense.field.resolution = 64;
  BodyAssets c(dense, options);
  EXPECT_EQ(c.field()->sparse(), nullptr);
  sparse.field.band = 2;
  BodyAssets d(sparse, options);
  d.field();
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 3);
}

TEST(SceneAssets, ANewBuilderVersionRebuildsWhatDependsOnIt) {
  testing::TempDir dir;
  AssetOptions options;
  options.cache_dir = dir / "cache";
  options.verbose = false;
  BodyAssets(Ball(128), options).pointshell();
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 1);
  EXPECT_EQ(CountFiles(dir / "cache", "pointshell-"), 1);
  // A new field builder: its field and the pointshell built from it are new entries.
  AssetOptions new_field = options;
  new_field.builders.field = 2;
  BodyAssets(Ball(128), new_field).pointshell();
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 2);
  EXPECT_EQ(CountFiles(dir / "cache", "pointshell-"), 2);
  // A new pointshell builder: the field is found, the pointshell is built again.
  AssetOptions new_shell = options;
  new_shell.builders.pointshell = 2;
  BodyAssets(Ball(128), new_shell).pointshell();
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 2);
  EXPECT_EQ(CountFiles(dir / "cache", "pointshell-"), 3);
  // The versions of today's builders find what they cached.
  BodyAssets(Ball(128), options).pointshell();
  EXPECT_EQ(CountFiles(dir / "cache", "pointshell-"), 3);
}

TEST(SceneAssets, ACorruptCacheEntryIsRebuilt) {
  testing::TempDir dir;
  AssetOptions options{.cache_dir = dir / "cache", .use_cache = true, .verbose = false};
  BodyAssets first(Ball(128), options);
  const auto expected = first.field();
  for (const auto& e : std::filesystem::directory_iterator(dir / "cache")) {
    std::filesystem::resize_file(e.path(), 40);  // truncate every entry
  }
  BodyAssets second(Ball(128), options);
  EXPECT_EQ(second.field()->values(), expected->values());
}

// A body whose mesh is held in memory (BodySpec::mesh_data): the plate of sphere-on-plate.
BodySpec InMemoryPlate(std::shared_ptr<const TriangleMesh> mesh) {
  BodySpec b;
  b.name = "plate";
  b.mesh = mesh->name;
  b.mesh_data = std::move(mesh);
  b.role = "field";
  b.field.resolution = 16;
  return b;
}

TEST(SceneAssets, AnInMemoryMeshIsCachedByContentAsTheSameMeshFromAFileIs) {
  testing::TempDir dir;
  AssetOptions options;
  options.cache_dir = dir / "cache";
  options.verbose = false;
  const TriangleMesh box = MakeBox(Eigen::Vector3d(0.1, 0.1, 1.0 / 30), 2);
  SaveMesh(box, dir / "plate.obj");
  BodySpec from_file = InMemoryPlate(std::make_shared<const TriangleMesh>(box));
  from_file.mesh_data = nullptr;
  from_file.mesh = (dir / "plate.obj").string();
  BodyAssets file_body(from_file, options);
  (void)file_body.field();
  ASSERT_EQ(CountFiles(dir / "cache", "field-"), 1);

  // Equal content under another name: the same key, the file's cache entry read, nothing built.
  TriangleMesh copy = box;
  copy.name = "another name";
  BodyAssets memory_body(InMemoryPlate(std::make_shared<const TriangleMesh>(copy)), options);
  EXPECT_EQ(memory_body.mesh_key(), file_body.mesh_key());
  EXPECT_EQ(memory_body.field()->values(), file_body.field()->values());
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 1);

  // One vertex moved: another key, another entry.
  copy.vertices[0].x() += 1e-9;
  BodyAssets moved(InMemoryPlate(std::make_shared<const TriangleMesh>(copy)), options);
  EXPECT_NE(moved.mesh_key(), file_body.mesh_key());
  (void)moved.field();
  EXPECT_EQ(CountFiles(dir / "cache", "field-"), 2);
}

TEST(SceneAssets, AnInMemoryMeshIsScaledAndCentredAsAFileIs) {
  testing::TempDir dir;
  TriangleMesh box = MakeBox(Eigen::Vector3d(1, 2, 3), 2);
  box.Transform(1.0, Eigen::Matrix3d::Identity(), Eigen::Vector3d(1.0 / 3, 0, 0));
  SaveMesh(box, dir / "box.obj");
  BodySpec b = InMemoryPlate(std::make_shared<const TriangleMesh>(box));
  b.scale = 0.01;
  b.center = true;
  const TriangleMesh memory = LoadBodyMesh(b);
  b.mesh_data = nullptr;
  b.mesh = (dir / "box.obj").string();
  const TriangleMesh file = LoadBodyMesh(b);
  EXPECT_EQ(memory.vertices, file.vertices);
  EXPECT_NEAR(memory.Bounds().size().z(), 0.06, 1e-12);
  EXPECT_NEAR(memory.Bounds().center().norm(), 0, 1e-12);
  // A mesh no reader would return is refused where it is used, naming the body's mesh.
  TriangleMesh bad = box;
  bad.triangles[3][1] = -2;
  b.mesh_data = std::make_shared<const TriangleMesh>(bad);
  b.mesh_where = "<dict>: bodies[1].mesh";
  EXPECT_EQ(testing::ErrorOf([&] { LoadBodyMesh(b); }),
            "<dict>: bodies[1].mesh: mesh 'box': triangle 3: face vertex index -2 out of range [0, " +
                std::to_string(box.num_vertices()) + ")");
}

// box:...,2.9 was built with 2 cuts, box:...,20000 hung building 9.6e9 triangles, and tube:...,1e8
// and a bumpy plate of resolution 1e5 ran out of memory: every count of a shape must be a whole
// number within its bound, refused naming the body and the count before anything is built.
TEST(SceneAssets, AProceduralShapesCountsAreWholeNumbersWithinTheirBounds) {
  BodySpec b = Ball(64);
  b.mesh_where = "s.yaml:3: bodies[0].mesh";
  const std::pair<const char*, const char*> refused[] = {
      {"box:0.01,0.01,0.01,2.9", "its cuts per edge (12 n^2 triangles) must be a whole number in [1, 512], got 2.9"},
      {"box:0.01,0.01,0.01,20000", "got 20000"},
      {"box:0.01,0.01,0.01,0", "got 0"},
      {"sphere:0.01,10", "its subdivisions (20 * 4^n triangles) must be a whole number in [0, 9], got 10"},
      {"tube:0.006,0.005,0.01,1e8", "its segments around (8 n triangles) must be a whole number in [3, 524288]"},
      {"bumpy-plate:0.1,0.01,4,0.001,100000", "its resolution (quads per side) must be a whole number in [2, 1024]"},
      {"bumpy-plate:0.1,0.01,200,0.001,128", "its bumps per side (at most the resolution) must be a whole number in [0, 128]"},
      {"bumpy-plate:0.1,0.01,2.5,0.001", "got 2.5"},
  };
  for (const auto& [spec, message] : refused) {
    b.mesh = spec;
    const std::string e = testing::ErrorOf([&] { LoadBodyMesh(b); });
    EXPECT_NE(e.find("s.yaml:3: bodies[0].mesh"), std::string::npos) << spec << ": " << e;
    EXPECT_NE(e.find(message), std::string::npos) << spec << ": " << e;
  }
  b.mesh = "box:0.01,0.01,0.01,3";
  EXPECT_EQ(LoadBodyMesh(b).num_triangles(), 12 * 3 * 3);  // MakeBox: 12 N^2
  b.mesh = "sphere:0.01,2";
  EXPECT_EQ(LoadBodyMesh(b).num_triangles(), 20 * 16);
}

TEST(SceneAssets, ProceduralShapeSpecsAreCheckedAndScaled) {
  BodySpec b = Ball(64);
  b.mesh = "sphere:0.5";
  b.scale = 0.1;
  EXPECT_NEAR(LoadBodyMesh(b).Bounds().size().x(), 0.1, 1e-9);
  b.mesh = "cylinder:1,2";
  EXPECT_THROW(LoadBodyMesh(b), Error);
  b.mesh = "box:1,2";
  EXPECT_THROW(LoadBodyMesh(b), Error);
  b.mesh = "sphere:x";
  EXPECT_THROW(LoadBodyMesh(b), Error);
}

// What loading the first body of a one-line-per-key scene says (empty when it loads).
std::string BodyMeshError(const std::string& mesh, double scale) {
  const std::string text = "name: s\nbodies:\n  - name: ball\n    mesh: \"" + mesh + "\"\n    scale: " +
                           std::to_string(scale) + "\n    role: pointshell\n  - name: plate\n    mesh: \"box:1,1,1\"\n"
                           "    role: field\n";
  try {
    LoadBodyMesh(ParseScene(ConfigNode::LoadString(text, "scene.yaml")).pointshell_body);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneAssets, BadProceduralShapeNamesTheSceneFileAndKey) {
  std::string e = BodyMeshError("sphere:-1", 1);
  EXPECT_NE(e.find("scene.yaml:4: bodies[0].mesh: 'sphere:-1'"), std::string::npos) << e;
  EXPECT_NE(e.find("radius > 0"), std::string::npos) << e;
  e = BodyMeshError("sphere:1e30", 1);
  EXPECT_NE(e.find("scene.yaml:4: bodies[0].mesh"), std::string::npos) << e;
  EXPECT_NE(e.find("coordinates out of range"), std::string::npos) << e;
  EXPECT_EQ(BodyMeshError("sphere:0.05", 1), "");
}

}  // namespace
}  // namespace contactlab
