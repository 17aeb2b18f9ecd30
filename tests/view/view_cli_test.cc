// `contactlab view` end to end: the pages it writes and the errors that name the bad input,
// with no output left behind.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"

namespace contactlab {
namespace {

using testing::TempDir;

using Outcome = testing::CommandOutcome;

// Runs `contactlab ARGS` through the shell after the shell commands PREFIX.
Outcome RunCli(const std::string& args, const std::string& prefix = "") {
  return testing::RunShellCommand(prefix + " " + std::string(CONTACTLAB_CLI) + " " + args);
}

// The shared ball on plate (tests/scene_fixtures.h), coarse: pages of it are quick to make.
const std::string kScene = testing::BallOnPlate{.name = "view-cli", .sphere_subdivisions = 2, .plate_subdivisions = 1,
                                                .points = 256, .resolution = 16, .k_C = 0}
                               .Yaml();

TEST(ViewCli, ScenePageIsOneSelfContainedFile) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const Outcome o = RunCli("view " + (dir / "scene.yaml").string() + " --out " + (dir / "page.html").string() +
                           " --max-points 100 --cache " + (dir / "cache").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string page = ReadWholeFile(dir / "page.html");
  EXPECT_NE(page.find("REVISION=\"111\""), std::string::npos);   // three.js inlined
  EXPECT_NE(page.find("OrbitControls"), std::string::npos);
  EXPECT_NE(page.find("\"pointshell\":{"), std::string::npos);   // the data embedded
  EXPECT_NE(page.find("\"kept\":[50,50]"), std::string::npos) << "not thinned per level";
  EXPECT_NE(page.find("\"total\":[64,192]"), std::string::npos);
  EXPECT_EQ(page.find("<script src"), std::string::npos);         // nothing fetched
  EXPECT_EQ(page.find("@DATA@"), std::string::npos);
}

TEST(ViewCli, ResultsOfSeveralJobsGiveOnePageWithAJobSelectorUnlessJobPicksOne) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: view-jobs\n"
                                     "scene: scene.yaml\n"
                                     "models: [pointshell]\n"
                                     "moving_body: ball\n"
                                     "trajectory: {type: twist, direction: [0, 0, -1], depth: 0.002, angle: 0.4, "
                                     "duration: 0.03}\n"
                                     "reference: ''\n"
                                     "sweep: {k_C: [500, 1500, 2500]}\n";
  const std::string cache = " --cache " + (dir / "cache").string();
  Outcome o = RunCli("run " + (dir / "exp.yaml").string() + " --out " + (dir / "results").string() + cache);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  // No --job: every job, the first shown, a job selector.
  o = RunCli("view " + (dir / "results").string() + " --out " + (dir / "all.html").string() + cache);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("3 jobs (job 0 shown first"), std::string::npos) << o.output;
  const std::string all = ReadWholeFile(dir / "all.html");
  EXPECT_NE(all.find("<select id=\"job\">"), std::string::npos);
  EXPECT_NE(all.find("\"job_data\":["), std::string::npos);
  EXPECT_NE(all.find("\"label\":\"k_C=2500\""), std::string::npos);
  EXPECT_NE(all.find("\"$blob\":"), std::string::npos);
  EXPECT_EQ(all.find("<script src"), std::string::npos);  // still self-contained
  // --job 2: that job alone, no job list.
  o = RunCli("view " + (dir / "results").string() + " --job 2 --out " + (dir / "two.html").string() + cache);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("job 2, 1 model(s)"), std::string::npos) << o.output;
  const std::string two = ReadWholeFile(dir / "two.html");
  EXPECT_EQ(two.find("\"job_data\""), std::string::npos);
  EXPECT_NE(two.find("\"label\":\"k_C=2500\""), std::string::npos);
  // A job the folder does not hold is an error listing those it does.
  o = RunCli("view " + (dir / "results").string() + " --job 5 --out " + (dir / "five.html").string() + cache);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("has no job 5 (it holds 0, 1, 2)"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "five.html"));
}

TEST(ViewCli, BadInputsFailNamingTheFileAndLeaveNoOutput) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string out = " --out " + (dir / "page.html").string() + " --cache " + (dir / "cache").string();
  // A scene that does not exist.
  Outcome o = RunCli("view " + (dir / "absent.yaml").string() + out);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("absent.yaml"), std::string::npos) << o.output;
  // A scene with a bad key.
  std::ofstream(dir / "bad.yaml") << "name: x\nbodies: []\nmodle: {}\n";
  o = RunCli("view " + (dir / "bad.yaml").string() + out);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("bad.yaml"), std::string::npos) << o.output;
  // A folder that is not a results folder.
  std::filesystem::create_directories(dir / "empty");
  o = RunCli("view " + (dir / "empty").string() + out);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find((dir / "empty" / "meta.json").string() + ": not found"), std::string::npos) << o.output;
  // --job with a scene.
  o = RunCli("view " + (dir / "scene.yaml").string() + " --job 1" + out);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("--job"), std::string::npos) << o.output;
  // The output onto the input, or onto a folder.
  o = RunCli("view " + (dir / "scene.yaml").string() + " --out " + (dir / "scene.yaml").string());
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("scene.yaml"), std::string::npos) << o.output;
  EXPECT_EQ(ReadWholeFile(dir / "scene.yaml"), kScene);
  o = RunCli("view " + (dir / "scene.yaml").string() + " --out " + (dir / "empty").string());
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("folder"), std::string::npos) << o.output;
  // A slice position that is not a finite number: an error naming the option, no page.
  for (const char* at : {"nan", "inf", "-inf", "ten"}) {
    o = RunCli("view " + (dir / "scene.yaml").string() + " --slice-at " + at + out);
    EXPECT_NE(o.exit_code, 0) << at;
    EXPECT_NE(o.output.find(std::string("--slice-at: '") + at + "' is not a finite number"), std::string::npos)
        << o.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "page.html")) << at;
  }
  // Too few points for the levels.
  o = RunCli("view " + (dir / "scene.yaml").string() + " --max-points 3" + out);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("--max-points"), std::string::npos) << o.output;
  // three.js missing: the file is named, with the package that provides it.
  o = RunCli("view " + (dir / "scene.yaml").string() + out, "CONTACTLAB_THREEJS_DIR=" + (dir / "nothree").string());
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find((dir / "nothree" / "three.min.js").string() + ": not found"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("libjs-three"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("building"), std::string::npos) << "three.js is checked before any work: " << o.output;
  // A live view on a port that is not one fails before the session builds anything.
  o = RunCli("session " + (dir / "scene.yaml").string() + " --device sim --duration 0.1 --view 70000 --cache " +
             (dir / "cache2").string());
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("--view: 70000 is not a port"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "cache2"));
  // So does --view-wait without --view, or with a count that is not one.
  o = RunCli("session " + (dir / "scene.yaml").string() + " --device sim --duration 0.1 --view-wait --cache " +
             (dir / "cache2").string());
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("--view-wait: needs --view"), std::string::npos) << o.output;
  o = RunCli("session " + (dir / "scene.yaml").string() + " --device sim --duration 0.1 --view --view-wait 0 --cache " +
             (dir / "cache2").string());
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("--view-wait: 0 is not a number of viewers"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "cache2"));
  // No page, and no temporary, was left by any of them.
  EXPECT_FALSE(std::filesystem::exists(dir / "page.html"));
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
  }
}

}  // namespace
}  // namespace contactlab
