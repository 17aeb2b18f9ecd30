// End-to-end checks of the `contactlab` program: exit codes, error messages that name the
// file, no output left behind on failure, and the session and run commands on small scenes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "test_support.h"
#include "util/atomic_file.h"

namespace contactlab {
namespace {

struct Outcome {
  int exit_code = -1;
  std::string output;  // stdout and stderr
};

Outcome RunCli(const std::string& args) {
  const std::string command = std::string(CONTACTLAB_CLI) + " " + args + " 2>&1";
  Outcome o;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return o;
  std::array<char, 4096> buf;
  while (std::fgets(buf.data(), int(buf.size()), pipe)) o.output += buf.data();
  const int status = ::pclose(pipe);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

const char* kScene = R"(name: cli-ball-plate
bodies:
  - name: ball
    mesh: "sphere:0.02,3"
    pose: [0, 0, 0.0205, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 512, levels: 2}
    field: {resolution: 24}
  - name: plate
    mesh: "box:0.05,0.05,0.01,2"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 24}
model: {k_C: 1000}
)";

TEST(Cli, ContactPrintsTheForceOnTheFieldBodyAsJson) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const Outcome o = RunCli("contact " + (dir / "scene.yaml").string() + " --json --cache " + (dir / "cache").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("\"points_in_contact\""), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("\"K_B\""), std::string::npos) << o.output;
}

TEST(Cli, BadSceneKeyFailsNamingFileAndKey) {
  testing::TempDir dir;
  std::string text = kScene;
  text.replace(text.find("k_C: 1000"), 9, "k_C: -5");
  std::ofstream(dir / "bad.yaml") << text;
  const Outcome o = RunCli("contact " + (dir / "bad.yaml").string() + " --no-cache");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("bad.yaml"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("model.k_C"), std::string::npos) << o.output;
}

TEST(Cli, MissingMeshAndBadArgumentsExitNonZero) {
  EXPECT_EQ(RunCli("mesh-info no-such-mesh-4711.obj").exit_code, 1);
  EXPECT_NE(RunCli("mesh-info no-such-mesh-4711.obj").output.find("no-such-mesh-4711.obj"), std::string::npos);
  EXPECT_NE(RunCli("no-such-command").exit_code, 0);
  EXPECT_NE(RunCli("contact").exit_code, 0);
}

TEST(Cli, FailedFieldBuildLeavesNoOutputFile) {
  testing::TempDir dir;
  std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const Outcome o = RunCli("sdf " + (dir / "tri.obj").string() + " --resolution 16 --mode closed --out " +
                        (dir / "out.sdf").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.sdf"));
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);  // only the input
}

TEST(Cli, SimSessionRunsAndWritesAReplayableLog) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const Outcome o = RunCli("session " + (dir / "scene.yaml").string() + " --device sim:circle:0.002:0.5 --duration 0.3 " +
                        "--no-realtime --quiet --log " + (dir / "log.csv").string() + " --cache " +
                        (dir / "cache").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("cycles"), std::string::npos) << o.output;
  const std::string log = ReadWholeFile(dir / "log.csv");
  EXPECT_NE(log.find("t,x,y,z,qw,qx,qy,qz,"), std::string::npos);
  EXPECT_GT(std::count(log.begin(), log.end(), '\n'), 200);
  // The log replays as a recorded trajectory through the replay device.
  const Outcome replay = RunCli("session " + (dir / "scene.yaml").string() + " --device replay:" + (dir / "log.csv").string() +
                             " --duration 0.1 --no-realtime --quiet --cache " + (dir / "cache").string());
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
}

TEST(Cli, RunListsJobsOfASweep) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: " << (dir / "scene.yaml").string()
                                  << "\ntrajectory: {type: approach-press, duration: 0.01}\nsweep: {points: [64, 128, 256]}\n";
  const Outcome o = RunCli("run " + (dir / "exp.yaml").string() + " --list-jobs");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("2\tpoints=256"), std::string::npos) << o.output;
  const Outcome bad = RunCli("run " + (dir / "exp.yaml").string() + " --set sweep.pionts=[1]");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("sweep.pionts"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace contactlab
