#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"
#include "util/error.h"

namespace contactlab {
namespace {

const char* kScene = R"(name: spheres
bodies:
  - name: ball
    mesh: "sphere:0.05"
    pose: [0.1, 0, 0, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 2000, levels: 3, seed: 4}
  - name: plate
    mesh: "box:0.2,0.2,0.02"
    role: field
    field: {resolution: 48}
model:
  k_C: 1500
  L: 10
  node_budget: 5000
  coherence: true
  max_point_speed: 0.8
)";

Scene Parse(const std::string& text) { return ParseScene(ConfigNode::LoadString(text, "scene.yaml")); }

// The error message of parsing TEXT (empty when it parses).
std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Scene, ParsesBodiesRolesAndModelParameters) {
  const Scene s = Parse(kScene);
  EXPECT_EQ(s.name, "spheres");
  EXPECT_EQ(s.pointshell_body.name, "ball");
  EXPECT_EQ(s.field_body.name, "plate");
  EXPECT_EQ(s.pointshell_body.pointshell.points, 2000);
  EXPECT_EQ(s.pointshell_body.pointshell.levels, 3);
  EXPECT_EQ(s.field_body.field.resolution, 48);
  EXPECT_DOUBLE_EQ(s.pointshell_body.pose.translation.x(), 0.1);
  EXPECT_DOUBLE_EQ(s.model.penalty.k_C, 1500);
  EXPECT_EQ(s.node_budget, 5000);
  EXPECT_TRUE(s.model.coherence);
  EXPECT_EQ(s.models, std::vector<std::string>{"pointshell"});
}

TEST(Scene, RolesMayBeListedInEitherOrder) {
  std::string text = Replace(kScene, "role: pointshell", "role: TMP");
  text = Replace(text, "role: field\n", "role: pointshell\n");
  text = Replace(text, "role: TMP", "role: field");
  const Scene s = Parse(text);
  EXPECT_EQ(s.pointshell_body.name, "plate");
  EXPECT_EQ(s.field_body.name, "ball");
}

TEST(Scene, UnknownKeyNamesFileLineAndKey) {
  const std::string e = ErrorOf(Replace(kScene, "levels: 3", "levles: 3"));
  EXPECT_NE(e.find("scene.yaml:7"), std::string::npos) << e;
  EXPECT_NE(e.find("bodies[0].pointshell.levles"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
}

TEST(Scene, WrongTypeNamesTheKey) {
  const std::string e = ErrorOf(Replace(kScene, "points: 2000", "points: many"));
  EXPECT_NE(e.find("bodies[0].pointshell.points"), std::string::npos) << e;
  EXPECT_NE(e.find("'many'"), std::string::npos) << e;
}

TEST(Scene, NegativeOrZeroStiffnessIsRejected) {
  for (const char* k : {"k_C: -3", "k_C: 0"}) {
    const std::string e = ErrorOf(Replace(kScene, "k_C: 1500", k));
    EXPECT_NE(e.find("scene.yaml:13: model.k_C"), std::string::npos) << e;
    EXPECT_NE(e.find("must be in (0, 1e+09]"), std::string::npos) << e;
  }
}

TEST(Scene, SizesAreBoundedBeforeAllocatingNamingTheKeyAndTheLimit) {
  std::string e = ErrorOf(Replace(kScene, "points: 2000", "points: 10000000000"));
  EXPECT_NE(e.find("scene.yaml:7: bodies[0].pointshell.points: must be between 1 and 16777216"), std::string::npos) << e;
  e = ErrorOf(Replace(kScene, "levels: 3", "levels: 100"));
  EXPECT_NE(e.find("bodies[0].pointshell.levels: must be between 1 and 12, got 100"), std::string::npos) << e;
  EXPECT_EQ(e.find("-9223372036854775808"), std::string::npos) << e;
  e = ErrorOf(Replace(kScene, "resolution: 48", "resolution: 100000"));
  EXPECT_NE(e.find("bodies[1].field.resolution: must be between 8 and 1024"), std::string::npos) << e;
  e = ErrorOf(Replace(kScene, "points: 2000", "points: 99999999999999999999999"));
  EXPECT_NE(e.find("bodies[0].pointshell.points: the integer '99999999999999999999999' is out of range"),
            std::string::npos)
      << e;
}

TEST(Scene, SparseFieldStorageIsParsedAndWhatItCannotServeIsRefusedByKey) {
  Scene s = Parse(Replace(kScene, "field: {resolution: 48}", "field: {resolution: 1024, storage: sparse, band: 4}"));
  EXPECT_EQ(s.field_body.field.storage, "sparse");
  EXPECT_EQ(s.field_body.field.band, 4);
  EXPECT_EQ(Parse(kScene).field_body.field.storage, "dense");
  // (field block, the message that must name the key) pairs.
  const std::pair<const char*, const char*> refused[] = {
      {"{resolution: 48, storage: bricked}", "bodies[1].field.storage"},
      {"{resolution: 100, storage: sparse}",
       "bodies[1].field.resolution: a sparse field needs a resolution that is a multiple of 8"},
      {"{resolution: 64, storage: sparse, mode: soup}", "bodies[1].field.mode: a sparse field needs the closed pipeline"},
      {"{resolution: 48, band: 3}", "bodies[1].field.band: band applies to storage: sparse only"},
      {"{resolution: 64, storage: sparse, band: 40}", "bodies[1].field.band: must be between 1 and 16"},
      {"{resolution: 64, storage: sparse}\n    deformable: {modes: 4, cells: 8}",
       "bodies[1].field.storage: a deformable body needs a dense field"},
  };
  for (const auto& [field, message] : refused) {
    const std::string e = ErrorOf(Replace(kScene, "field: {resolution: 48}", std::string("field: ") + field));
    EXPECT_NE(e.find(message), std::string::npos) << field << ": " << e;
  }
}

TEST(Scene, DuplicateKeyIsRejectedNamingFileLineAndKey) {
  const std::string e = ErrorOf(Replace(kScene, "  L: 10\n", "  L: 10\n  k_C: 0.5\n"));
  EXPECT_NE(e.find("scene.yaml:15: model.k_C: duplicate key 'k_C'"), std::string::npos) << e;
}

// A sequence or mapping used as a key is refused as a Error naming the file and line; it
// escaped as yaml-cpp's bad-conversion exception ("internal error"). Found by
// tests/fuzz/fuzz_scene.
TEST(Scene, ComplexKeyIsRejectedNamingFileAndLine) {
  std::string e = ErrorOf(Replace(kScene, "  L: 10\n", "  L: 10\n  ? [x, y]\n  : 1\n"));
  EXPECT_NE(e.find("scene.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("a key must be a plain name"), std::string::npos) << e;
  e = ErrorOf("{a: 1}: 2\n");
  EXPECT_NE(e.find("scene.yaml:1:"), std::string::npos) << e;
  EXPECT_NE(e.find("a key must be a plain name"), std::string::npos) << e;
}

TEST(Scene, ErrorsNeverEchoLongTokensOrControlBytes) {
  const std::string huge(1000000, '7');  // a million digits: within the 1 MiB a scene may hold
  std::string e = ErrorOf(Replace(kScene, "k_C: 1500", "k_C: " + huge));
  EXPECT_LT(e.size(), 300u) << e.substr(0, 300);
  EXPECT_NE(e.find("out of range"), std::string::npos) << e.substr(0, 300);
  e = ErrorOf(Replace(kScene, "points: 2000", "points: \"ab\\x1b[2Jcd\""));
  EXPECT_EQ(e.find('\x1b'), std::string::npos) << e;
  EXPECT_NE(e.find("ab\\x1b[2Jcd"), std::string::npos) << e;
  e = ErrorOf(Replace(kScene, "k_C: 1500", "k_C: 1e400"));
  EXPECT_NE(e.find("model.k_C: the number '1e400' is out of range"), std::string::npos) << e;
  // 9.2e18 N/m per point once rendered 2e17 N: k_C is bounded in its row.
  e = ErrorOf(Replace(kScene, "k_C: 1500", "k_C: 9.2e18"));
  EXPECT_NE(e.find("model.k_C:"), std::string::npos) << e;
  EXPECT_NE(e.find("must be in (0, 1e+09], got 9.2e18"), std::string::npos) << e;
}

// bodies[0].field.padding: 1e308 crashed the field build (a segmentation fault), and 1e30 to
// 1e300 ended in "a sample is not finite": the padding is bounded at its key, at 4.
TEST(Scene, AFieldPaddingOf1e308IsRefusedAtItsKey) {
  for (const char* padding : {"1e308", "1e30", "4.5"}) {
    const std::string e =
        ErrorOf(Replace(kScene, "field: {resolution: 48}", std::string("field: {resolution: 48, padding: ") + padding + "}"));
    EXPECT_NE(e.find(".field.padding: must be in [0, 4], got " + std::string(padding)), std::string::npos) << e;
  }
  EXPECT_EQ(Parse(Replace(kScene, "field: {resolution: 48}", "field: {resolution: 48, padding: 4}")).field_body.field.padding, 4);
  const TriangleMesh box = MakeBox(Eigen::Vector3d(0.01, 0.01, 0.01), 1);
  DistanceFieldOptions options;
  options.resolution = 8;
  options.show_progress = false;
  options.padding = 1e308;
  EXPECT_THROW(BuildDistanceField(box, options), Error);
}

TEST(Scene, MissingMeshKeyAndBadRolesAreRejected) {
  EXPECT_NE(ErrorOf(Replace(kScene, "    mesh: \"sphere:0.05\"\n", "")).find("missing required key 'mesh'"), std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kScene, "role: field\n", "role: pointshell\n")).find("different roles"), std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kScene, "role: field\n", "role: wall\n")).find("bodies[1].role"), std::string::npos);
  EXPECT_NE(ErrorOf("bodies: []\n").find("at least two bodies, got 0"), std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kScene, "    role: field\n", "")).find("missing required key 'role'"), std::string::npos);
  EXPECT_NE(ErrorOf("bodies: [\n").find("YAML syntax error"), std::string::npos);
}

TEST(Scene, BadPosesAreRejected) {
  EXPECT_NE(ErrorOf(Replace(kScene, "[0.1, 0, 0, 1, 0, 0, 0]", "[0.1, 0, 0]")).find("7 numbers"), std::string::npos);
  EXPECT_NE(ErrorOf(Replace(kScene, "[0.1, 0, 0, 1, 0, 0, 0]", "[0.1, 0, 0, 0, 0, 0, 0]")).find("zero"), std::string::npos);
  // A quaternion not of unit length (within 1e-6) is refused naming the file, its line and the
  // order, not normalised: 0.99 for 0.999 and a swapped order are typos to report.
  for (const std::string pose : {"[0.1, 0, 0, 0.99, 0.0447101778, 0, 0]", "[0.1, 0, 0, 0, 0, 0, 1.1]",
                                 "{position: [0.1, 0, 0], rotation: [2, 0, 0, 0]}"}) {
    const std::string e = ErrorOf(Replace(kScene, "[0.1, 0, 0, 1, 0, 0, 0]", pose));
    EXPECT_NE(e.find("scene.yaml:5:"), std::string::npos) << pose << ": " << e;
    EXPECT_NE(e.find("x, y, z, qw, qx, qy, qz"), std::string::npos) << pose << ": " << e;
    EXPECT_NE(e.find("not 1"), std::string::npos) << pose << ": " << e;
  }
  // Unit to nine digits is accepted (cos 15 deg, sin 15 deg) and made unit to double precision.
  const Scene rotated = Parse(Replace(kScene, "[0.1, 0, 0, 1, 0, 0, 0]", "[0.1, 0, 0, 0.965925826, 0, 0.258819045, 0]"));
  EXPECT_NEAR(rotated.pointshell_body.pose.rotation.norm(), 1.0, 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(rotated.pointshell_body.pose.rotation).angle(), M_PI / 6, 1e-8);
  const Scene s = Parse(Replace(kScene, "[0.1, 0, 0, 1, 0, 0, 0]", "{position: [0, 0.2, 0], rotation_vector: [0, 0, 1.5]}"));
  EXPECT_NEAR(Eigen::AngleAxisd(s.pointshell_body.pose.rotation).angle(), 1.5, 1e-12);
}

TEST(Scene, SwappedExchangesTheBodies) {
  const Scene s = Parse(kScene).Swapped();
  EXPECT_EQ(s.pointshell_body.name, "plate");
  EXPECT_EQ(s.field_body.name, "ball");
  EXPECT_EQ(s.pointshell_body.role, "pointshell");
}

}  // namespace
}  // namespace contactlab
