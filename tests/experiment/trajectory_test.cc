#include "scene/trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "test_support.h"
#include "util/data_path.h"
#include "util/error.h"

namespace contactlab {
namespace {

TEST(Trajectory, ApproachAndPressReachesTheDepthHalfwayAndReturns) {
  ProceduralTrajectorySpec s;
  s.direction = Eigen::Vector3d(0, 0, -2);
  s.approach = 0.004;
  s.depth = 0.001;
  s.duration = 1.0;
  const Trajectory t = MakeProceduralTrajectory(s);
  EXPECT_NEAR(t.At(0).translation.z(), 0.004, 1e-12);
  EXPECT_NEAR(t.At(0.5).translation.z(), -0.001, 1e-12);
  EXPECT_NEAR(t.At(1.0).translation.z(), 0.004, 1e-12);
  EXPECT_NEAR(t.At(0.5).translation.head<2>().norm(), 0, 1e-15);
}

TEST(Trajectory, PassMovesAtConstantSpeedOnceAndItsSpeedSetsTheDuration) {
  const Trajectory t = ParseTrajectory(ConfigNode::LoadString(
      "type: pass\ndirection: [0, 0, -2]\napproach: 0.02\ndepth: 0.02\nspeed: 5\n", "pass.yaml"));
  EXPECT_NEAR(t.duration(), 0.04 / 5, 1e-15);
  for (const double time : {0.0, 0.001, 0.0037, 0.008}) {
    EXPECT_NEAR(t.At(time).translation.z(), 0.02 - 5 * time, 1e-12) << time;  // 5 mm per ms, straight down
    EXPECT_NEAR(t.At(time).translation.head<2>().norm(), 0, 1e-15);
  }
  const std::string e = testing::ErrorOf([] {
    ParseTrajectory(ConfigNode::LoadString("type: pass\napproach: 0\ndepth: 0\n", "still.yaml"));
  });
  EXPECT_NE(e.find("still.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("approach + depth must be positive"), std::string::npos) << e;
  EXPECT_NE(testing::ErrorOf([] { ParseTrajectory(ConfigNode::LoadString("type: pass\nduration: 1\n", "d.yaml")); })
                .find("duration"),
            std::string::npos);  // a pass has no duration key: its speed sets it
}

TEST(Trajectory, TwistRotatesAboutTheDirectionAndSlideMovesAlongTheTangent) {
  ProceduralTrajectorySpec s;
  s.type = "twist";
  s.angle = 0.6;
  s.direction = Eigen::Vector3d(0, 0, 1);
  const Trajectory twist = MakeProceduralTrajectory(s);
  const Eigen::AngleAxisd aa(twist.At(1.0).rotation);  // middle of the action
  EXPECT_NEAR(aa.angle(), 0.6, 1e-9);
  EXPECT_NEAR(std::abs(aa.axis().z()), 1.0, 1e-9);
  s.type = "slide";
  s.length = 0.03;
  s.tangent = Eigen::Vector3d(0, 1, 1);  // made orthogonal to the direction: +y
  const Trajectory slide = MakeProceduralTrajectory(s);
  EXPECT_NEAR(slide.At(1.0).translation.y(), 0.03, 1e-9);
  EXPECT_NEAR(slide.At(1.0).translation.x(), 0.0, 1e-12);
}

TEST(Trajectory, MaxPointSpeedBoundsTranslationAndRotation) {
  const Trajectory t({0.0, 1.0}, {Pose::Identity(), Pose{RotationFromVector(Eigen::Vector3d(0, 0, 0.5)),
                                                         Eigen::Vector3d(0.2, 0, 0)}},
                     "two samples");
  EXPECT_NEAR(t.MaxPointSpeed(0.1), 0.2 + 0.5 * 0.1, 1e-12);
  const Pose mid = t.At(0.5);
  EXPECT_NEAR(mid.translation.x(), 0.1, 1e-15);
  EXPECT_NEAR(Eigen::AngleAxisd(mid.rotation).angle(), 0.25, 1e-12);
}

TEST(Trajectory, CsvRoundTripIsRelativeToTheFirstSample) {
  testing::TempDir dir;
  ProceduralTrajectorySpec s;
  s.type = "circle";
  s.radius = 0.01;
  s.duration = 0.5;
  const Trajectory t = MakeProceduralTrajectory(s);
  SaveTrajectoryCsv(t, dir / "t.csv");
  const Trajectory back = LoadTrajectoryCsv(dir / "t.csv");
  for (double time : {0.0, 0.1234, 0.25, 0.4}) {
    const Eigen::Vector3d expected = t.At(time).translation - t.At(0).translation;
    EXPECT_LT((back.At(time).translation - expected).norm(), 1e-9) << time;
  }
}

std::string ErrorOfCsv(const std::string& text) {
  testing::TempDir dir;
  std::ofstream(dir / "bad.csv") << text;
  try {
    LoadTrajectoryCsv(dir / "bad.csv");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Trajectory, BadCsvRowsNameTheFileAndLine) {
  const std::string header = "t,x,y,z,qw,qx,qy,qz\n";
  EXPECT_NE(ErrorOfCsv(header + "0,0,0,0,1,0,0,0\n0.001,0,0,0,1,0\n").find("bad.csv:3"), std::string::npos);
  EXPECT_NE(ErrorOfCsv(header + "0,0,0,0,1,0,0,0\n0,0,0,0,1,0,0,0\n").find("not greater"), std::string::npos);
  EXPECT_NE(ErrorOfCsv(header + "0,0,0,0,0,0,0,0\n").find("quaternion is zero"), std::string::npos);
  // A row whose quaternion is not unit length (within 1e-6) is refused naming its line and the
  // order of the columns, not normalised.
  const std::string e = ErrorOfCsv(header + "0,0,0,0,1,0,0,0\n0.001,0,0,0,0.999,0.0001,0,0\n");
  EXPECT_NE(e.find("bad.csv:3: the quaternion (qw, qx, qy, qz) = (0.999, 0.0001, 0, 0) has length"), std::string::npos) << e;
  EXPECT_NE(e.find("x, y, z, qw, qx, qy, qz"), std::string::npos) << e;
  EXPECT_NE(ErrorOfCsv(header + "0,0,nan,0,1,0,0,0\n").find("not finite"), std::string::npos);
  EXPECT_NE(ErrorOfCsv(header + "0,0,x,0,1,0,0,0\n").find("column 3"), std::string::npos);
  EXPECT_NE(ErrorOfCsv("t,a,b\n").find("header"), std::string::npos);
  EXPECT_NE(ErrorOfCsv(header + "0,0,0,0,1,0,0,0\n").find("at least two rows"), std::string::npos);
}

// A recorded trajectory's bad cell is quoted cut short, its control bytes escaped.
TEST(Trajectory, CsvErrorsNeverEchoLongTokensOrControlBytes) {
  const std::string header = "t,x,y,z,qw,qx,qy,qz\n";
  std::string e = ErrorOfCsv(header + "0,0," + std::string(100000, '7') + "x,0,1,0,0,0\n");
  EXPECT_LT(e.size(), 300u) << e.substr(0, 300);
  EXPECT_NE(e.find("column 3"), std::string::npos) << e.substr(0, 300);
  EXPECT_NE(e.find("(100001 characters)"), std::string::npos) << e.substr(0, 300);
  e = ErrorOfCsv(header + "0,0,\x1b[2Jab\x07,0,1,0,0,0\n");
  EXPECT_EQ(e.find('\x1b'), std::string::npos) << e;
  EXPECT_EQ(e.find('\x07'), std::string::npos) << e;
  EXPECT_NE(e.find("'\\x1b[2Jab\\x07'"), std::string::npos) << e;
}

// Every trajectory the repository ships has unit quaternions, and so does a twisting motion
// written with nine significant digits, as a session log writes the device's pose: both load,
// the twist at the angles it was written with.
TEST(Trajectory, ShippedAndNineDigitTrajectoriesHaveUnitQuaternions) {
  const std::optional<std::filesystem::path> data = InstalledDataDir();
  ASSERT_TRUE(data.has_value());
  int shipped = 0;
  for (const auto& e : std::filesystem::directory_iterator(*data / "trajectories")) {
    if (e.path().extension() != ".csv") continue;
    EXPECT_NO_THROW(LoadTrajectoryCsv(e.path())) << e.path();
    ++shipped;
  }
  EXPECT_GT(shipped, 0);
  testing::TempDir dir;
  {
    std::ofstream out(dir / "log.csv");
    out << "t,x,y,z,qw,qx,qy,qz\n";
    char line[256];
    for (int i = 0; i <= 1000; ++i) {
      const Eigen::Quaterniond q = RotationFromVector(Eigen::Vector3d(0.3, -0.2, 1.0 / 3.0) * (0.003 * i));
      std::snprintf(line, sizeof line, "%.6f,0,0,0,%.9g,%.9g,%.9g,%.9g\n", 0.001 * i, q.w(), q.x(), q.y(), q.z());
      out << line;
    }
  }
  const Trajectory t = LoadTrajectoryCsv(dir / "log.csv");
  const double angle = Eigen::Vector3d(0.3, -0.2, 1.0 / 3.0).norm() * 3.0;
  EXPECT_NEAR(Eigen::AngleAxisd(t.At(1.0).rotation).angle(), angle, 1e-7);
}

TEST(Trajectory, SessionLogsWithExtraColumnsReplay) {
  testing::TempDir dir;
  std::ofstream(dir / "log.csv") << "# session log\nt,x,y,z,qw,qx,qy,qz,fx,fy\n0,1,2,3,1,0,0,0,5,6\n0.001,1.001,2,3,1,0,0,0,5,6\n";
  const Trajectory t = LoadTrajectoryCsv(dir / "log.csv");
  EXPECT_NEAR(t.At(0.001).translation.x(), 0.001, 1e-12);
}

TEST(Trajectory, HugeDurationIsRefusedBeforeAllocatingNamingTheKeyAndLimit) {
  const ConfigNode n = ConfigNode::LoadString("type: approach-press\nduration: 1e9\n", "config.yaml");
  try {
    ParseTrajectory(n);
    FAIL() << "a 1e9 s trajectory was accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("config.yaml:2: duration:"), std::string::npos) << m;
    EXPECT_NE(m.find("limit of 1e+08"), std::string::npos) << m;
  }
  // At the limit's scale but under it, the spec still parses (without building it here).
  EXPECT_NO_THROW(ParseTrajectory(ConfigNode::LoadString("type: approach-press\nduration: 3\n", "c.yaml")));
}


ConfigNode Yaml(const std::string& text, const std::string& file = "t.yaml") {
  return ConfigNode::LoadString(text, file);
}

using testing::ErrorOf;

// Each type's table reads its keys to the spec; keys left out keep the defaults
// (trajectory.h: approach 5 mm, depth 2 mm, radius 5 mm, 2 s at 1 kHz, no touch, 0.1 mm).
TEST(Trajectory, EachTypeReadsItsKeysAndKeepsTheDefaultsOfTheOthers) {
  TrajectorySpec s = ParseTrajectorySpec(Yaml(
      "type: slide\ndirection: [0, 1, 0]\ntangent: [1, 0, 1]\napproach: 0.0\ndepth: 0.0015\nlength: 0.02\n"
      "duration: 0.5\nrate: 500\ntouch: true\ntouch_depth: 0.0002\n"));
  EXPECT_EQ(s.shape.type, "slide");
  EXPECT_FALSE(s.toward);
  EXPECT_EQ(s.shape.direction, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(s.shape.tangent, Eigen::Vector3d(1, 0, 1));
  EXPECT_EQ(s.shape.approach, 0.0);
  EXPECT_EQ(s.shape.depth, 0.0015);
  EXPECT_EQ(s.shape.length, 0.02);
  EXPECT_EQ(s.shape.duration, 0.5);
  EXPECT_EQ(s.shape.rate, 500);
  EXPECT_TRUE(s.touch);
  EXPECT_EQ(s.touch_depth, 0.0002);

  s = ParseTrajectorySpec(Yaml("{type: circle, direction: toward, radius: 0.003}"));
  EXPECT_EQ(s.shape.type, "circle");
  EXPECT_TRUE(s.toward);  // left to the runner: the direction keeps its default until then
  EXPECT_EQ(s.shape.direction, Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(s.shape.radius, 0.003);
  EXPECT_EQ(s.shape.approach, 0.005);
  EXPECT_EQ(s.shape.depth, 0.002);
  EXPECT_EQ(s.shape.duration, 2.0);
  EXPECT_EQ(s.shape.rate, 1000);
  EXPECT_FALSE(s.touch);
  EXPECT_EQ(s.touch_depth, 1e-4);

  // Depth and angle take any sign.
  s = ParseTrajectorySpec(Yaml("{type: twist, angle: -0.4, depth: -0.001}"));
  EXPECT_EQ(s.shape.angle, -0.4);
  EXPECT_EQ(s.shape.depth, -0.001);
  EXPECT_NEAR(Eigen::AngleAxisd(MakeTrajectory(s).At(1.0).rotation).angle(), 0.4, 1e-9);

  // A recorded file is found beside the config that names it.
  testing::TempDir dir;
  std::ofstream(dir / "log.csv") << "t,x,y,z,qw,qx,qy,qz\n0,1,2,3,1,0,0,0\n0.002,1.5,2,3,1,0,0,0\n";
  s = ParseTrajectorySpec(
      Yaml("{type: recorded, file: log.csv, direction: [1, 0, 0], touch: true}", (dir / "c.yaml").string()));
  EXPECT_EQ(s.shape.type, "recorded");
  EXPECT_TRUE(std::filesystem::equivalent(s.file, dir / "log.csv")) << s.file;
  EXPECT_EQ(s.shape.direction, Eigen::Vector3d(1, 0, 0));
  EXPECT_TRUE(s.touch);
  const Trajectory t = MakeTrajectory(s);
  EXPECT_EQ(t.num_samples(), 2u);
  EXPECT_NEAR(t.At(0.002).translation.x(), 0.5, 1e-12);
}

// A key the type does not take, an unknown key or type, and a value out of range or of the
// wrong kind: each error names the file, the line, the key and what is wrong.
TEST(Trajectory, BadKeysAreErrorsNamingTheFileLineAndKey) {
  const auto error = [](const std::string& text) { return ErrorOf([&] { ParseTrajectorySpec(Yaml(text)); }); };
  std::string e = error("type: twist\nlength: 0.01\n");
  EXPECT_NE(e.find("t.yaml:2: length: not a key of type twist, only of slide, scan (twist takes: type, direction, "
                   "approach, depth, angle, duration, rate, touch, touch_depth)"),
            std::string::npos)
      << e;
  e = error("type: recorded\nfile: log.csv\ndepth: 0.01\n");
  EXPECT_NE(e.find("t.yaml:3: depth: not a key of type recorded, only of approach-press, slide, twist, scan, circle"),
            std::string::npos)
      << e;
  e = error("type: slide\nlenght: 0.01\n");
  EXPECT_NE(e.find("t.yaml:2: lenght: unknown key (known keys here: direction, tangent, approach, depth, length, "
                   "duration, rate, touch, touch_depth, type)"),
            std::string::npos)
      << e;
  e = error("type: wiggle\n");
  EXPECT_NE(e.find("t.yaml:1: type: 'wiggle' is not one of: approach-press, slide, twist, scan, circle, pass, recorded"),
            std::string::npos)
      << e;
  e = error("duration: 1\n");
  EXPECT_NE(e.find("t.yaml:1: (top level): missing required key 'type'"), std::string::npos) << e;
  e = error("type: recorded\ntouch: true\n");
  EXPECT_NE(e.find("missing required key 'file'"), std::string::npos) << e;
  e = error("type: approach-press\napproach: -0.001\n");
  EXPECT_NE(e.find("t.yaml:2: approach: must not be negative, got -0.001"), std::string::npos) << e;
  e = error("type: scan\nrate: 0\n");
  EXPECT_NE(e.find("t.yaml:2: rate: must be positive, got 0"), std::string::npos) << e;
  e = error("type: circle\ndirection: [0, 0, 0]\n");
  EXPECT_NE(e.find("t.yaml:2: direction: must be non-zero"), std::string::npos) << e;
  e = error("type: slide\ntangent: [1, 0]\n");
  EXPECT_NE(e.find("t.yaml:2: tangent: needs 3 numbers"), std::string::npos) << e;
  e = error("type: slide\ntouch: maybe\n");
  EXPECT_NE(e.find("t.yaml:2: touch: expected true or false, got 'maybe'"), std::string::npos) << e;
  e = error("type: approach-press\ntouch_depth: 0\n");
  EXPECT_NE(e.find("t.yaml:2: touch_depth: must be positive, got 0"), std::string::npos) << e;
  // A direction whose length overflows normalised to zero and nothing moved; a twist of 1e300
  // rad was refused only after the run.
  e = error("type: circle\ndirection: [1e308, 1e308, 0]\n");
  EXPECT_NE(e.find("t.yaml:2: direction: its length overflows"), std::string::npos) << e;
  e = error("type: slide\ntangent: [1e308, 0, 1e308]\n");
  EXPECT_NE(e.find("t.yaml:2: tangent: its length overflows"), std::string::npos) << e;
  e = error("type: twist\nangle: 1e300\n");
  EXPECT_NE(e.find("t.yaml:2: angle: must be in [-1000, 1000], got 1e300"), std::string::npos) << e;
  e = error("type: twist\nangle: wide\n");
  EXPECT_NE(e.find("t.yaml:2: angle: expected a finite number, got 'wide'"), std::string::npos) << e;
}

// The reference (`contactlab params`) shows each type's keys, and only those, with the
// defaults of trajectory.h.
TEST(Trajectory, ReferenceListsEachTypesKeysWithTheirDefaults) {
  const std::string r = TrajectoryReference();
  EXPECT_NE(r.find("| `type` | choice | approach-press, slide, twist, scan, circle, pass, recorded |"), std::string::npos)
      << r;
  for (const char* type : {"approach-press", "slide", "twist", "scan", "circle", "recorded"}) {
    EXPECT_NE(r.find(std::string("### `trajectory: {type: ") + type + "}`"), std::string::npos) << type;
  }
  EXPECT_NE(r.find("| `radius` | number | >= 0 | 0.005 | m |"), std::string::npos) << r;
  EXPECT_NE(r.find("| `duration` | number | > 0 | 2 | s |"), std::string::npos) << r;
  EXPECT_NE(r.find("| `touch_depth` | number | > 0 | 0.0001 | m |"), std::string::npos) << r;
  EXPECT_NE(r.find("| `direction` | vector | [x, y, z] not zero, or toward | [0, 0, -1] |"), std::string::npos) << r;
  const auto rows = [&](const std::string& key) {
    const std::string cell = "| `" + key + "` |";
    int n = 0;
    for (std::size_t at = r.find(cell); at != std::string::npos; at = r.find(cell, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(rows("direction"), 7);  // every type
  EXPECT_EQ(rows("touch"), 7);
  EXPECT_EQ(rows("speed"), 1);      // pass
  EXPECT_EQ(rows("duration"), 5);   // the procedural ones
  EXPECT_EQ(rows("tangent"), 3);    // slide, scan, circle
  EXPECT_EQ(rows("length"), 2);     // slide, scan
  EXPECT_EQ(rows("radius"), 1);
  EXPECT_EQ(rows("angle"), 1);
  EXPECT_EQ(rows("file"), 1);
}

}  // namespace
}  // namespace contactlab
