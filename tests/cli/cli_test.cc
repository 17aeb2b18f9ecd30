// End-to-end checks of the `contactlab` program: exit codes, error messages that name the
// file, no output left behind on failure, and the session and run commands on small scenes.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

// The CSV TEXT without its timing columns (header names ending in "_us"), which differ run to run.
std::string WithoutTimings(const std::string& text) {
  std::vector<bool> keep;
  std::string out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (keep.empty()) {
      for (const std::string& h : cells) keep.push_back(!(h.size() > 3 && h.compare(h.size() - 3, 3, "_us") == 0));
    }
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (c < keep.size() && keep[c]) out += cells[c] + ",";
    }
    out += "\n";
  }
  return out;
}

// --slurm --dry-run writes the scripts; running each array task and then the merge with bash
// (as Slurm's nodes would) gives the summary.csv of a local run, timings aside. With a task's
// results missing, the merge fails naming that task and writes nothing.
TEST(Cli, SlurmScriptsRunByHandMergeToTheLocalRunsSummary) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: scene.yaml\ntrajectory: {type: approach-press, duration: 0.02}"
                                  << "\nsweep: {points: [64, 128, 256]}\n";
  const std::string cache = " --cache " + (dir / "cache").string();
  const Outcome local = RunCli("run " + (dir / "exp.yaml").string() + " --out " + (dir / "local").string() + cache);
  ASSERT_EQ(local.exit_code, 0) << local.output;
  const std::filesystem::path out = dir / "cluster";
  const Outcome dry = RunCli("run " + (dir / "exp.yaml").string() + " --slurm --dry-run --time 5 --out " + out.string() + cache);
  ASSERT_EQ(dry.exit_code, 0) << dry.output;
  EXPECT_NE(dry.output.find("not submitted"), std::string::npos) << dry.output;
  const std::string array = ReadWholeFile(out / "slurm" / "array.sbatch");
  EXPECT_NE(array.find("#SBATCH --array=0-2\n"), std::string::npos) << array;
  EXPECT_NE(array.find("#SBATCH --time=5\n"), std::string::npos) << array;
  EXPECT_FALSE(std::filesystem::exists(out / "summary.csv"));
  for (int task = 2; task >= 0; --task) {
    const std::string cmd = "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash " + (out / "slurm" / "array.sbatch").string() +
                            " > /dev/null 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  // One task's results gone: the merge names it and writes nothing.
  std::filesystem::rename(out / "job-1", dir / "job-1-aside");
  const std::string merge = "bash " + (out / "slurm" / "merge.sbatch").string() + " > " + (dir / "merge.txt").string() + " 2>&1";
  EXPECT_NE(std::system(merge.c_str()), 0);
  const std::string said = ReadWholeFile(dir / "merge.txt");
  EXPECT_NE(said.find("task 1: " + (out / "job-1").string()), std::string::npos) << said;
  EXPECT_FALSE(std::filesystem::exists(out / "summary.csv"));
  // All back: the merge matches the local run.
  std::filesystem::rename(dir / "job-1-aside", out / "job-1");
  ASSERT_EQ(std::system(merge.c_str()), 0) << ReadWholeFile(dir / "merge.txt");
  const std::string summary_local = ReadWholeFile(dir / "local" / "summary.csv");
  EXPECT_EQ(WithoutTimings(ReadWholeFile(out / "summary.csv")), WithoutTimings(summary_local));
  EXPECT_EQ(WithoutTimings(ReadWholeFile(out / "cycles.csv")), WithoutTimings(ReadWholeFile(dir / "local" / "cycles.csv")));
  EXPECT_GT(std::count(summary_local.begin(), summary_local.end(), '\n'), 3);
}

}  // namespace
}  // namespace contactlab
