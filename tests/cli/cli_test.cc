// End-to-end checks of the `contactlab` program: exit codes, error messages that name the
// file, no output left behind on failure, and the session and run commands on small scenes.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sched.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/data_path.h"

namespace contactlab {
namespace {

using Outcome = testing::CommandOutcome;

// Runs `contactlab ARGS` through the shell, after the shell commands PREFIX (e.g. "cd DIR;").
Outcome RunCliAfter(const std::string& prefix, const std::string& args) {
  return testing::RunShellCommand(prefix + " " + std::string(CONTACTLAB_CLI) + " " + args);
}

Outcome RunCli(const std::string& args) { return RunCliAfter("", args); }

// Shell commands that make every write to a regular file fail beyond 512 bytes, as on a full
// disk (EFBIG instead of ENOSPC; the signal SIGXFSZ is ignored so the write just fails).
const char* kSmallDisk = "trap '' XFSZ; ulimit -f 1;";

int CountFiles(const std::filesystem::path& dir) {
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  return files;
}

const char* kTetrahedron = "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

// The shared ball on plate (tests/scene_fixtures.h), resting 0.5 mm above it.
const std::string kScene = testing::BallOnPlate{.name = "cli-ball-plate"}.Yaml();

// The first COUNT numbers after "KEY": in JSON text (nested arrays read row by row).
std::vector<double> JsonNumbers(const std::string& json, const std::string& key, int count) {
  std::vector<double> v;
  std::size_t at = json.find("\"" + key + "\"");
  if (at == std::string::npos) return v;
  at = json.find(':', at) + 1;
  const char* p = json.c_str() + at;
  while (int(v.size()) < count && *p) {
    while (*p && !(std::isdigit(static_cast<unsigned char>(*p)) || *p == '-')) ++p;
    char* end = nullptr;
    v.push_back(std::strtod(p, &end));
    p = end;
  }
  return v;
}

// The ball 3 mm into the plate (its pointshell on a 1 mm offset surface: R = 21 mm, centre
// H = 18 mm above the plate's top): the force on the plate (B) matches the eq. (2) limit of a
// sphere on a halfspace, |F| = k_C L R (R/3 - H/2 + H^3/(6 R^2)) / (R - H), straight down, and
// the torque about the plate's origin is that force's moment from the contact's centre.
TEST(Cli, ContactPrintsTheForceOnTheFieldBodyAsJson) {
  testing::TempDir dir;
  std::string scene = kScene;
  scene.replace(scene.find("[0, 0, 0.0205, 1, 0, 0, 0]"), 26, "[0.001, -0.002, 0.018, 1, 0, 0, 0]");
  scene.replace(scene.find("{points: 512, levels: 2}"), 24, "{points: 512, levels: 2, offset: 0.001}");
  std::ofstream(dir / "scene.yaml") << scene;
  const Outcome o = RunCli("contact " + (dir / "scene.yaml").string() + " --json --cache " + (dir / "cache").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::vector<double> F = JsonNumbers(o.output, "force", 3), T = JsonNumbers(o.output, "torque", 3);
  const std::vector<double> l = JsonNumbers(o.output, "points_in_contact", 1), K = JsonNumbers(o.output, "K_B", 36);
  ASSERT_EQ(F.size(), 3u) << o.output;
  ASSERT_EQ(T.size(), 3u) << o.output;
  ASSERT_EQ(l.size(), 1u) << o.output;
  ASSERT_EQ(K.size(), 36u) << o.output;
  const double R = 0.021, H = 0.018, kC = 1000, L = 10;
  const double limit = kC * L * R * (R / 3 - H / 2 + H * H * H / (6 * R * R)) / (R - H);
  EXPECT_GE(l[0], L);  // the L/l rule holds: the force is k_C L times the mean depth
  EXPECT_NEAR(F[2], -limit, 0.05 * limit) << o.output;
  EXPECT_LT(std::hypot(F[0], F[1]), 0.05 * limit) << o.output;
  // r x F from the plate's origin (0, 0, -0.01) to the contact (0.001, -0.002, 0).
  const Eigen::Vector3d r(0.001, -0.002, 0.01);
  const Eigen::Vector3d expected = r.cross(Eigen::Vector3d(0, 0, -limit));
  EXPECT_LT((Eigen::Vector3d(T[0], T[1], T[2]) - expected).norm(), 0.15 * r.norm() * limit) << o.output;
  // K_B (row-major), the halfspace rule: -sum k_i N_i N_i^T with A's unit normals N_i and
  // stiffnesses summing to k_C L, so its force block has trace -k_C L; on the cap N_z^2 lies
  // between (H/R)^2 and 1, so dF_z/dz lies between -k_C L and -(H/R)^2 k_C L.
  EXPECT_NEAR(K[0] + K[7] + K[14], -kC * L, 1e-6 * kC * L) << o.output;
  EXPECT_LT(K[14], -(H / R) * (H / R) * kC * L) << o.output;
  EXPECT_GT(K[14], -kC * L) << o.output;
}

// A scene of many bodies (data/scenes/tool-among-parts.yaml): the ball pressed 2 mm into the
// floor and 2 mm against the wall, two brackets off to the side touching each other. `contact
// --json` gives one entry per pair in its model's A/B order; the wrench on the tool is minus the
// sum of the forces on the B of its pairs (it is their A), the brackets' pair stays out of it,
// and the two equal presses push the ball equally up and away from the wall. Under --model fcl
// no body gets more than its mesh. A session runs it live; commands that take two bodies refuse
// it by name.
TEST(Cli, ContactQueriesEveryPairOfASceneOfManyBodies) {
  testing::TempDir dir;
  const std::string cache = " --cache " + (dir / "cache").string();
  const Outcome o = RunCli("contact scenes/tool-among-parts.yaml --json" + cache);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j = nlohmann::json::parse(o.output);
  EXPECT_EQ(j["tool"], "ball");
  ASSERT_EQ(j["pairs"].size(), 5u);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int near = 0;
  for (const nlohmann::json& p : j["pairs"]) {
    near += p["near"].get<bool>();
    const Eigen::Vector3d F(p["force"][0].get<double>(), p["force"][1].get<double>(), p["force"][2].get<double>());
    if (p["bodies"][0] == "ball") sum -= F;
    if (!p["near"].get<bool>()) EXPECT_EQ(F.norm(), 0) << p.dump();
  }
  EXPECT_EQ(j["pairs"][4]["bodies"], nlohmann::json({"bracket-a", "bracket-b"}));
  EXPECT_EQ(j["pairs"][4]["model"], "fcl");
  EXPECT_GT(j["pairs"][4]["points_in_contact"].get<int>(), 0);
  EXPECT_EQ(near, j["pairs_near"].get<int>());
  EXPECT_EQ(near, 3);
  const Eigen::Vector3d F(j["force"][0].get<double>(), j["force"][1].get<double>(), j["force"][2].get<double>());
  EXPECT_LT((F - sum).norm(), 1e-9 * F.norm()) << o.output;
  ASSERT_GT(F.z(), 1.0);
  EXPECT_NEAR(-F.x(), F.z(), 0.05 * F.z());
  EXPECT_LT(std::abs(F.y()), 0.05 * F.z());
  EXPECT_EQ(j["bodies"][1]["built"], nlohmann::json({"mesh", "field"}));
  // Only meshes under FCL.
  const Outcome fcl = RunCli("contact scenes/tool-among-parts.yaml --model fcl" + cache);
  ASSERT_EQ(fcl.exit_code, 0) << fcl.output;
  for (const char* body : {"ball", "floor", "wall", "bracket-a", "bracket-b"}) {
    EXPECT_NE(fcl.output.find("built for " + std::string(body) + ": mesh\n"), std::string::npos) << fcl.output;
  }
  const Outcome pose_a = RunCli("contact scenes/tool-among-parts.yaml --pose-a 0,0,0,1,0,0,0" + cache);
  EXPECT_NE(pose_a.exit_code, 0);
  EXPECT_NE(pose_a.output.find("--pose-tool"), std::string::npos) << pose_a.output;
  // A live session moves the tool among them; --touch places one of two bodies.
  const Outcome session = RunCli("session scenes/tool-among-parts.yaml --device sim:circle:0.005:0.5 --duration 0.3 "
                                 "--no-realtime --quiet" + cache);
  EXPECT_EQ(session.exit_code, 0) << session.output;
  EXPECT_NE(session.output.find("5 bodies, tool ball, 5 pairs, 0 deformable"), std::string::npos) << session.output;
  const Outcome touch = RunCli("session scenes/tool-among-parts.yaml --device sim --duration 0.1 --touch 0.001" + cache);
  EXPECT_NE(touch.exit_code, 0);
  EXPECT_NE(touch.output.find("tool-among-parts.yaml: a scene of many bodies runs without --touch"), std::string::npos)
      << touch.output;
  // body-export finds any of its bodies by name: the wall's mesh, 2 x 20 x 8 cm.
  const Outcome body = RunCli("body-export scenes/tool-among-parts.yaml --body wall --mesh " +
                              (dir / "wall.obj").string() + cache);
  ASSERT_EQ(body.exit_code, 0) << body.output;
  const Outcome missing = RunCli("body-export scenes/tool-among-parts.yaml --body roof --mesh " +
                                 (dir / "roof.obj").string() + cache);
  EXPECT_NE(missing.output.find("no body 'roof'"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("bracket-b)"), std::string::npos) << missing.output;
}

// `contact --contacts --json`: the pointshell model lists one contact per point in contact,
// each on the ball and below the plate at its distance below the plate's top (z = 0), pushing
// the plate down, and k depth normal summed over them is the force printed (eq. (1) with
// k = k_C times the stiffness scale). pressure-field adds areas and pressures whose
// area * pressure * normal sums to its force; a model without a contact list prints null, and
// the text form a table or says so.
TEST(Cli, ContactListsTheContactsAsJsonAndText) {
  testing::TempDir dir;
  std::string scene = kScene;
  scene.replace(scene.find("[0, 0, 0.0205, 1, 0, 0, 0]"), 26, "[0, 0, 0.018, 1, 0, 0, 0]");
  std::ofstream(dir / "scene.yaml") << scene;
  const std::string contact = "contact " + (dir / "scene.yaml").string() + " --cache " + (dir / "cache").string();
  auto vec = [](const nlohmann::json& v) {
    return Eigen::Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  };

  const Outcome o = RunCli(contact + " --contacts --json");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j = nlohmann::json::parse(o.output);
  const nlohmann::json& c = j.at("contacts");
  ASSERT_TRUE(c.is_object()) << o.output;
  const std::size_t n = c.at("points").size();
  EXPECT_EQ(std::int64_t(n), j.at("points_in_contact").get<std::int64_t>());
  ASSERT_GT(n, 0u);
  ASSERT_EQ(c.at("normals").size(), n);
  ASSERT_EQ(c.at("depths").size(), n);
  EXPECT_FALSE(c.contains("areas"));
  const double k = 1000 * j.at("stiffness_scale").get<double>();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = vec(c["points"][i]), normal = vec(c["normals"][i]);
    const double depth = c["depths"][i].get<double>();
    // On the ball's pointshell: its offset surface, half a cell (about 1 mm) outside the 2 cm ball.
    EXPECT_LE((p - Eigen::Vector3d(0, 0, 0.018)).norm(), 0.0225) << i;
    EXPECT_NEAR(depth, -p.z(), 2e-4) << i;
    EXPECT_NEAR(normal.norm(), 1, 1e-6) << i;
    EXPECT_LT(normal.z(), 0) << i;
    sum += k * depth * normal;
  }
  const Eigen::Vector3d F = vec(j.at("force"));
  EXPECT_LT((sum - F).norm(), 1e-5 * F.norm()) << o.output;

  const Outcome pf = RunCli(contact + " --model pressure-field --contacts --json");
  ASSERT_EQ(pf.exit_code, 0) << pf.output;
  const nlohmann::json jp = nlohmann::json::parse(pf.output);
  const nlohmann::json& cp = jp.at("contacts");
  ASSERT_TRUE(cp.contains("areas") && cp.contains("pressures")) << pf.output;
  ASSERT_GT(cp.at("points").size(), 0u);
  Eigen::Vector3d pressed = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < cp.at("points").size(); ++i) {
    pressed += cp["areas"][i].get<double>() * cp["pressures"][i].get<double>() * vec(cp["normals"][i]);
  }
  const Eigen::Vector3d F_p = vec(jp.at("force"));
  EXPECT_LT((pressed - F_p).norm(), 1e-6 * F_p.norm()) << pf.output;

  // A model without a contact list (a reference, built with CGAL): null, and a message as text.
  if (CONTACTLAB_TEST_WITH_CGAL) {
    const Outcome none = RunCli(contact + " --model eq2-halfspace --contacts --json");
    ASSERT_EQ(none.exit_code, 0) << none.output;
    EXPECT_TRUE(nlohmann::json::parse(none.output).at("contacts").is_null()) << none.output;
    const Outcome text_none = RunCli(contact + " --model eq2-halfspace --contacts");
    EXPECT_NE(text_none.output.find("has no contact list"), std::string::npos) << text_none.output;
  }
  // Without --contacts the key is absent.
  EXPECT_FALSE(nlohmann::json::parse(RunCli(contact + " --json").output).contains("contacts"));

  const Outcome text = RunCli(contact + " --contacts");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("contacts: " + std::to_string(n) + " (world frame"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("depth [m]"), std::string::npos) << text.output;
}

// A shipped scene whose bodies start apart (the screwdriver 8 cm from the knight): `contact`
// finds no contact at the scene's poses; `--touch 0.002` moves the knight toward the
// screwdriver until the query sees 2 mm of penetration (to the placement's 1 % bisection), and
// the force on the knight pushes it back along the line it came in on. Moved from --pose-b,
// the knight comes in from that pose's side instead.
TEST(Cli, ContactTouchPutsAShippedSceneThatStartsApartInContact) {
  testing::TempDir dir;
  const std::optional<std::filesystem::path> data = InstalledDataDir();
  ASSERT_TRUE(data.has_value());
  const std::string scene = (*data / "scenes" / "knight-screwdriver.yaml").string();
  const std::string contact = "contact " + scene + " --json --cache " + (dir / "cache").string();
  const Outcome apart = RunCli(contact);
  ASSERT_EQ(apart.exit_code, 0) << apart.output;
  EXPECT_EQ(JsonNumbers(apart.output, "points_in_contact", 1), std::vector<double>{0}) << apart.output;

  const struct {
    std::string option;
    Eigen::Vector3d A_to_B;  // from the screwdriver's origin to the knight's start
  } cases[] = {{"", Eigen::Vector3d(1, 0, 0)}, {" --pose-b 0,0.08,0,1,0,0,0", Eigen::Vector3d(0, 1, 0)}};
  for (const auto& c : cases) {
    const Outcome o = RunCli(contact + " --touch 0.002" + c.option);
    ASSERT_EQ(o.exit_code, 0) << c.option << ": " << o.output;
    const std::vector<double> l = JsonNumbers(o.output, "points_in_contact", 1);
    const std::vector<double> d = JsonNumbers(o.output, "max_penetration", 1), F = JsonNumbers(o.output, "force", 3);
    ASSERT_EQ(l.size(), 1u) << o.output;
    ASSERT_EQ(d.size(), 1u) << o.output;
    ASSERT_EQ(F.size(), 3u) << o.output;
    EXPECT_GT(l[0], 0) << c.option;
    EXPECT_GE(d[0], 0.002 * (1 - 1e-9)) << c.option;
    EXPECT_LE(d[0], 0.002 * 1.02) << c.option;
    const Eigen::Vector3d force(F[0], F[1], F[2]);
    EXPECT_GT(force.dot(c.A_to_B), 0.5 * force.norm()) << c.option << ": " << o.output;
  }

  const Outcome same = RunCli(contact + " --touch 0.002 --pose-b 0,0,0,1,0,0,0");
  EXPECT_EQ(same.exit_code, 1) << same.output;
  EXPECT_NE(same.output.find("--touch: the two bodies' origins coincide"), std::string::npos) << same.output;
  for (const std::string bad : {"--touch 0", "--touch -0.001", "--touch nan"}) {
    const Outcome o = RunCli(contact + " " + bad);
    EXPECT_NE(o.exit_code, 0) << bad;
    EXPECT_NE(o.output.find("--touch"), std::string::npos) << bad << ": " << o.output;
  }
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

// A named pipe stands for a device (as root, /dev/full or /dev/null would have been replaced).
TEST(CliOutputs, OutputOntoASpecialFileIsRefusedBeforeAnyWork) {
  testing::TempDir dir;
  std::ofstream(dir / "tet.obj") << kTetrahedron;
  const auto pipe = dir / "out.sdf";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  const Outcome o = RunCli("sdf " + (dir / "tet.obj").string() + " --resolution 16 --out " + pipe.string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find(pipe.string() + ": --out is a named pipe"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("written to"), std::string::npos) << o.output;
  EXPECT_TRUE(std::filesystem::is_fifo(pipe));
  EXPECT_EQ(CountFiles(dir.path()), 2);
}

TEST(CliOutputs, OutputEqualToTheInputIsRefusedNamingBoth) {
  testing::TempDir dir;
  const auto mesh = dir / "tet.obj";
  std::ofstream(mesh) << kTetrahedron;
  // The same file under another spelling.
  const Outcome o = RunCli("sdf " + mesh.string() + " --resolution 16 --out " + (dir / "." / "tet.obj").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("is the input " + mesh.string()), std::string::npos) << o.output;
  EXPECT_EQ(ReadWholeFile(mesh), kTetrahedron);
  // sdf-eval onto its points file.
  ASSERT_EQ(RunCli("sdf " + mesh.string() + " --resolution 16 --out " + (dir / "tet.sdf").string()).exit_code, 0);
  const std::string points = "x,y,z\n0.01,0.01,0.01\n";
  std::ofstream(dir / "points.csv") << points;
  const Outcome eval = RunCli("sdf-eval " + (dir / "tet.sdf").string() + " --points " + (dir / "points.csv").string() +
                              " --out " + (dir / "points.csv").string());
  EXPECT_EQ(eval.exit_code, 1) << eval.output;
  EXPECT_NE(eval.output.find("is the input"), std::string::npos) << eval.output;
  EXPECT_EQ(ReadWholeFile(dir / "points.csv"), points);
}

// A named pipe nobody writes to: opening it for reading would block forever.
TEST(CliInputs, NamedPipeInputIsRefusedWithoutBlocking) {
  testing::TempDir dir;
  const auto pipe = dir / "field.sdf";
  ASSERT_EQ(::mkfifo(pipe.c_str(), 0600), 0);
  std::ofstream(dir / "p.csv") << "0,0,0\n";
  Outcome o = RunCliAfter("timeout 60", "sdf-eval " + pipe.string() + " --points " + (dir / "p.csv").string() +
                                            " --out " + (dir / "d.csv").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("is a named pipe, not a file"), std::string::npos) << o.output;
  const auto mesh_pipe = dir / "mesh.obj";
  ASSERT_EQ(::mkfifo(mesh_pipe.c_str(), 0600), 0);
  o = RunCliAfter("timeout 60", "mesh-info " + mesh_pipe.string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("is a named pipe"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("not found"), std::string::npos) << o.output;
}

TEST(CliInputs, UnparsableFirstPointsRowIsAnErrorNotAHeader) {
  testing::TempDir dir;
  const auto mesh = dir / "tet.obj";
  std::ofstream(mesh) << kTetrahedron;
  ASSERT_EQ(RunCli("sdf " + mesh.string() + " --resolution 16 --out " + (dir / "tet.sdf").string()).exit_code, 0);
  std::ofstream(dir / "p.csv") << "1;2;3\n4;5;6\n";
  const Outcome o = RunCli("sdf-eval " + (dir / "tet.sdf").string() + " --points " + (dir / "p.csv").string() +
                           " --out " + (dir / "d.csv").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("p.csv:1:"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "d.csv"));
}

TEST(CliInputs, NegativeBudgetOnTheCommandLineIsRejectedLikeInTheScene) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const Outcome o = RunCli("contact " + (dir / "scene.yaml").string() + " --no-cache --budget -1");
  EXPECT_NE(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("--budget"), std::string::npos) << o.output;
}

// `session --duration nan` ran for ever and `--k-vc nan`, `--touch nan` fell back to the
// defaults: the program refuses each before the session starts (exit 105, a CLI11 validation
// error naming the option); an over-long duration is refused naming its limit.
TEST(CliInputs, NanDurationCouplingOrTouchIsRefusedBeforeTheSessionStarts) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string session = "session " + (dir / "scene.yaml").string() + " --no-realtime --quiet ";
  for (const std::string option : {"--duration nan", "--k-vc nan", "--touch nan", "--duration inf", "--k-vc=-inf"}) {
    const Outcome o = RunCli(session + option);
    EXPECT_EQ(o.exit_code, 105) << option << ": " << o.output;
    EXPECT_NE(o.output.find(option.substr(0, option.find_first_of(" =")) + ": '"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("is not a finite number"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("session: scene"), std::string::npos) << o.output;
  }
  const Outcome huge = RunCli(session + "--duration 1e300");
  EXPECT_EQ(huge.exit_code, 105) << huge.output;
  EXPECT_NE(huge.output.find("--duration"), std::string::npos) << huge.output;
}

// The session loop runs at the scene's rate, 1 / model.cycle_seconds, and --rate sets both;
// a cycle that gives no rate in [10 Hz, 100 kHz] is refused naming the scene file and the key, a
// --rate outside it naming the option, before the session starts.
TEST(CliSession, TheLoopRunsAtTheScenesCycleOrAtTheRateAsked) {
  testing::TempDir dir;
  std::string scene = kScene;
  const std::string model = "model: {k_C: 1000}";
  ASSERT_NE(scene.find(model), std::string::npos);
  scene.replace(scene.find(model), model.size(), "model: {k_C: 1000, cycle_seconds: 0.0005}");
  std::ofstream(dir / "scene.yaml") << scene;
  const std::string session = "session " + (dir / "scene.yaml").string() + " --device sim --duration 0.1 --no-realtime --quiet";
  const Outcome own = RunCli(session);
  ASSERT_EQ(own.exit_code, 0) << own.output;
  EXPECT_NE(own.output.find("0.1 s at 2000 Hz"), std::string::npos) << own.output;
  EXPECT_NE(own.output.find("rate 2000 Hz (period 500 us"), std::string::npos) << own.output;
  const Outcome asked = RunCli(session + " --rate 5000");
  ASSERT_EQ(asked.exit_code, 0) << asked.output;
  EXPECT_NE(asked.output.find("rate 5000 Hz (period 200 us, spin 50 us"), std::string::npos) << asked.output;
  const Outcome fast = RunCli(session + " --rate 40000");
  ASSERT_EQ(fast.exit_code, 0) << fast.output;
  EXPECT_NE(fast.output.find("rate 40000 Hz (period 25 us, spin 12.5 us"), std::string::npos) << fast.output;

  std::string tiny = kScene;
  tiny.replace(tiny.find(model), model.size(), "model: {k_C: 1000, cycle_seconds: 1e-6}");
  std::ofstream(dir / "tiny.yaml") << tiny;
  const Outcome refused = RunCli("session " + (dir / "tiny.yaml").string() + " --duration 0.1 --no-realtime --quiet");
  EXPECT_NE(refused.exit_code, 0) << refused.output;
  EXPECT_NE(refused.output.find("tiny.yaml:"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("model.cycle_seconds"), std::string::npos) << refused.output;
  EXPECT_EQ(refused.output.find("session: scene"), std::string::npos) << refused.output;
  // A cycle slower than 10 Hz (10 s once ran a session of no cycles) is refused at its key, and
  // a --duration shorter than one cycle naming the option.
  std::string slow = kScene;
  slow.replace(slow.find(model), model.size(), "model: {k_C: 1000, cycle_seconds: 10}");
  std::ofstream(dir / "slow.yaml") << slow;
  const Outcome too_slow = RunCli("session " + (dir / "slow.yaml").string() + " --duration 1 --no-realtime --quiet");
  EXPECT_NE(too_slow.exit_code, 0) << too_slow.output;
  EXPECT_NE(too_slow.output.find("slow.yaml"), std::string::npos) << too_slow.output;
  EXPECT_NE(too_slow.output.find("cycle_seconds"), std::string::npos) << too_slow.output;
  EXPECT_EQ(too_slow.output.find("session: scene"), std::string::npos) << too_slow.output;
  const Outcome too_short =
      RunCli("session " + (dir / "scene.yaml").string() + " --device sim --rate 10 --duration 0.05 --no-realtime --quiet");
  EXPECT_NE(too_short.exit_code, 0) << too_short.output;
  EXPECT_NE(too_short.output.find("--duration: 0.05 s is shorter than one haptic cycle"), std::string::npos)
      << too_short.output;
  const Outcome budgeted = RunCli(session + " --rate 5000 --budget 64");
  EXPECT_EQ(budgeted.exit_code, 0) << budgeted.output;
  const Outcome negative = RunCli(session + " --budget -1");
  EXPECT_EQ(negative.exit_code, 105) << negative.output;
  EXPECT_NE(negative.output.find("--budget"), std::string::npos) << negative.output;
  for (const std::string bad : {"0", "200000", "nan", "-1000"}) {
    const Outcome o = RunCli(session + " --rate " + bad);
    EXPECT_EQ(o.exit_code, 105) << bad << ": " << o.output;
    EXPECT_NE(o.output.find("--rate"), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("session: scene"), std::string::npos) << o.output;
  }
}

TEST(CliInputs, TooManyLevelsIsRefusedNamingTheLimit) {
  testing::TempDir dir;
  std::ofstream(dir / "tet.obj") << kTetrahedron;
  const Outcome o = RunCli("pointshell " + (dir / "tet.obj").string() + " --points 64 --levels 100 --out " +
                           (dir / "tet.ps").string());
  EXPECT_NE(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("--levels"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("-9223372036854775808"), std::string::npos) << o.output;
}

TEST(CliOutputs, SessionLogOntoAFolderFailsBeforeTheSession) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::filesystem::create_directory(dir / "logs");
  const Outcome o = RunCli("session " + (dir / "scene.yaml").string() + " --device sim --duration 5 --no-realtime " +
                           "--quiet --log " + (dir / "logs").string() + " --cache " + (dir / "cache").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find((dir / "logs").string() + ": --log is a folder"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("session: scene"), std::string::npos) << o.output;  // it never started
  EXPECT_FALSE(std::filesystem::exists(dir / "cache"));                       // nor built anything
}

TEST(CliOutputs, FailedSessionLogWriteLeavesNoTemporary) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string cache = " --cache " + (dir / "cache").string();
  ASSERT_EQ(RunCli("contact " + (dir / "scene.yaml").string() + cache).exit_code, 0);  // fills the cache
  const Outcome o = RunCliAfter(kSmallDisk, "session " + (dir / "scene.yaml").string() +
                                                " --device sim --duration 0.3 --no-realtime --quiet --log " +
                                                (dir / "log.csv").string() + cache);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find((dir / "log.csv").string()), std::string::npos) << o.output;
  EXPECT_EQ(CountFiles(dir.path()), 2) << "scene.yaml and cache/ only";
}

TEST(CliOutputs, RunOutOntoAFileFailsBeforeAnyJob) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: scene.yaml\n" << testing::PressTrajectoryYaml(0.01) << "\n";
  std::ofstream(dir / "taken") << "x";
  const Outcome o = RunCli("run " + (dir / "exp.yaml").string() + " --out " + (dir / "taken").string() + " --cache " +
                           (dir / "cache").string());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find((dir / "taken").string() + ": --out is a file, not a folder"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "cache"));  // no job ran
}

TEST(CliOutputs, RunNameThatIsAPathIsRefused) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir / "a" / "b");
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: ../../x\nscene: scene.yaml\n"
                                  << testing::PressTrajectoryYaml(0.01) << "\n";
  const Outcome o = RunCliAfter("cd " + (dir / "a" / "b").string() + " &&",
                                "run " + (dir / "exp.yaml").string() + " --no-cache");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("name: must be a plain name"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "a" / "x"));  // results/../../x from a/b
}

TEST(CliOutputs, FailedRunLeavesNoEmptyResultsFolder) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: scene.yaml\n" << testing::PressTrajectoryYaml(0.02) << "\n";
  const Outcome o = RunCliAfter(std::string("cd ") + dir.path().string() + " && " + kSmallDisk, "run exp.yaml --no-cache");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("cycles.csv"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "results")) << o.output;
}

TEST(Cli, SimSessionRunsAndWritesAReplayableLog) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const Outcome o = RunCli("session " + (dir / "scene.yaml").string() + " --device sim:circle:0.002:0.5 --duration 0.3 " +
                        "--no-realtime --quiet --log " + (dir / "log.csv").string() + " --cache " +
                        (dir / "cache").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  // One row per cycle the loop ran and the consumer did not drop: however many cycles 0.3 s of
  // a loaded machine gave, every one of them is in the log (at least the two a replay needs).
  const std::size_t at_cycles = o.output.find("\ncycles ");
  const std::size_t at_dropped = o.output.find("records dropped by the log consumer: ");
  ASSERT_NE(at_cycles, std::string::npos) << o.output;
  ASSERT_NE(at_dropped, std::string::npos) << o.output;
  const long long cycles = std::atoll(o.output.c_str() + at_cycles + std::strlen("\ncycles "));
  const long long dropped =
      std::atoll(o.output.c_str() + at_dropped + std::strlen("records dropped by the log consumer: "));
  const std::string log = ReadWholeFile(dir / "log.csv");
  EXPECT_EQ(log.rfind("# contactlab session log:", 0), 0u);
  EXPECT_NE(log.find("\nt,x,y,z,qw,qx,qy,qz,"), std::string::npos);
  const long long rows = std::count(log.begin(), log.end(), '\n') - 2;  // less the comment and the header
  EXPECT_EQ(rows, cycles - dropped) << o.output;
  ASSERT_GE(rows, 2) << o.output;
  // The log replays as a recorded trajectory through the replay device.
  const Outcome replay = RunCli("session " + (dir / "scene.yaml").string() + " --device replay:" + (dir / "log.csv").string() +
                             " --duration 0.1 --no-realtime --quiet --cache " + (dir / "cache").string());
  EXPECT_EQ(replay.exit_code, 0) << replay.output;
}

// udp:0 binds a port the system picks: the session must say which, or no device can reach it.
TEST(Cli, UdpSessionOnAPickedPortPrintsThePort) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const Outcome o = RunCli("session " + (dir / "scene.yaml").string() + " --device udp:0 --duration 0.2 " +
                           "--no-realtime --quiet --cache " + (dir / "cache").string());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::size_t at = o.output.find("device: udp on 127.0.0.1:");
  ASSERT_NE(at, std::string::npos) << o.output;
  const int port = std::atoi(o.output.c_str() + at + std::strlen("device: udp on 127.0.0.1:"));
  EXPECT_GT(port, 0) << o.output;
  EXPECT_NE(o.output.find("coherence resets"), std::string::npos) << o.output;
}

// --cpu that is no CPU of the machine is refused before the session, naming the option; a good
// one pins the loop and says so, and the report splits the misses.
TEST(Cli, SessionCpuOptionIsCheckedAndPinsTheLoop) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string session = "session " + (dir / "scene.yaml").string() + " --device sim --duration 0.2 " +
                              "--no-realtime --quiet --cache " + (dir / "cache").string();
  for (const std::string bad : {"-1", "100000", "one"}) {
    const Outcome o = RunCli(session + " --cpu " + bad);
    EXPECT_EQ(o.exit_code, 1) << o.output;
    EXPECT_NE(o.output.find("--cpu: "), std::string::npos) << o.output;
    EXPECT_EQ(o.output.find("session: scene"), std::string::npos) << o.output;  // refused before it started
  }
  const Outcome free = RunCli(session);
  ASSERT_EQ(free.exit_code, 0) << free.output;
  EXPECT_NE(free.output.find(" (overrun "), std::string::npos) << free.output;
  // Pinning needs a second CPU for the other threads (sched_getaffinity of this process).
  cpu_set_t set;
  CPU_ZERO(&set);
  ASSERT_EQ(sched_getaffinity(0, sizeof(set), &set), 0);
  if (CPU_COUNT(&set) < 2) GTEST_SKIP() << "one CPU: --cpu has no core to leave to the other threads";
  int last = CPU_SETSIZE - 1;
  while (!CPU_ISSET(last, &set)) --last;
  const Outcome pinned = RunCli(session + " --cpu " + std::to_string(last));
  ASSERT_EQ(pinned.exit_code, 0) << pinned.output;
  EXPECT_NE(pinned.output.find("cpu: loop thread pinned to CPU " + std::to_string(last)), std::string::npos)
      << pinned.output;
  EXPECT_NE(pinned.output.find("pinned to CPU " + std::to_string(last) + "\n"), std::string::npos) << pinned.output;
}

TEST(Cli, RunListsJobsOfASweep) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: " << (dir / "scene.yaml").string()
                                  << "\n" << testing::PressTrajectoryYaml(0.01) << "\nsweep: {points: [64, 128, 256]}\n";
  const Outcome o = RunCli("run " + (dir / "exp.yaml").string() + " --list-jobs");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("2\tpoints=256"), std::string::npos) << o.output;
  const Outcome bad = RunCli("run " + (dir / "exp.yaml").string() + " --set sweep.pionts=[1]");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.output.find("sweep.pionts"), std::string::npos) << bad.output;
}

// A config's mistakes are named where they were written: an unknown --profile lists the
// config's profiles; a misspelled model (in the config's models, a swept models list, the
// reference, or the scene's own models list) fails --list-jobs naming the file and line of the
// list that holds it, the config's never blamed on the scene; and `contact` given a config says
// to use `run` instead of calling its keys unknown scene keys.
TEST(CliConfigs, MistakesAreNamedInTheFileThatHoldsThem) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string base = "name: e\ndescription: two models pressed\nscene: scene.yaml\n" +
                           testing::PressTrajectoryYaml(0.01) + "\n";
  auto run = [&](const std::string& config, const std::string& options) {
    std::ofstream(dir / "exp.yaml") << config;
    return RunCli("run " + (dir / "exp.yaml").string() + " " + options);
  };
  const std::string config = (dir / "exp.yaml").string(), scene = (dir / "scene.yaml").string();

  const Outcome profile = run(base + "profiles:\n  quick: {sweep.points: [64]}\n  paper: {sweep.points: [256]}\n",
                              "--profile papr --list-jobs");
  EXPECT_EQ(profile.exit_code, 1) << profile.output;
  EXPECT_NE(profile.output.find(config + ": has no profile 'papr' (under 'profiles'); its profiles: quick, paper"),
            std::string::npos) << profile.output;
  const Outcome none = run(base, "--profile paper --list-jobs");
  EXPECT_EQ(none.exit_code, 1) << none.output;
  EXPECT_NE(none.output.find("it has no profiles"), std::string::npos) << none.output;

  // The models list is line 4 of the config, after name, description and scene.
  const std::string models = "name: e\ndescription: two models\nscene: scene.yaml\nmodels: [pointshell, pointshel-linear]\n" +
                             testing::PressTrajectoryYaml(0.01) + "\n";
  const Outcome model = run(models, "--list-jobs");
  EXPECT_EQ(model.exit_code, 1) << model.output;
  EXPECT_NE(model.output.find(config + ":4: models[1]: unknown contact model 'pointshel-linear' (known: "),
            std::string::npos) << model.output;
  EXPECT_EQ(model.output.find(scene), std::string::npos) << model.output;
  const Outcome swept = run(base + "sweep:\n  model:\n    - pointshell\n    - fcll\n", "--list-jobs");
  EXPECT_EQ(swept.exit_code, 1) << swept.output;
  EXPECT_NE(swept.output.find(config + ":8: sweep.model[1]: unknown contact model 'fcll'"), std::string::npos)
      << swept.output;
  EXPECT_EQ(swept.output.find(scene), std::string::npos) << swept.output;
  const Outcome reference = run(base + "reference: pointshell-lineer\n", "--list-jobs");
  EXPECT_EQ(reference.exit_code, 1) << reference.output;
  EXPECT_NE(reference.output.find(config + ":5: reference: unknown contact model 'pointshell-lineer'"),
            std::string::npos) << reference.output;  // line 5: after name, description, scene, trajectory

  // A misspelled model in the scene's own list is the scene's.
  std::ofstream(dir / "scene.yaml") << kScene << "models: [pointshell, vsp]\n";
  const Outcome scene_model = run(base, "--list-jobs");
  EXPECT_EQ(scene_model.exit_code, 1) << scene_model.output;
  EXPECT_NE(scene_model.output.find(scene + ": models: unknown contact model 'vsp'"), std::string::npos)
      << scene_model.output;
  std::ofstream(dir / "scene.yaml") << kScene;
  EXPECT_EQ(run(base, "--list-jobs").exit_code, 0);

  const Outcome contact = RunCli("contact " + config + " --no-cache");
  EXPECT_EQ(contact.exit_code, 1) << contact.output;
  EXPECT_NE(contact.output.find(config + ": this is an experiment config"), std::string::npos) << contact.output;
  EXPECT_NE(contact.output.find("use `contactlab run " + config + "`"), std::string::npos) << contact.output;
  EXPECT_EQ(contact.output.find("unknown key"), std::string::npos) << contact.output;
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
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: scene.yaml\n" << testing::PressTrajectoryYaml(0.02)
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
  // A task killed while writing (its cycles.csv cut mid-row): the merge fails naming its folder.
  const std::string cut = ReadWholeFile(out / "job-2" / "cycles.csv");
  std::filesystem::remove(out / "summary.csv");
  std::ofstream(out / "job-2" / "cycles.csv", std::ios::binary | std::ios::trunc) << cut.substr(0, cut.size() / 2);
  EXPECT_NE(std::system(merge.c_str()), 0);
  const std::string said_cut = ReadWholeFile(dir / "merge.txt");
  EXPECT_NE(said_cut.find((out / "job-2" / "cycles.csv").string()), std::string::npos) << said_cut;
  EXPECT_FALSE(std::filesystem::exists(out / "summary.csv"));
}

// Two single-job runs of a two-point sweep, for the merge checks.
struct TwoJobRuns {
  testing::TempDir dir;
  TwoJobRuns() {
    std::ofstream(dir / "scene.yaml") << kScene;
    std::ofstream(dir / "exp.yaml") << "name: e\nscene: scene.yaml\n" << testing::PressTrajectoryYaml(0.02)
                                    << "\nsweep: {points: [64, 128]}\n";
    for (int job : {0, 1}) {
      const Outcome o = RunCli("run " + (dir / "exp.yaml").string() + " --job " + std::to_string(job) + " --out " +
                               (dir / ("f" + std::to_string(job))).string() + " --cache " + (dir / "cache").string());
      EXPECT_EQ(o.exit_code, 0) << o.output;
    }
  }
  std::string Merge(const std::string& folders, const std::string& out, const std::string& more = "") const {
    std::string args = "merge";
    std::istringstream names(folders);
    for (std::string f; names >> f;) args += " " + (dir / f).string();
    return args + " --out " + (dir / out).string() + more;
  }
  void CopyFolder(const std::string& from, const std::string& to) const {
    std::filesystem::copy(dir / from, dir / to, std::filesystem::copy_options::recursive);
  }
};

// A job's cycles.csv cut short (mid-row, as by `head -c 3000`, or at a line break): the merge
// fails naming the file and writes nothing, where it used to write a file the viewer rejects.
TEST(CliMerge, ACutShortTableIsRefusedNamingItsFile) {
  TwoJobRuns runs;
  const std::filesystem::path& dir = runs.dir.path();
  runs.CopyFolder("f1", "f1t");
  const std::string cycles = ReadWholeFile(dir / "f1" / "cycles.csv");
  ASSERT_GT(cycles.size(), 3000u);
  std::ofstream(dir / "f1t" / "cycles.csv", std::ios::binary | std::ios::trunc) << cycles.substr(0, 3000);
  Outcome o = RunCli(runs.Merge("f0 f1t", "mt"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find((dir / "f1t" / "cycles.csv").string()), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "mt"));
  // Cut at a line break: every row well formed, but fewer than meta.json counted.
  const std::size_t last_row = cycles.rfind('\n', cycles.size() - 2);
  std::ofstream(dir / "f1t" / "cycles.csv", std::ios::binary | std::ios::trunc) << cycles.substr(0, last_row + 1);
  o = RunCli(runs.Merge("f0 f1t", "mt"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find((dir / "f1t" / "cycles.csv").string() + ": "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("meta.json counted"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "mt"));
  // The intact folders merge, and the viewer replays the merged job.
  o = RunCli(runs.Merge("f0 f1", "m"));
  ASSERT_EQ(o.exit_code, 0) << o.output;
  o = RunCli("view " + (dir / "m").string() + " --job 1 --out " + (dir / "x.html").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "x.html"));
}

// The merge trusted meta.json's integers: a job index of 2^32 read as 0 (the merged meta.json
// said jobs [0, 1] while every row was job 1), sweep_jobs of 2^32 + 5 as 5, and a cycles.csv
// whose job column disagreed with its meta.json merged silently. Each is refused naming the
// file, and nothing is written.
TEST(CliMerge, JobNumbersPastTheSweepBoundOrDisagreeingWithTheTablesAreRefused) {
  TwoJobRuns runs;
  const std::filesystem::path& dir = runs.dir.path();
  auto edit_meta = [&](const std::string& folder, const std::string& from, const std::string& to) {
    std::string meta = ReadWholeFile(dir / folder / "meta.json");
    const std::size_t at = meta.find(from);
    ASSERT_NE(at, std::string::npos) << from << " not in " << meta;
    std::ofstream(dir / folder / "meta.json", std::ios::binary | std::ios::trunc) << meta.replace(at, from.size(), to);
  };
  runs.CopyFolder("f0", "big");
  edit_meta("big", "\"jobs\": [\n    0\n  ]", "\"jobs\": [\n    4294967296\n  ]");
  Outcome o = RunCli(runs.Merge("big f1", "m1"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find((dir / "big" / "meta.json").string() + ": jobs holds 4294967296, not a job number"),
            std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "m1"));
  runs.CopyFolder("f0", "total");
  edit_meta("total", "\"sweep_jobs\": 2", "\"sweep_jobs\": 4294967301");
  o = RunCli(runs.Merge("total f1", "m2"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("sweep_jobs holds 4294967301"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "m2"));
  runs.CopyFolder("f0", "other");
  edit_meta("other", "\"jobs\": [\n    0\n  ]", "\"jobs\": [\n    1\n  ]");
  o = RunCli(runs.Merge("other", "m3", " --partial"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("is none of the jobs its meta.json lists"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "m3"));
}

// A negative --job is named as such, not taken for "no --job" (which replays every job, with a
// job selector in the page).
TEST(CliMerge, ANegativeJobIsNotAJobIndex) {
  TwoJobRuns runs;
  const std::filesystem::path& dir = runs.dir.path();
  ASSERT_EQ(RunCli(runs.Merge("f0 f1", "m")).exit_code, 0);
  Outcome o = RunCli("view " + (dir / "m").string() + " --job -1 --out " + (dir / "x.html").string());
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("--job: -1 is not a job index (jobs count from 0)"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("choose one with --job"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "x.html"));
  o = RunCli("view " + (dir / "m").string() + " --out " + (dir / "x.html").string());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("2 jobs (job 0 shown first"), std::string::npos) << o.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "x.html"));
}

// The same job twice, a job of the sweep missing, and a job of another config are refused
// (naming the folder); --partial merges some of a sweep.
TEST(CliMerge, DuplicateMissingAndForeignJobsAreRefused) {
  TwoJobRuns runs;
  const std::filesystem::path& dir = runs.dir.path();
  Outcome o = RunCli(runs.Merge("f0 f0", "m00"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("holds job 0, which an earlier folder holds too"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "m00"));

  o = RunCli(runs.Merge("f1", "m1"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("the sweep has 2 jobs and 1 of them are in none of the folders (0)"), std::string::npos)
      << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "m1"));
  o = RunCli(runs.Merge("f1", "m1", " --partial"));
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(ReadWholeFile(dir / "m1" / "meta.json").find("\"partial\": true"), std::string::npos);

  // Job 1 of the sweep under another config value.
  const Outcome other = RunCli("run " + (dir / "exp.yaml").string() + " --job 1 --set trajectory.depth=0.001 --out " +
                               (dir / "g1").string() + " --cache " + (dir / "cache").string());
  ASSERT_EQ(other.exit_code, 0) << other.output;
  o = RunCli(runs.Merge("f0 g1", "mg"));
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find((dir / "g1" / "meta.json").string() + ": was run with another config"), std::string::npos)
      << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "mg"));
}

}  // namespace
}  // namespace contactlab

namespace contactlab {
namespace {

// A small deformable beam (body A) under a probe, for the commands that take reduced coordinates.
const char* kBeamScene = R"(name: cli-beam
bodies:
  - name: beam
    mesh: "box:0.1,0.01,0.01,4"
    role: pointshell
    pointshell: {points: 512, levels: 3}
    field: {resolution: 48}
    deformable: {model: stvk, modes: 4, cells: 16, E: 5.0e7, nu: 0.3, rho: 1100, anchor: {below: [x, -0.09]}}
  - name: probe
    mesh: "sphere:0.01,2"
    pose: [0.07, 0, 0.0195, 1, 0, 0, 0]
    role: field
    field: {resolution: 24}
model: {k_C: 1000}
)";

std::vector<std::vector<double>> ReadNumbers(const std::filesystem::path& file, char separator, bool header) {
  std::istringstream in(ReadWholeFile(file));
  std::vector<std::vector<double>> rows;
  std::string line;
  if (header) std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, separator);) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

TEST(CliDeformable, ContactAtQAndBodyExportAreConsistentAndBadQIsRefused) {
  testing::TempDir dir;
  std::ofstream(dir / "beam.yaml") << kBeamScene;
  const std::string scene = (dir / "beam.yaml").string() + " --cache " + (dir / "cache").string();
  // At q = 0 the wrench is the rigid one; the reduced force has r entries.
  const Outcome rest = RunCli("contact " + scene + " --json");
  const Outcome zero = RunCli("contact " + scene + " --json --q-a 0,0,0,0");
  ASSERT_EQ(zero.exit_code, 0) << zero.output;
  const auto force_of = [](const std::string& out) { return out.substr(out.find("\"force\"")); };
  EXPECT_EQ(force_of(rest.output).substr(0, 80), force_of(zero.output).substr(0, 80));
  EXPECT_NE(zero.output.find("\"reduced_force_A\""), std::string::npos) << zero.output;

  // The exported mesh is linear in q: the mean of +q and -q is the rest mesh.
  ASSERT_EQ(RunCli("body-export " + scene + " --body beam --mesh " + (dir / "rest.obj").string()).exit_code, 0);
  std::ofstream(dir / "q.csv") << "# q\n0.02, -0.01\n0.005 0.001\n";
  std::ofstream(dir / "mq.csv") << "-0.02,0.01,-0.005,-0.001\n";
  ASSERT_EQ(RunCli("body-export " + scene + " --body beam --q @" + (dir / "q.csv").string() + " --mesh " +
                   (dir / "plus.obj").string()).exit_code, 0);
  ASSERT_EQ(RunCli("body-export " + scene + " --body beam --q @" + (dir / "mq.csv").string() + " --mesh " +
                   (dir / "minus.obj").string()).exit_code, 0);
  const auto vertices = [](const std::filesystem::path& f) {
    std::vector<Eigen::Vector3d> v;
    std::istringstream in(ReadWholeFile(f));
    for (std::string tag; in >> tag;) {
      if (tag == "v") {
        Eigen::Vector3d p;
        in >> p.x() >> p.y() >> p.z();
        v.push_back(p);
      } else {
        std::string rest_of_line;
        std::getline(in, rest_of_line);
      }
    }
    return v;
  };
  const auto r0 = vertices(dir / "rest.obj"), rp = vertices(dir / "plus.obj"), rm = vertices(dir / "minus.obj");
  ASSERT_EQ(r0.size(), rp.size());
  ASSERT_EQ(r0.size(), rm.size());
  double moved = 0;
  for (std::size_t i = 0; i < r0.size(); ++i) {
    EXPECT_LT((0.5 * (rp[i] + rm[i]) - r0[i]).norm(), 1e-6);
    moved = std::max(moved, (rp[i] - r0[i]).norm());
  }
  EXPECT_GT(moved, 1e-4);

  // The exported BD-tree radii at q contain every point of each node's subtree.
  ASSERT_EQ(RunCli("body-export " + scene + " --body beam --q @" + (dir / "q.csv").string() + " --pointshell " +
                   (dir / "ps.csv").string()).exit_code, 0);
  const auto rows = ReadNumbers(dir / "ps.csv", ',', true);
  ASSERT_GT(rows.size(), 512u);
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 9u);
    const Eigen::Vector3d x(row[0], row[1], row[2]);
    EXPECT_NEAR(Eigen::Vector3d(row[3], row[4], row[5]).norm(), 1.0, 1e-5);
    for (int p = int(row[7]); p >= 0; p = int(rows[p][7])) {
      EXPECT_LE((x - Eigen::Vector3d(rows[p][0], rows[p][1], rows[p][2])).norm(), rows[p][8] * (1 + 1e-6) + 1e-9);
    }
  }

  // Bad q: an error naming the argument, exit 1, no output written.
  const Outcome count = RunCli("contact " + scene + " --q-a 1,2");
  EXPECT_EQ(count.exit_code, 1);
  EXPECT_NE(count.output.find("--q-a (body 'beam'): 2 values given; the body has r = 4"), std::string::npos)
      << count.output;
  const Outcome nan = RunCli("contact " + scene + " --q-a 0,nan,0,0");
  EXPECT_EQ(nan.exit_code, 1);
  EXPECT_NE(nan.output.find("value 2 'nan' is not a finite number"), std::string::npos) << nan.output;
  const Outcome rigid = RunCli("body-export " + scene + " --body probe --q 1 --mesh " + (dir / "no.obj").string());
  EXPECT_EQ(rigid.exit_code, 1);
  EXPECT_NE(rigid.output.find("--q (body 'probe'): the body is rigid"), std::string::npos) << rigid.output;
  const Outcome unknown = RunCli("body-export " + scene + " --body nobody --mesh " + (dir / "no.obj").string());
  EXPECT_EQ(unknown.exit_code, 1);
  EXPECT_NE(unknown.output.find("no body 'nobody'"), std::string::npos) << unknown.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "no.obj"));

  // A device session couples the deformable body; its log gains the step time and |q|.
  const Outcome session = RunCli("session " + scene + " --device sim --duration 0.3 --no-realtime --quiet --log " +
                                 (dir / "session.csv").string());
  ASSERT_EQ(session.exit_code, 0) << session.output;
  EXPECT_NE(session.output.find("beam deformable, r = 4"), std::string::npos) << session.output;
  EXPECT_NE(ReadWholeFile(dir / "session.csv").find(",step_us,q_norm,q_norm_body,cpu_us\n"), std::string::npos);
}

// Finite coordinates whose deformation overflows (q = 1e308: positions inf) are an input error
// naming the option, in every command that takes them; nothing is written.
TEST(CliDeformable, CoordinatesWhoseDeformationOverflowsAreRefusedNamingTheOption) {
  testing::TempDir dir;
  std::ofstream(dir / "beam.yaml") << kBeamScene;
  std::ofstream(dir / "p.csv") << "x,y,z\n0,0,0\n0.05,0,0\n";
  const std::string scene = (dir / "beam.yaml").string() + " --cache " + (dir / "cache").string();
  const std::string huge = "1e308,1e308,1e308,1e308";
  const std::string said = "(body 'beam'): these coordinates deform the body beyond finite numbers";
  Outcome o = RunCli("body-export " + scene + " --body beam --q " + huge + " --mesh " + (dir / "o.obj").string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--q " + said), std::string::npos) << o.output;
  o = RunCli("body-export " + scene + " --body beam --q " + huge + " --pointshell " + (dir / "o.csv").string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--q " + said), std::string::npos) << o.output;
  o = RunCli("body-eval " + scene + " --body beam --q " + huge + " --points " + (dir / "p.csv").string() + " --out " +
             (dir / "d.csv").string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--q " + said), std::string::npos) << o.output;
  o = RunCli("contact " + scene + " --q-a " + huge);
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--q-a " + said), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("force on"), std::string::npos) << o.output;
  for (const char* f : {"o.obj", "o.csv", "d.csv"}) EXPECT_FALSE(std::filesystem::exists(dir / f)) << f;
  // A quaternion too large for its norm is not of unit length: refused naming the option, the
  // order and its length, computed without overflow.
  o = RunCli("contact " + scene + " --pose-a 0,0,0,1e308,1e308,0,0 --json");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("--pose-a: the quaternion (qw, qx, qy, qz) = (1e+308, 1e+308, 0, 0) has length "
                          "1.41421356e+308, not 1"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("x, y, z, qw, qx, qy, qz"), std::string::npos) << o.output;
}

// Finite coordinates whose deformation is finite but beyond the coordinates any reader accepts
// (q = 1e30: a mesh of 5.6e30 m that mesh-info then refused) are refused where they are parsed,
// naming the option and the limit; large coordinates within it export a mesh that mesh-info reads.
TEST(CliDeformable, CoordinatesThatDeformBeyondTheMeshReadersLimitAreRefusedNotExported) {
  testing::TempDir dir;
  std::ofstream(dir / "beam.yaml") << kBeamScene;
  const std::string scene = (dir / "beam.yaml").string() + " --cache " + (dir / "cache").string();
  for (const char* q : {"1e30,1e30,1e30,1e30", "0,0,0,1e12"}) {
    const Outcome o = RunCli("body-export " + scene + " --body beam --q " + q + " --mesh " + (dir / "far.obj").string());
    EXPECT_EQ(o.exit_code, 1) << q;
    EXPECT_NE(o.output.find("--q (body 'beam'): these coordinates move node "), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("beyond the 1e9 m every mesh, field and body must stay within"), std::string::npos)
        << o.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "far.obj")) << q;
  }
  const Outcome big = RunCli("body-export " + scene + " --body beam --q 100,-100,100,-100 --mesh " +
                             (dir / "big.obj").string());
  ASSERT_EQ(big.exit_code, 0) << big.output;
  const Outcome info = RunCli("mesh-info " + (dir / "big.obj").string() + " --json");
  EXPECT_EQ(info.exit_code, 0) << info.output;
}

// Messages that say what is wrong: a word among the coordinates is not a number (not a count),
// a negative --level is out of range (not "all levels"), and an anchor that holds no vertex is
// named by the file and line that give it.
TEST(CliDeformable, BadCoordinatesLevelsAndAnchorsAreNamedForWhatTheyAre) {
  testing::TempDir dir;
  std::ofstream(dir / "beam.yaml") << kBeamScene;
  const std::string scene = (dir / "beam.yaml").string() + " --cache " + (dir / "cache").string();
  Outcome o = RunCli("body-export " + scene + " --body beam --q hello --mesh " + (dir / "o.obj").string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--q (body 'beam'): value 1 'hello' is not a finite number"), std::string::npos) << o.output;
  o = RunCli("contact " + scene + " --q-a 0,0,x");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--q-a (body 'beam'): value 3 'x' is not a finite number"), std::string::npos) << o.output;
  o = RunCli("body-export " + scene + " --body beam --level -1 --pointshell " + (dir / "o.csv").string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--level: -1 is out of range: the pointshell has levels 0..2"), std::string::npos) << o.output;
  o = RunCli("body-export " + scene + " --body beam --level 3 --pointshell " + (dir / "o.csv").string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find("--level: 3 is out of range"), std::string::npos) << o.output;
  for (const char* f : {"o.obj", "o.csv"}) EXPECT_FALSE(std::filesystem::exists(dir / f)) << f;
  // Without --level: every level (0..2), and with --level 1 levels 0..1 only.
  ASSERT_EQ(RunCli("body-export " + scene + " --body beam --pointshell " + (dir / "all.csv").string()).exit_code, 0);
  ASSERT_EQ(RunCli("body-export " + scene + " --body beam --level 1 --pointshell " + (dir / "l1.csv").string()).exit_code, 0);
  const auto all = ReadNumbers(dir / "all.csv", ',', true), l1 = ReadNumbers(dir / "l1.csv", ',', true);
  EXPECT_EQ(all.back()[6], 2.0);
  EXPECT_EQ(l1.back()[6], 1.0);
  EXPECT_LT(l1.size(), all.size());

  // An anchor plane below the whole beam: the error names the scene file, its line and key.
  std::string far = kBeamScene;
  far.replace(far.find("[x, -0.09]"), 10, "[x, -5.0]");
  std::ofstream(dir / "far.yaml") << far;
  o = RunCli("body-export " + (dir / "far.yaml").string() + " --cache " + (dir / "cache").string() +
             " --body beam --q 0,0,0,0 --mesh " + (dir / "o.obj").string());
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.output.find((dir / "far.yaml").string() + ":8: bodies[0].deformable.anchor ("), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("body 'beam'"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("no vertex of the simulation mesh is anchored"), std::string::npos) << o.output;
}

TEST(CliDeformable, BodyEvalGivesTheRigidFieldAndTheDeformedFieldOnTheDeformedSurface) {
  testing::TempDir dir;
  std::ofstream(dir / "beam.yaml") << kBeamScene;
  const std::string scene = (dir / "beam.yaml").string() + " --cache " + (dir / "cache").string();
  // Rigid probe: the field of a 1 cm sphere, against the analytic distance.
  std::ofstream(dir / "p.csv") << "x,y,z\n0.012,0,0\n0,0.009,0\n0,0,-0.0105\n0.004,0.004,0.004\n";
  ASSERT_EQ(RunCli("body-eval " + scene + " --body probe --points " + (dir / "p.csv").string() + " --out " +
                   (dir / "probe.csv").string()).exit_code, 0);
  for (const auto& row : ReadNumbers(dir / "probe.csv", ',', true)) {
    ASSERT_EQ(row.size(), 4u);
    EXPECT_NEAR(row[3], Eigen::Vector3d(row[0], row[1], row[2]).norm() - 0.01, 5e-4);
  }
  // Deformable beam: at rest (no --q, or q = 0) the box's distance near its faces.
  std::ofstream(dir / "b.csv") << "x,y,z\n0.05,0,0.012\n-0.03,0.011,0\n0.0,0,-0.009\n0.098,0,0\n";
  ASSERT_EQ(RunCli("body-eval " + scene + " --body beam --points " + (dir / "b.csv").string() + " --out " +
                   (dir / "rest.csv").string()).exit_code, 0);
  ASSERT_EQ(RunCli("body-eval " + scene + " --body beam --q 0,0,0,0 --points " + (dir / "b.csv").string() +
                   " --out " + (dir / "zero.csv").string()).exit_code, 0);
  const auto rest = ReadNumbers(dir / "rest.csv", ',', true), zero = ReadNumbers(dir / "zero.csv", ',', true);
  const double expected[4] = {0.002, 0.001, -0.001, -0.002};
  ASSERT_EQ(rest.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(rest[i][3], expected[i], 1e-3) << "point " << i;
    EXPECT_EQ(rest[i][3], zero[i][3]);
  }
  // Deformed: the vertices of the deformed surface (body-export at the same q) lie on the
  // deformed field's zero level, within a cell of the beam's field (0.24 m / 48).
  const std::string q = "0.002,-0.0015,0.001,0.0005";  // about 7 mm at the free end
  ASSERT_EQ(RunCli("body-export " + scene + " --body beam --q " + q + " --mesh " + (dir / "bent.obj").string())
                .exit_code, 0);
  std::ofstream pts(dir / "bent.csv");
  pts << "x,y,z\n";
  std::istringstream obj(ReadWholeFile(dir / "bent.obj"));
  int vertices = 0;
  for (std::string line; std::getline(obj, line);) {
    if (line.rfind("v ", 0) == 0) {
      std::istringstream v(line.substr(2));
      double x, y, z;
      v >> x >> y >> z;
      pts << x << "," << y << "," << z << "\n";
      ++vertices;
    }
  }
  pts.close();
  ASSERT_GT(vertices, 50);
  ASSERT_EQ(RunCli("body-eval " + scene + " --body beam --q " + q + " --points " + (dir / "bent.csv").string() +
                   " --out " + (dir / "bent-d.csv").string()).exit_code, 0);
  const auto bent = ReadNumbers(dir / "bent-d.csv", ',', true);
  ASSERT_EQ(int(bent.size()), vertices);
  double worst = 0;
  for (const auto& row : bent) worst = std::max(worst, std::abs(row[3]));
  EXPECT_LT(worst, 0.005) << "largest |d| at the deformed surface";
  // Bad input: the output may not be the points file; a rigid body takes no --q.
  const Outcome same = RunCli("body-eval " + scene + " --body beam --points " + (dir / "b.csv").string() + " --out " +
                              (dir / "b.csv").string());
  EXPECT_EQ(same.exit_code, 1);
  EXPECT_EQ(ReadWholeFile(dir / "b.csv").substr(0, 6), "x,y,z\n");
  const Outcome rigid_q = RunCli("body-eval " + scene + " --body probe --q 1 --points " + (dir / "p.csv").string() +
                                 " --out " + (dir / "no.csv").string());
  EXPECT_EQ(rigid_q.exit_code, 1);
  EXPECT_NE(rigid_q.output.find("the body is rigid"), std::string::npos) << rigid_q.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "no.csv"));
}


// A plate as a 12-triangle box mesh file (0.05 x 0.05 x 0.01 m, faces outward), for the scene
// whose mesh is a file the session reads.
const char* kPlateObj =
    "v -0.025 -0.025 -0.005\nv 0.025 -0.025 -0.005\nv 0.025 0.025 -0.005\nv -0.025 0.025 -0.005\n"
    "v -0.025 -0.025 0.005\nv 0.025 -0.025 0.005\nv 0.025 0.025 0.005\nv -0.025 0.025 0.005\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\nf 2 3 7\nf 2 7 6\n";

// `session --log` naming a file the session reads (its scene, its replay file, a mesh of the
// scene) used to overwrite it with the log: only the scene's explicit path was ever compared,
// and not even that. Every input read is now recorded and no output may replace one.
TEST(CliOutputs, SessionLogNamingItsSceneReplayFileOrMeshIsRefusedAndTheInputKept) {
  testing::TempDir dir;
  std::string scene = kScene;
  scene.replace(scene.find("\"box:0.05,0.05,0.01,2\""), 22, "\"plate.obj\"");
  std::ofstream(dir / "scene.yaml") << scene;
  std::ofstream(dir / "plate.obj") << kPlateObj;
  const std::string cache = " --cache " + (dir / "cache").string();
  const std::string session = "session " + (dir / "scene.yaml").string() + " --duration 0.2 --no-realtime --quiet" + cache;
  const Outcome recorded = RunCli(session + " --device sim --log " + (dir / "replay.csv").string());
  ASSERT_EQ(recorded.exit_code, 0) << recorded.output;
  const std::string replay = ReadWholeFile(dir / "replay.csv");
  for (const char* input : {"scene.yaml", "replay.csv", "plate.obj"}) {
    SCOPED_TRACE(input);
    const std::string before = ReadWholeFile(dir / input);
    // The input by another spelling: a symlink to it.
    std::filesystem::create_symlink(dir / input, dir / "log-link.csv");
    for (const std::filesystem::path& log : {dir / input, dir / "log-link.csv"}) {
      const Outcome o = RunCli(session + " --device replay:" + (dir / "replay.csv").string() + " --log " + log.string());
      EXPECT_EQ(o.exit_code, 1) << o.output;
      EXPECT_NE(o.output.find("is the input"), std::string::npos) << o.output;
      EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
      EXPECT_EQ(ReadWholeFile(dir / input), before);
    }
    std::filesystem::remove(dir / "log-link.csv");
  }
  EXPECT_EQ(ReadWholeFile(dir / "replay.csv"), replay);
}

// `run RESULTS/summary.csv --out RESULTS`: a config kept in its results folder under the name of
// a result file used to be replaced by the results; it is refused before any job runs. A config
// under any other name in the folder is kept with the new results.
TEST(CliOutputs, RunConfigInsideItsResultsFolderIsNeverOverwritten) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::filesystem::create_directory(dir / "r");
  const std::string config = "name: e\nscene: ../scene.yaml\n" + testing::PressTrajectoryYaml(0.02) + "\n";
  std::ofstream(dir / "r" / "summary.csv") << config;
  const std::string cache = " --cache " + (dir / "cache").string();
  const Outcome o = RunCli("run " + (dir / "r" / "summary.csv").string() + " --out " + (dir / "r").string() + cache);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("is the input"), std::string::npos) << o.output;
  EXPECT_EQ(ReadWholeFile(dir / "r" / "summary.csv"), config);
  EXPECT_FALSE(std::filesystem::exists(dir / "cache"));  // refused before any job ran
  std::filesystem::rename(dir / "r" / "summary.csv", dir / "r" / "exp.yaml");
  const Outcome kept = RunCli("run " + (dir / "r" / "exp.yaml").string() + " --out " + (dir / "r").string() + cache);
  ASSERT_EQ(kept.exit_code, 0) << kept.output;
  EXPECT_EQ(ReadWholeFile(dir / "r" / "exp.yaml"), config);
  EXPECT_TRUE(std::filesystem::exists(dir / "r" / "summary.csv"));
}

// Shell commands that run what follows with FOLDER on a read-only file system (a tmpfs mounted
// read-only in a private mount namespace, which stops root as well as mode 0555 would stop a
// user), or an empty string when this machine cannot make one.
std::string ReadOnlyMountBefore(const std::filesystem::path& folder) {
  if (std::system("unshare -rm true > /dev/null 2>&1") != 0) return "";
  return "unshare -rm sh -c 'mount -t tmpfs -o ro none " + folder.string() + " && exec \"$0\" \"$@\"'";
}

// `run --out` and `merge --out` on a read-only file system used to compute every job and then
// fail with "internal error: filesystem error", the results lost; both are refused before any
// work, naming the option and the reason.
TEST(CliOutputs, OutputOnAReadOnlyFileSystemIsRefusedBeforeTheWork) {
  TwoJobRuns runs;
  const std::filesystem::path& dir = runs.dir.path();
  std::filesystem::create_directory(dir / "ro");
  const std::string prefix = ReadOnlyMountBefore(dir / "ro");
  if (prefix.empty()) GTEST_SKIP() << "no private mount namespace here (unshare -rm) to make a read-only file system";
  const std::string cache = " --cache " + (dir / "cache2").string();
  Outcome o = RunCliAfter(prefix, "run " + (dir / "exp.yaml").string() + " --out " + (dir / "ro" / "res").string() + cache);
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("--out: cannot write in " + (dir / "ro").string() + ": Read-only file system"),
            std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "cache2"));  // no field was built: no job ran
  o = RunCliAfter(prefix, runs.Merge("f0 f1", "ro/merged"));
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("Read-only file system"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
}

// The files of a results folder, name and bytes.
std::vector<std::pair<std::string, std::string>> FolderFiles(const std::filesystem::path& folder) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& e : std::filesystem::directory_iterator(folder)) {
    files.emplace_back(e.path().filename().string(), e.is_regular_file() ? ReadWholeFile(e.path()) : "(folder)");
  }
  std::sort(files.begin(), files.end());
  return files;
}

// A disk that fills between the files of one results commit used to leave a new cycles.csv
// beside the old summary.csv and meta.json, which the viewer and load_results read as one run.
// The folder is now written beside it and exchanged in one step: a failed rewrite leaves every
// old file as it was and nothing else behind; a good one replaces every result file.
TEST(CliOutputs, DiskFullBetweenTheFilesOfAResultsCommitLeavesTheOldResultsWhole) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: scene.yaml\n" << testing::PressTrajectoryYaml(0.02) << "\n";
  const std::string cache = " --cache " + (dir / "cache").string();
  const std::string run = "run " + (dir / "exp.yaml").string() + " --out " + (dir / "r").string() + cache;
  ASSERT_EQ(RunCli(run).exit_code, 0);
  std::ofstream(dir / "r" / "notes.txt") << "kept";
  const auto old_files = FolderFiles(dir / "r");
  // A new run of the same config with a longer trajectory: its cycles.csv is written first and
  // its meta.json last; a file size limit between their sizes fails the commit between them.
  std::ofstream(dir / "exp.yaml") << "name: e\nscene: scene.yaml\n" << testing::PressTrajectoryYaml(0.03) << "\n";
  const std::size_t first = ReadWholeFile(dir / "r" / "cycles.csv").size();
  const std::size_t last = ReadWholeFile(dir / "r" / "meta.json").size();
  ASSERT_LT(first * 3 / 2 + 1024, last) << "the limit must fall between the first file's size and the last's";
  const std::string limit = "trap '' XFSZ; ulimit -f " + std::to_string((first * 3 / 2 + 1024) / 512) + ";";
  const Outcome full = RunCliAfter(limit, run);
  EXPECT_EQ(full.exit_code, 1) << full.output;
  EXPECT_NE(full.output.find("meta.json"), std::string::npos) << full.output;
  EXPECT_EQ(FolderFiles(dir / "r"), old_files);
  EXPECT_EQ(CountFiles(dir.path()), 4) << "scene.yaml, exp.yaml, cache/ and r/ only";
  // Without the limit every result file is new and the notes are kept.
  ASSERT_EQ(RunCli(run).exit_code, 0);
  const auto old_cycles = std::find_if(old_files.begin(), old_files.end(), [](const auto& f) { return f.first == "cycles.csv"; });
  ASSERT_NE(old_cycles, old_files.end());
  EXPECT_NE(ReadWholeFile(dir / "r" / "cycles.csv"), old_cycles->second);
  EXPECT_EQ(ReadWholeFile(dir / "r" / "notes.txt"), "kept");
  EXPECT_EQ(CountFiles(dir.path()), 4);
}

// SIGHUP (a closed terminal) to a session used to kill it with exit 129, the log lost and its
// half-written temporary left behind. Every stop signal now ends the session as Ctrl-C does: the
// log complete, every row whole, committed under its name. The signal is sent once the session
// printed its start line (the log is open by then).
TEST(CliOutputs, HangupOrQuitToASessionLeavesACompleteLog) {
  testing::TempDir dir;
  std::ofstream(dir / "scene.yaml") << kScene;
  const std::string cache = " --cache " + (dir / "cache").string();
  ASSERT_EQ(RunCli("contact " + (dir / "scene.yaml").string() + cache).exit_code, 0);  // fills the cache
  for (const char* signal : {"HUP", "QUIT", "TERM", "INT"}) {
    SCOPED_TRACE(signal);
    const std::filesystem::path log = dir / (std::string(signal) + ".csv");
    const std::string pid = (dir / "pid").string();
    const std::string session = "sh -c 'echo $$ > " + pid + "; exec " + CONTACTLAB_CLI + " session " +
                                (dir / "scene.yaml").string() + " --device sim --duration 600 --no-realtime --quiet --log " +
                                log.string() + cache + "'";
    const Outcome o = testing::RunShellCommand("{ " + session + "; echo \"exit $?\"; } | { IFS= read -r first; echo \"$first\"; kill -" +
                                               signal + " $(cat " + pid + "); cat; }");
    EXPECT_NE(o.output.find("session: scene"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("\nexit 0\n"), std::string::npos) << o.output;
    ASSERT_TRUE(std::filesystem::exists(log)) << o.output;
    const std::string text = ReadWholeFile(log);
    ASSERT_FALSE(text.empty());
    EXPECT_EQ(text.back(), '\n');
    std::istringstream lines(text);
    std::string line;
    std::getline(lines, line);  // the comment
    std::getline(lines, line);
    const long cells = std::count(line.begin(), line.end(), ',');
    long rows = 0;
    while (std::getline(lines, line)) {
      EXPECT_EQ(std::count(line.begin(), line.end(), ','), cells) << "row " << rows;
      ++rows;
    }
  }
  EXPECT_EQ(CountFiles(dir.path()), 7) << "scene.yaml, cache/, pid and the four logs; no temporary";
}

}  // namespace
}  // namespace contactlab
