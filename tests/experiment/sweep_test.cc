// Sweeps as overrides: each value is written at its key path into the config or scene
// document and the scene is parsed again, so the scene parser's checks apply to every value.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "experiment/experiment_config.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/config_node.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// The ball-on-plate scene, the ball 1.5 mm above the plate, 256 points of seed 3.
const std::string kScene = [] {
  testing::BallOnPlate s;
  s.ball_z = 0.0215;
  s.points = 256;
  s.seed = 3;
  return s.Yaml();
}();

// A config over the scene file, with SWEEP (YAML lines under "sweep:").
ExperimentConfig Load(const TempDir& dir, const std::string& sweep) {
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "config.yaml") << "name: s\nscene: " << (dir / "scene.yaml").string()
                                     << "\nmodels: [pointshell-linear]\n"
                                        "trajectory: {type: approach-press, direction: [0, 0, -1], depth: 0.001, "
                                        "duration: 0.01}\nsweep:\n"
                                     << sweep;
  return LoadExperimentConfig(dir / "config.yaml");
}

std::string ErrorOf(const TempDir& dir, const std::string& sweep) {
  try {
    Load(dir, sweep);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Sweep, AliasesAndTheirKeyPathsMakeTheSameJobs) {
  TempDir dir;
  const std::vector<Job> by_alias = ExpandJobs(Load(dir, "  points: [64, 1024]\n  resolution: [32]\n  k_C: [250]\n"));
  const std::vector<Job> by_path = ExpandJobs(Load(dir,
      "  scene.bodies[role=pointshell].pointshell.points: [64, 1024]\n"
      "  scene.bodies[name=plate].field.resolution: [32]\n  scene.model.k_C: [250]\n"));
  ASSERT_EQ(by_alias.size(), 2u);
  ASSERT_EQ(by_path.size(), 2u);
  for (std::size_t j = 0; j < 2; ++j) {
    for (const std::vector<Job>* jobs : {&by_alias, &by_path}) {
      const Scene& s = (*jobs)[j].scene;
      EXPECT_EQ(s.pointshell_body.pointshell.points, j == 0 ? 64 : 1024);
      EXPECT_EQ(s.field_body.field.resolution, 32);
      EXPECT_EQ(s.pointshell_body.field.resolution, 24);
      EXPECT_EQ(s.model.penalty.k_C, 250);
      EXPECT_EQ(s.pointshell_body.pointshell.seed, 3u);  // untouched keys stay
    }
  }
}

TEST(Sweep, AnyKeyIsSweepableByItsPath) {
  TempDir dir;
  const std::vector<Job> jobs =
      ExpandJobs(Load(dir, "  scene.model.lipschitz: [1, 2.5]\n  trajectory.depth: [0.0005]\n"
                           "  scene.bodies[1].scale: [2]\n"));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].scene.model.lipschitz, 1);
  EXPECT_EQ(jobs[1].scene.model.lipschitz, 2.5);
  EXPECT_EQ(jobs[1].trajectory_node.Double("depth", 0), 0.0005);
  EXPECT_EQ(jobs[1].scene.field_body.scale, 2);
  EXPECT_EQ(jobs[1].Label(), "scene.model.lipschitz=2.5 trajectory.depth=0.0005 scene.bodies[1].scale=2");
}

TEST(Sweep, TheValueDefaultRemovesTheKey) {
  TempDir dir;
  const std::vector<Job> jobs = ExpandJobs(Load(dir, "  offset: [default, 0.001]\n  scene.bodies[0].pointshell.seed: [default]\n"));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].scene.pointshell_body.pointshell.offset, -1);  // the builder's default
  EXPECT_EQ(jobs[1].scene.pointshell_body.pointshell.offset, 0.001);
  EXPECT_EQ(jobs[0].scene.pointshell_body.pointshell.seed, PointshellSpec{}.seed);
}

TEST(Sweep, RolesApplyBeforeTheOtherAxes) {
  TempDir dir;
  const std::vector<Job> jobs = ExpandJobs(Load(dir, "  resolution: [40]\n  roles: [normal, swapped]\n"));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].scene.field_body.name, "plate");
  EXPECT_EQ(jobs[1].scene.field_body.name, "ball");
  // "resolution" is the field body's, whichever body that is after the swap.
  EXPECT_EQ(jobs[0].scene.field_body.field.resolution, 40);
  EXPECT_EQ(jobs[1].scene.field_body.field.resolution, 40);
  EXPECT_EQ(jobs[1].scene.pointshell_body.field.resolution, 24);
  // The same physical body moves in both role orders.
  EXPECT_EQ(jobs[0].moving_body, "plate");
  EXPECT_EQ(jobs[1].moving_body, "plate");
}

TEST(Sweep, ABadValueNamesTheConfigTheAxisTheValueAndTheSceneKey) {
  TempDir dir;
  std::string e = ErrorOf(dir, "  points: [64, -5]\n");
  EXPECT_NE(e.find("config.yaml: sweep.points value '-5'"), std::string::npos) << e;
  EXPECT_NE(e.find("pointshell.points"), std::string::npos) << e;
  e = ErrorOf(dir, "  k_C: [-1]\n");
  EXPECT_NE(e.find("sweep.k_C value '-1'"), std::string::npos) << e;
  EXPECT_NE(e.find("model.k_C"), std::string::npos) << e;
  e = ErrorOf(dir, "  scene.model.lipschitz: [0.5]\n");
  EXPECT_NE(e.find("sweep.scene.model.lipschitz value '0.5'"), std::string::npos) << e;
  EXPECT_NE(e.find("at least 1"), std::string::npos) << e;
  e = ErrorOf(dir, "  roles: [upside-down]\n");
  EXPECT_NE(e.find("sweep.roles value 'upside-down'"), std::string::npos) << e;
  // A model name is checked when the config loads, against the registered names, and blamed on
  // the sweep value that holds it.
  e = ErrorOf(dir, "  model: [pointshell, pointshel]\n");
  EXPECT_NE(e.find("config.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find(": sweep.model[1]: unknown contact model 'pointshel' (known: "), std::string::npos) << e;
}

TEST(Sweep, AnOversizedValueIsRefusedWhenTheConfigLoadsNamingTheLimit) {
  TempDir dir;
  std::string e = ErrorOf(dir, "  points: [64, 10000000000]\n");
  EXPECT_NE(e.find("sweep.points value '10000000000'"), std::string::npos) << e;
  EXPECT_NE(e.find("must be between 1 and 16777216"), std::string::npos) << e;
  e = ErrorOf(dir, "  levels: [100]\n");
  EXPECT_NE(e.find("sweep.levels value '100'"), std::string::npos) << e;
  EXPECT_NE(e.find("must be between 1 and 12"), std::string::npos) << e;
}

// The values 1..N as a YAML list.
std::string Values(int n) {
  std::string list = "[";
  for (int i = 1; i <= n; ++i) list += (i > 1 ? ", " : "") + std::to_string(i);
  return list + "]";
}

TEST(Sweep, ABillionJobsAreRefusedBeforeAnyIsBuiltNamingTheFileAndTheLimit) {
  TempDir dir;
  // 1000 x 1000 x 1000: counted from the axes' lengths, never expanded.
  const std::string axes = "  scene.model.lipschitz: " + Values(1000) + "\n  trajectory.depth: " + Values(1000) +
                           "\n  trajectory.duration: " + Values(1000) + "\n";
  std::string e = ErrorOf(dir, axes);
  EXPECT_NE(e.find((dir / "config.yaml").string()), std::string::npos) << e;
  EXPECT_NE(e.find("sweep: 1000 x 1000 x 1000 values make 1000000000 jobs; a sweep may have at most 10000"),
            std::string::npos)
      << e;
  // Seven such axes overflow 64 bits: still refused, not wrapped around to a small count.
  std::string seven;
  for (int a = 0; a < 7; ++a) seven += "  scene.bodies[" + std::to_string(a % 2) + "].pose" + std::string(a, 'x') + ": " + Values(1000) + "\n";
  e = ErrorOf(dir, seven);
  EXPECT_NE(e.find("values make more than 2^64 jobs; a sweep may have at most 10000"), std::string::npos) << e;
  EXPECT_EQ(kMaxSweepJobs, 10000u);
}

TEST(ExperimentConfig, AConfigOrSceneFileOverOneMebibyteIsRefusedBeforeParsingNamingItAndTheLimit) {
  TempDir dir;
  // A valid config followed by a comment: only its size is wrong.
  Load(dir, "  points: [64]\n");
  const std::string config = ReadWholeFile(dir / "config.yaml");
  std::ofstream(dir / "big.yaml") << config << "# " << std::string(kMaxConfigBytes, 'x') << "\n";
  try {
    LoadExperimentConfig(dir / "big.yaml");
    FAIL() << "a config of more than 1 MiB was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "big.yaml").string() + ": is " +
                                         std::to_string(config.size() + kMaxConfigBytes + 3) +
                                         " bytes; a config or scene file may hold at most 1048576 bytes"),
              std::string::npos)
        << e.what();
  }
  // The same for a scene file the config names.
  std::ofstream(dir / "big-scene.yaml") << kScene << "# " << std::string(kMaxConfigBytes, 'x') << "\n";
  try {
    ConfigNode::LoadFile(dir / "big-scene.yaml");
    FAIL() << "a scene of more than 1 MiB was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "big-scene.yaml").string() + ": is "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at most 1048576 bytes"), std::string::npos) << e.what();
  }
  EXPECT_EQ(kMaxConfigBytes, 1u << 20);
}

TEST(Sweep, AnUnknownAxisOrABadPathIsNamed) {
  TempDir dir;
  std::string e = ErrorOf(dir, "  pionts: [64]\n");
  EXPECT_NE(e.find("sweep.pionts"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown sweep axis"), std::string::npos) << e;
  e = ErrorOf(dir, "  scene.bodies[role=nobody].scale: [1]\n");
  EXPECT_NE(e.find("sweep.scene.bodies[role=nobody].scale value '1'"), std::string::npos) << e;
  EXPECT_NE(e.find("no element of 'bodies' has role = nobody"), std::string::npos) << e;
  e = ErrorOf(dir, "  scene.bodies[7].scale: [1]\n");
  EXPECT_NE(e.find("at index 7"), std::string::npos) << e;
  e = ErrorOf(dir, "  scene.model.k_C.x: [1]\n");
  EXPECT_NE(e.find("'k_C' is not a mapping"), std::string::npos) << e;
  e = ErrorOf(dir, "  scene.bodies[0].colour: [red]\n");
  EXPECT_NE(e.find("colour"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown key"), std::string::npos) << e;
}

// An error in a job's trajectory or its scene names the line of the key in its own file, as the
// config's own keys do: each job's documents are parsed from their text, not copied without
// their lines.
TEST(Sweep, AJobsTrajectoryOrSceneErrorNamesTheKeysOwnLine) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string head = "name: s\nscene: " + (dir / "scene.yaml").string() + "\nmodels: [pointshell-linear]\n\n";
  std::ofstream(dir / "config.yaml") << head
                                     << "trajectory:\n"          // line 5
                                        "  type: approach-press\n"
                                        "  direction: [0, 0, -1]\n"
                                        "  duraton: 0.01\n"      // line 8
                                        "sweep:\n  k_C: [1000, 2000]\n";
  std::string e;
  try {
    LoadExperimentConfig(dir / "config.yaml");
  } catch (const Error& error) {
    e = error.what();
  }
  EXPECT_NE(e.find("config.yaml:8: trajectory.duraton: unknown key"), std::string::npos) << e;
  // The same under --set: the lines are those of the config as resolved.
  std::ofstream(dir / "config.yaml") << head << "trajectory:\n  type: approach-press\n  deptth: 0.001\n";
  e.clear();
  try {
    LoadExperimentConfig(dir / "config.yaml", {"trajectory.duration=0.01"});
  } catch (const Error& error) {
    e = error.what();
  }
  EXPECT_NE(e.find("trajectory.deptth: unknown key"), std::string::npos) << e;
  EXPECT_EQ(e.find(":1: trajectory"), std::string::npos) << e;
  // A scene key a job's sweep leaves alone keeps its line in the scene file.
  std::string scene = kScene;
  const std::size_t at = scene.find("resolution:");
  ASSERT_NE(at, std::string::npos);
  scene.replace(at, std::string("resolution:").size(), "resolutoin:");
  std::ofstream(dir / "scene.yaml") << scene;
  const long line = long(std::count(scene.begin(), scene.begin() + long(at), '\n')) + 1;
  std::ofstream(dir / "config.yaml") << head << "trajectory: {type: approach-press, duration: 0.01}\n"
                                     << "sweep:\n  k_C: [1000, 2000]\n";
  e.clear();
  try {
    LoadExperimentConfig(dir / "config.yaml");
  } catch (const Error& error) {
    e = error.what();
  }
  EXPECT_NE(e.find("scene.yaml:" + std::to_string(line) + ":"), std::string::npos) << e;
  EXPECT_NE(e.find("resolutoin"), std::string::npos) << e;
}

TEST(Sweep, OverridesAndProfilesTakeKeyPathsWithSelectors) {
  TempDir dir;
  Load(dir, "  trajectory.depth: [0.001]\n");
  // A key path holding "[field=value]" ends at the '=' after the selector, in --set and in a
  // profile (whose overrides are written the same way); after "sweep." the whole rest is the
  // name of one axis, itself a key path.
  std::ofstream(dir / "config.yaml", std::ios::app)
      << "profiles:\n  big:\n    sweep.scene.bodies[role=pointshell].pointshell:\n"
         "      - {label: a, value: {points: 128, levels: 3}}\n";
  ExperimentConfig c = LoadExperimentConfig(dir / "config.yaml", {"sweep.scene.bodies[name=plate].field.resolution=[32]"});
  ASSERT_EQ(c.sweep.size(), 2u);
  ASSERT_EQ(ExpandJobs(c).size(), 1u);
  EXPECT_EQ(ExpandJobs(c)[0].scene.field_body.field.resolution, 32);
  EXPECT_EQ(c.sweep[1].name, "scene.bodies[name=plate].field.resolution");
  c = LoadExperimentConfig(dir / "config.yaml", {}, "big");
  ASSERT_EQ(c.sweep.size(), 2u);
  const std::vector<Job> jobs = ExpandJobs(c);
  ASSERT_EQ(jobs.size(), 1u);
  EXPECT_EQ(jobs[0].scene.pointshell_body.pointshell.points, 128);
  EXPECT_EQ(jobs[0].scene.pointshell_body.pointshell.levels, 3);
  EXPECT_EQ(jobs[0].axis_values[1].second, "a");
}

TEST(SetAtPath, CreatesMappingsPicksElementsAndRemovesKeys) {
  YAML::Node doc = YAML::Load("a: {b: 1}\nlist: [{name: x, v: 1}, {name: y, v: 2}]\n");
  SetAtPath(doc, "a.c.d", YAML::Node(5), "t");
  EXPECT_EQ(doc["a"]["c"]["d"].as<int>(), 5);
  EXPECT_EQ(doc["a"]["b"].as<int>(), 1);
  SetAtPath(doc, "list[name=y].v", YAML::Node(7), "t");
  SetAtPath(doc, "list[0].v", YAML::Node(8), "t");
  EXPECT_EQ(doc["list"][1]["v"].as<int>(), 7);
  EXPECT_EQ(doc["list"][0]["v"].as<int>(), 8);
  SetAtPath(doc, "a.b", std::nullopt, "t");
  EXPECT_FALSE(doc["a"]["b"]);
  EXPECT_THROW(SetAtPath(doc, "a..b", YAML::Node(1), "t"), Error);
  EXPECT_THROW(SetAtPath(doc, "list[2].v", YAML::Node(1), "t"), Error);
  EXPECT_THROW(SetAtPath(doc, "list[name=y.v", YAML::Node(1), "t"), Error);
  // [*]: every element gets the rest of the path.
  SetAtPath(doc, "list[*].w.z", YAML::Node(3), "t");
  EXPECT_EQ(doc["list"][0]["w"]["z"].as<int>(), 3);
  EXPECT_EQ(doc["list"][1]["w"]["z"].as<int>(), 3);
  EXPECT_EQ(doc["list"][1]["v"].as<int>(), 7);
  EXPECT_THROW(SetAtPath(doc, "list[*]", YAML::Node(1), "t"), Error);
  EXPECT_THROW(SetAtPath(doc, "a[*].v", YAML::Node(1), "t"), Error);
}

TEST(Sweep, LabelledValuesWriteTheirValueAndNameTheJobByLabel) {
  TempDir dir;
  // A list-valued parameter (the plate's pose) swept under labels.
  const std::vector<Job> jobs = ExpandJobs(Load(dir,
      "  scene.bodies[name=plate].pose: [{label: low, value: [0, 0, -0.02, 1, 0, 0, 0]},\n"
      "                                  {label: high, value: {position: [0, 0, 0.01]}}]\n"));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].Label(), "scene.bodies[name=plate].pose=low");
  EXPECT_EQ(jobs[1].axis_values[0].second, "high");
  EXPECT_DOUBLE_EQ(jobs[0].scene.field_body.pose.translation.z(), -0.02);
  EXPECT_DOUBLE_EQ(jobs[1].scene.field_body.pose.translation.z(), 0.01);
  // A label must be a plain name, and a labelled value needs both keys.
  EXPECT_NE(ErrorOf(dir, "  scene.bodies[name=plate].pose: [{label: 'a,b', value: [0, 0, 0, 1, 0, 0, 0]}]\n")
                .find("label"),
            std::string::npos);
  EXPECT_NE(ErrorOf(dir, "  scene.bodies[name=plate].pose: [{label: a, valu: 1}]\n").find("valu"), std::string::npos);
  // Its value gets the scene parser's checks, named by the axis and label.
  const std::string bad = ErrorOf(dir, "  scene.bodies[name=plate].pose: [{label: short, value: [1, 2]}]\n");
  EXPECT_NE(bad.find("config.yaml: sweep.scene.bodies[name=plate].pose value 'short'"), std::string::npos) << bad;
}

}  // namespace
}  // namespace contactlab
