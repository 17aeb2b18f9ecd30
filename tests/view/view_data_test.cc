#include "view/view_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "contact/register_contact_models.h"
#include "experiment/studies/contact/contact_study.h"
#include "experiment/studies/contact/result_csv.h"
#include "experiment/studies/many_bodies/many_bodies_study.h"
#include "../experiment/csv_rows.h"
#include "scene_fixtures.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "view/page_encoding.h"
#include "view/viewer_page.h"

namespace contactlab {
namespace {

using testing::TempDir;

// A 4 cm ball pressed into a plate and twisted, compared by two models: procedural and fast.
// The ball is the shared ball on plate (tests/scene_fixtures.h), 1.5 mm above the plate.
const std::string kConfig =
    "name: view-tiny\n"
    "description: a ball pressed into a plate and twisted\n"
    "scene:\n" +
    testing::BallOnPlate{.ball_z = 0.0215, .points = 256, .levels = 3, .seed = 3}.Yaml(2) +
    "models: [pointshell, pointshell-linear]\n"
    "moving_body: ball\n"
    "trajectory: {type: twist, direction: [0, 0, -1], depth: 0.002, angle: 0.4, duration: 0.06}\n"
    "reference: ''\n";

RunOptions Options(const TempDir& dir) {
  RunOptions o;
  o.out_dir = dir / "out";
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  o.parallel_jobs = 1;
  return o;
}

// Runs kConfig (with OVERRIDES) into DIR/out.
void RunTiny(const TempDir& dir, const std::vector<std::string>& overrides = {}) {
  std::ofstream(dir / "config.yaml") << kConfig;
  RunExperiment(LoadExperimentConfig(dir / "config.yaml", overrides), Options(dir));
}

using testing::ErrorOf;

TEST(Replay, ReadsEveryModelsPosesAndWrenchesFromTheResultsFolder) {
  TempDir dir;
  RunTiny(dir);
  const Replay r = ReadReplay(dir / "out", std::nullopt);
  EXPECT_EQ(r.experiment, "view-tiny");
  EXPECT_EQ(r.job, 0);
  EXPECT_EQ(r.moving_body, "ball");
  EXPECT_EQ(r.scene.pointshell_body.name, "ball");
  ASSERT_EQ(r.tracks.size(), 2u);
  EXPECT_EQ(r.tracks[0].model, "pointshell");
  EXPECT_EQ(r.tracks[1].model, "pointshell-linear");
  // The rows of cycles.csv, read back: cycle k at t = k ms, orientation a unit quaternion that
  // turns during the twist.
  const std::string csv = ReadWholeFile(dir / "out" / "cycles.csv");
  const std::int64_t rows = std::count(csv.begin(), csv.end(), '\n') - 1;
  EXPECT_EQ(r.tracks[0].cycles + r.tracks[1].cycles, rows);
  const ReplayTrack& t = r.tracks[0];
  ASSERT_EQ(t.t.size(), std::size_t(t.cycles));
  ASSERT_EQ(t.pose.size(), 7 * t.t.size());
  ASSERT_EQ(t.force.size(), 3 * t.t.size());
  double max_angle = 0, max_force = 0;
  for (std::size_t i = 0; i < t.t.size(); ++i) {
    EXPECT_NEAR(t.t[i], 0.001 * double(i), 1e-6);
    const Eigen::Quaternionf q(t.pose[7 * i + 3], t.pose[7 * i + 4], t.pose[7 * i + 5], t.pose[7 * i + 6]);
    EXPECT_NEAR(q.norm(), 1.0, 1e-5);
    max_angle = std::max(max_angle, 2.0 * std::acos(std::min(1.0f, std::abs(q.w()))));
    max_force = std::max(max_force, double(Eigen::Vector3f(t.force[3 * i], t.force[3 * i + 1], t.force[3 * i + 2]).norm()));
  }
  EXPECT_NEAR(max_angle, 0.4, 0.02);  // the twist's angle is in the orientation columns
  EXPECT_GT(max_force, 0.0);          // pressed into the plate
}

TEST(Replay, ThinsLongRunsToTheFrameCap) {
  TempDir dir;
  RunTiny(dir);
  const Replay r = ReadReplay(dir / "out", 0, 20);
  EXPECT_EQ(r.stride, 4);  // 61 cycles, at most 20 frames
  for (const ReplayTrack& t : r.tracks) {
    EXPECT_LE(t.t.size(), 20u);
    EXPECT_NEAR(t.t[1] - t.t[0], 0.004, 1e-6);
  }
}

TEST(Replay, PageDataHoldsBothBodiesThePointshellAndEveryTrack) {
  TempDir dir;
  RunTiny(dir);
  const Replay r = ReadReplay(dir / "out", std::nullopt);
  SceneAssets assets(r.scene, Options(dir).assets);
  SceneViewOptions options;
  options.max_points = 100;
  const nlohmann::json j = ReplayViewData(r, assets, options);
  ASSERT_EQ(j["bodies"].size(), 2u);
  EXPECT_EQ(j["bodies"][0]["name"], "ball");
  EXPECT_EQ(j["replay"]["moving"], 0);
  EXPECT_EQ(j["replay"]["models"].size(), 2u);
  const auto positions = DecodeArray<float>(j["bodies"][1]["positions"].get<std::string>(), "plate");
  EXPECT_EQ(positions.size(), 3 * j["bodies"][1]["vertices"].get<std::size_t>());
  const auto levels = DecodeArray<std::uint8_t>(j["pointshell"]["level"].get<std::string>(), "levels");
  EXPECT_LE(levels.size(), 100u);
  EXPECT_EQ(std::set<int>(levels.begin(), levels.end()).size(), 3u);  // every level drawn
  // The slice goes through the ball's origin and holds both signs (the plate's surface).
  EXPECT_LT(j["slice"]["min"].get<double>(), 0);
  EXPECT_GT(j["slice"]["max"].get<double>(), 0);
  // The page embeds it all and nothing else is needed.
  if (std::filesystem::exists(ThreeJsDir() / "three.min.js")) {
    const std::string page = ViewerPage(j);
    EXPECT_NE(page.find("REVISION=\"111\""), std::string::npos);
    EXPECT_NE(page.find("OrbitControls"), std::string::npos);
    EXPECT_EQ(page.find("@DATA@"), std::string::npos);
    EXPECT_EQ(page.find("<script src"), std::string::npos);
  }
}

// The points flagged in contact are those below the plate's top face (z = 0) at the start poses.
TEST(SceneView, PointsInContactAreThoseInsideTheFieldBody) {
  TempDir dir;
  std::ofstream(dir / "config.yaml") << kConfig;
  ExperimentConfig config = LoadExperimentConfig(dir / "config.yaml");
  Scene scene = config.scene;
  scene.pointshell_body.pose.translation.z() = 0.018;  // 2 mm into the plate
  scene.pointshell_body.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  SceneAssets assets(scene, Options(dir).assets);
  const nlohmann::json j = SceneViewData(scene, assets, SceneViewOptions{});
  const auto xyz = DecodeArray<float>(j["pointshell"]["positions"].get<std::string>(), "positions");
  const auto contact = DecodeArray<std::uint8_t>(j["pointshell"]["contact"].get<std::string>(), "contact");
  ASSERT_EQ(contact.size() * 3, xyz.size());
  const double h = assets.B.field()->spacing();
  int flagged = 0;
  for (std::size_t i = 0; i < contact.size(); ++i) {
    const Eigen::Vector3d p_W = scene.pointshell_body.pose * Eigen::Vector3d(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    if (contact[i]) {
      ++flagged;
      EXPECT_LT(p_W.z(), h) << i;
    } else {
      EXPECT_GT(p_W.z(), -h) << i;
    }
  }
  EXPECT_GT(flagged, 0);
  EXPECT_EQ(j["pointshell"]["in_contact"].get<int>(), flagged);  // every point is drawn here
}

// A scene of many bodies on the scene page: every body at its scene pose with its own mesh, the
// tool marked, and each pair in its model's A/B order (a box-only FCL pair between two others).
TEST(SceneView, AManyBodyPageDrawsEveryBodyAndListsThePairsInTheirModelsOrder) {
  TempDir dir;
  std::ofstream(dir / "many.yaml") << "name: many\n"
                                      "tool: ball\n"
                                      "bodies:\n"
                                      "  - {name: plate, mesh: \"box:0.05,0.05,0.01,2\", pose: [0, 0, -0.01, 1, 0, 0, 0], role: field}\n"
                                      "  - {name: ball, mesh: \"sphere:0.02,2\", pose: [0, 0, 0.03, 1, 0, 0, 0], role: pointshell}\n"
                                      "  - {name: post, mesh: \"box:0.01,0.01,0.03,1\", pose: [0.04, 0.01, 0.02, 0, 0, 0, 1]}\n"
                                      "pairs:\n"
                                      "  - {bodies: [plate, post], model: fcl}\n";
  const Scene scene = LoadScene(dir / "many.yaml");
  const nlohmann::json j = ManyBodiesViewData(scene, "pointshell", Options(dir).assets, SceneViewOptions{});
  ASSERT_EQ(j["bodies"].size(), 3u);
  EXPECT_EQ(j["tool"].get<int>(), 1);
  EXPECT_FALSE(j.contains("pointshell")) << "a pair's pointshell is not built for the page";
  EXPECT_FALSE(j.contains("slice"));
  const std::vector<int> triangles = {48, 320, 12};  // 6 faces x 2 x n^2 (n = 2, 1); an icosphere of 20 x 4^2
  for (std::size_t i = 0; i < 3; ++i) {
    const nlohmann::json& b = j["bodies"][i];
    EXPECT_EQ(b["name"].get<std::string>(), scene.bodies[i].name);
    EXPECT_EQ(b["tool"].get<bool>(), i == 1);
    EXPECT_EQ(b["triangles"].get<int>(), triangles[i]) << b["name"];
    const auto xyz = DecodeArray<float>(b["positions"].get<std::string>(), "positions");
    EXPECT_EQ(xyz.size(), 3 * b["vertices"].get<std::size_t>());
    const std::vector<double> pose = b["pose"].get<std::vector<double>>();
    EXPECT_NEAR(pose[0], scene.bodies[i].pose.translation.x(), 1e-12);
    EXPECT_NEAR(pose[2], scene.bodies[i].pose.translation.z(), 1e-12);
    EXPECT_NEAR(std::abs(pose[3]), std::abs(scene.bodies[i].pose.rotation.w()), 1e-12);
  }
  // The ball's pairs: the ball (pointshell) is A; the plate-post pair as FCL takes it.
  ASSERT_EQ(j["pairs"].size(), 3u);
  std::set<std::string> pairs;
  for (const nlohmann::json& p : j["pairs"]) {
    pairs.insert(p["bodies"][0].get<std::string>() + "/" + p["bodies"][1].get<std::string>() + ":" +
                 p["model"].get<std::string>());
  }
  EXPECT_EQ(pairs, (std::set<std::string>{"ball/plate:pointshell", "ball/post:pointshell", "plate/post:fcl"}));
  // A two-body scene is not a scene of many bodies.
  std::ofstream(dir / "two.yaml") << "name: two\nbodies:\n"
                                     "  - {name: a, mesh: \"sphere:0.02\", role: pointshell}\n"
                                     "  - {name: b, mesh: \"box:0.05,0.05,0.01\", role: field}\n";
  const std::string e = ErrorOf([&] { (void)ManyBodiesViewData(LoadScene(dir / "two.yaml"), "pointshell", AssetOptions{}, SceneViewOptions{}); });
  EXPECT_NE(e.find("two.yaml"), std::string::npos) << e;
}

// The replay of a many-bodies run: the tool's poses and forces as world_cycles.csv holds them,
// the deformable floor's coordinates as world_bodies.csv holds them, its basis in the page data.
TEST(Replay, AManyBodiesRunReplaysTheToolAndEveryDeformableBody) {
  TempDir dir;
  std::ofstream(dir / "config.yaml")
      << "name: world-replay\n"
         "study: many-bodies\n"
         "models: [pointshell]\n"
         "scene:\n"
         "  tool: ball\n"
         "  bodies:\n"
         "    - {name: ball, mesh: \"sphere:0.02,2\", pose: [0, 0, 0.0195, 1, 0, 0, 0], role: pointshell,\n"
         "       pointshell: {points: 256, levels: 3, seed: 2}}\n"
         "    - {name: floor, mesh: \"box:0.04,0.04,0.01,2\", pose: [0, 0, -0.01, 1, 0, 0, 0], role: field,\n"
         "       field: {resolution: 24},\n"
         "       deformable: {model: linear, modes: 6, cells: 10, E: 2.0e5, nu: 0.3, rho: 1100,\n"
         "                    anchor: {outside: [-0.035, -0.035, -1, 0.035, 0.035, 1]}, field: {proxies: 20}}}\n"
         "    - {name: post, mesh: \"box:0.01,0.01,0.01,1\", pose: [0, 0.2, 0, 1, 0, 0, 0], role: field}\n"
         "  model: {k_C: 1000, L: 0, max_point_speed: 0.5}\n"
         "trajectory: {type: slide, direction: [0, 0, -1], depth: 0.0005, tangent: [0, 1, 0], length: 0.01,\n"
         "             duration: 0.05}\n";
  RunWorldStudy(LoadExperimentConfig(dir / "config.yaml"), Options(dir));
  const Replay r = ReadReplay(dir / "out", std::nullopt);
  EXPECT_EQ(r.moving_body, "ball");
  ASSERT_EQ(r.tracks.size(), 1u);
  const ReplayTrack& t = r.tracks.front();
  const auto cycles = testing::ReadCsvRows(dir / "out" / "world_cycles.csv");
  ASSERT_EQ(t.t.size(), cycles.size());
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    EXPECT_NEAR(t.pose[7 * k + 2], std::stod(cycles[k].at("z")), 1e-6) << k;
    EXPECT_NEAR(t.force[3 * k + 2], std::stod(cycles[k].at("fz")), 1e-4 * (1 + std::abs(std::stod(cycles[k].at("fz")))));
  }
  ASSERT_EQ(t.bodies_q.size(), 1u);
  EXPECT_EQ(t.bodies_q[0].body, "floor");
  EXPECT_EQ(t.bodies_q[0].r, 6);
  const auto rows = testing::ReadCsvRows(dir / "out" / "world_bodies.csv");
  ASSERT_EQ(rows.size(), cycles.size());
  std::istringstream last(rows.back().at("q"));
  for (int m = 0; m < 6; ++m) {
    double q = 0;
    last >> q;
    EXPECT_NEAR(t.bodies_q[0].q[6 * (cycles.size() - 1) + std::size_t(m)], q, 1e-6 * (1 + std::abs(q))) << m;
  }
  EXPECT_GT(std::abs(t.bodies_q[0].q.back()) + std::abs(t.bodies_q[0].q[t.bodies_q[0].q.size() - 2]), 0.0)
      << "the pressed floor deforms";
  const nlohmann::json j = WorldReplayViewData(r, Options(dir).assets, SceneViewOptions{});
  EXPECT_EQ(j["replay"]["moving"].get<int>(), 0);
  EXPECT_EQ(j["bodies"][1]["modes"].get<int>(), 6);
  const auto basis = DecodeArray<float>(j["bodies"][1]["basis"].get<std::string>(), "basis");
  EXPECT_EQ(basis.size(), j["bodies"][1]["vertices"].get<std::size_t>() * 3 * 6);
  EXPECT_FALSE(j["bodies"][0].contains("basis")) << "the rigid ball";
  EXPECT_EQ(j["replay"]["models"][0]["bodies_q"][0]["body"].get<int>(), 1);
}

// A contact surface (pressure-field) drawn on the scene page: of the scene's models that keep
// one, at the start poses, every corner inside both bodies; none for the other models.
TEST(SceneView, ThePressureFieldsContactSurfaceLiesInsideBothBodies) {
  RegisterContactModels();
  TempDir dir;
  std::ofstream(dir / "config.yaml") << kConfig;
  Scene scene = LoadExperimentConfig(dir / "config.yaml").scene;
  scene.pointshell_body.pose.translation.z() = 0.017;  // 3 mm into the plate
  SceneAssets assets(scene, Options(dir).assets);
  scene.models = {"pointshell"};
  EXPECT_TRUE(SceneViewData(scene, assets, SceneViewOptions{})["surfaces"].empty());
  scene.models = {"pointshell", "pressure-field"};
  const nlohmann::json j = SceneViewData(scene, assets, SceneViewOptions{});
  ASSERT_EQ(j["surfaces"].size(), 1u);
  const nlohmann::json& s = j["surfaces"][0];
  EXPECT_EQ(s["model"], "pressure-field");
  const auto corners = DecodeArray<float>(s["corners"].get<std::string>(), "corners");
  const auto pressure = DecodeArray<float>(s["pressure"].get<std::string>(), "pressure");
  ASSERT_GT(corners.size(), 0u);
  ASSERT_EQ(corners.size(), 9 * s["triangles"].get<std::size_t>());
  ASSERT_EQ(pressure.size() * 3, corners.size());
  const double h = std::max(assets.A.field()->spacing(), assets.B.field()->spacing());
  const Eigen::Vector3d c = scene.pointshell_body.pose.translation;
  for (std::size_t i = 0; i < corners.size() / 3; ++i) {
    const Eigen::Vector3d x(corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]);
    EXPECT_LE((x - c).norm(), 0.02 + h) << i;  // inside the ball
    EXPECT_LE(x.z(), h) << i;                  // inside the plate (top face z = 0)
    EXPECT_GE(pressure[i], 0.0f);
    EXPECT_LE(pressure[i], s["pmax"].get<float>());
  }
}

// A replay keeps a pressure-field model's surface at evenly spaced frames, the first and the
// last among them, each evaluated at that frame's recorded pose: it lies inside the ball where
// the ball was then, and is empty while the ball is clear of the plate.
TEST(Replay, APressureFieldTrackCarriesItsSurfaceAtEvenlySpacedFrames) {
  RegisterContactModels();
  TempDir dir;
  RunTiny(dir, {"models=[pointshell, pressure-field]", "trajectory.depth=0.005"});
  const Replay r = ReadReplay(dir / "out", std::nullopt);
  SceneAssets assets(r.scene, Options(dir).assets);
  SceneViewOptions options;
  options.max_surface_frames = 10;
  const nlohmann::json j = ReplayViewData(r, assets, options);
  ASSERT_EQ(j["replay"]["models"].size(), 2u);
  EXPECT_FALSE(j["replay"]["models"][0].contains("surface"));  // pointshell
  const nlohmann::json& m = j["replay"]["models"][1];
  ASSERT_EQ(m["name"], "pressure-field");
  ASSERT_TRUE(m.contains("surface"));
  const nlohmann::json& s = m["surface"];
  const auto frames = DecodeArray<std::int32_t>(s["frames"].get<std::string>(), "frames");
  const auto start = DecodeArray<std::uint32_t>(s["start"].get<std::string>(), "start");
  const auto corners = DecodeArray<float>(s["corners"].get<std::string>(), "corners");
  const ReplayTrack& t = r.tracks[1];
  ASSERT_EQ(frames.size(), 10u);
  EXPECT_EQ(frames.front(), 0);
  EXPECT_EQ(frames.back(), std::int32_t(t.t.size()) - 1);
  EXPECT_TRUE(std::is_sorted(frames.begin(), frames.end()));
  ASSERT_EQ(start.size(), frames.size() + 1);
  EXPECT_TRUE(std::is_sorted(start.begin(), start.end()));
  ASSERT_EQ(corners.size(), 9 * std::size_t(start.back()));
  const double h = std::max(assets.A.field()->spacing(), assets.B.field()->spacing());
  int touching = 0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const float* p = t.pose.data() + 7 * frames[k];
    const Eigen::Vector3d c(p[0], p[1], p[2]);
    const double depth = 0.02 - c.z();  // of the ball's lowest point below the plate's top
    if (depth < -h) EXPECT_EQ(start[k + 1], start[k]) << "frame " << frames[k];
    if (start[k + 1] > start[k]) ++touching;
    for (std::uint32_t i = 3 * start[k]; i < 3 * start[k + 1]; ++i) {
      const Eigen::Vector3d x(corners[3 * i], corners[3 * i + 1], corners[3 * i + 2]);
      EXPECT_LE((x - c).norm(), 0.02 + h) << "frame " << frames[k];
      EXPECT_LE(x.z(), h) << "frame " << frames[k];
    }
  }
  EXPECT_GE(touching, 3);
}

// A deformable ball pressed onto a plate: the replay carries its reduced coordinates per frame
// and the basis at its mesh vertices, and U q reproduces the run's largest displacement.
TEST(Replay, DeformableBodyCarriesItsCoordinatesAndBasis) {
  TempDir dir;
  std::ofstream(dir / "ball.yaml") << R"(name: soft-ball-plate
bodies:
  - name: ball
    mesh: "sphere:0.02,2"
    pose: [0, 0, 0.0205, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 256, levels: 2, seed: 2}
    field: {resolution: 24}
    deformable: {model: stvk, modes: 6, cells: 8, E: 2.0e5, nu: 0.4, rho: 1000,
                 damping: {alpha: 10.0, beta: 0.001}, anchor: none}
  - name: plate
    mesh: "box:0.05,0.05,0.01,2"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 24}
model: {k_C: 1000, L: 10}
)";
  std::ofstream(dir / "config.yaml") << "name: soft\nscene: ball.yaml\nmodels: [pointshell]\nmoving_body: ball\n"
                                        "trajectory: {type: approach-press, direction: [0, 0, -1], approach: 0.0, "
                                        "depth: 0.003, duration: 0.4}\n";
  RunExperiment(LoadExperimentConfig(dir / "config.yaml"), Options(dir));
  const Replay r = ReadReplay(dir / "out", std::nullopt);
  ASSERT_EQ(r.tracks.size(), 1u);
  const ReplayTrack& t = r.tracks[0];
  EXPECT_EQ(t.r, 6);
  EXPECT_EQ(t.r_B, 0);
  ASSERT_EQ(t.q.size(), 6 * t.t.size());
  SceneAssets assets(r.scene, Options(dir).assets);
  const nlohmann::json j = ReplayViewData(r, assets, SceneViewOptions{});
  ASSERT_EQ(j["bodies"][0]["modes"], 6);
  EXPECT_FALSE(j["bodies"][1].contains("basis"));  // the plate is rigid
  const auto basis = DecodeArray<float>(j["bodies"][0]["basis"].get<std::string>(), "basis");
  const int V = j["bodies"][0]["vertices"].get<int>();
  ASSERT_EQ(basis.size(), std::size_t(V) * 3 * 6);
  // The largest surface displacement over the run, against cycles.csv's max_displacement (over
  // the simulation mesh's vertices, which enclose the surface).
  double largest_u = 0;
  for (std::size_t f = 0; f < t.t.size(); ++f) {
    for (int v = 0; v < V; ++v) {
      Eigen::Vector3d u = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 6; ++m) u[k] += double(basis[(3 * v + k) * 6 + m]) * t.q[6 * f + m];
      largest_u = std::max(largest_u, u.norm());
    }
  }
  double largest_recorded = 0;
  {
    std::istringstream in(ReadWholeFile(dir / "out" / "cycles.csv"));
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = SplitCsvLine(line);
    const std::size_t c = std::find(header.begin(), header.end(), "max_displacement") - header.begin();
    while (std::getline(in, line)) largest_recorded = std::max(largest_recorded, std::stod(SplitCsvLine(line)[c]));
  }
  EXPECT_GT(largest_recorded, 1e-5);  // it did deform
  EXPECT_GT(largest_u, 0.5 * largest_recorded);
  EXPECT_LT(largest_u, 1.05 * largest_recorded);
  // Coordinates that do not fit a body are an error naming the file, the model and the body: a
  // count other than the ball's r, and any for the rigid plate.
  Replay wrong = r;
  wrong.tracks[0].r = 5;
  std::string e = ErrorOf([&] { ReplayViewData(wrong, assets, SceneViewOptions{}); });
  EXPECT_NE(e.find("cycles.csv"), std::string::npos) << e;
  EXPECT_NE(e.find("model pointshell holds 5 reduced coordinates (column q) of body 'ball', whose model has r = 6"),
            std::string::npos) << e;
  Replay rigid = r;
  rigid.tracks[0].r_B = 2;
  rigid.tracks[0].q_B.assign(2 * t.t.size(), 0.f);
  e = ErrorOf([&] { ReplayViewData(rigid, assets, SceneViewOptions{}); });
  EXPECT_NE(e.find("holds 2 reduced coordinates (column q_B) of body 'plate', which is rigid"), std::string::npos) << e;
}

TEST(Replay, SeveralJobsNeedAJobNumber) {
  TempDir dir;
  RunTiny(dir, {"sweep={k_C: [500, 1500]}"});
  const std::string e = ErrorOf([&] { ReadReplay(dir / "out", std::nullopt); });
  EXPECT_NE(e.find("cycles.csv"), std::string::npos) << e;
  EXPECT_NE(e.find("holds jobs 0, 1: choose one with --job"), std::string::npos) << e;
  const Replay r = ReadReplay(dir / "out", 1);
  EXPECT_EQ(r.job, 1);
  EXPECT_EQ(r.job_label, "k_C=1500");
  EXPECT_DOUBLE_EQ(r.scene.model.penalty.k_C, 1500);
  const std::string e2 = ErrorOf([&] { ReadReplay(dir / "out", 7); });
  EXPECT_NE(e2.find("has no job 7 (it holds 0, 1)"), std::string::npos) << e2;
}

// The long strings of DATA taken back from BLOBS (the inverse of SeveralJobsViewData's sharing).
nlohmann::json ResolveBlobs(const nlohmann::json& data, const nlohmann::json& blobs) {
  if (data.is_object() && data.size() == 1 && data.contains("$blob")) return blobs.at(data["$blob"].get<std::size_t>());
  if (!data.is_structured()) return data;
  nlohmann::json out = data;
  for (auto it = out.begin(); it != out.end(); ++it) *it = ResolveBlobs(*it, blobs);
  return out;
}

// The longest string in DATA.
std::size_t LongestString(const nlohmann::json& data) {
  if (data.is_string()) return data.get_ref<const std::string&>().size();
  std::size_t longest = 0;
  if (data.is_structured())
    for (const auto& item : data) longest = std::max(longest, LongestString(item));
  return longest;
}

TEST(Replay, EveryJobIsReadInOnePassAsReadReplayReadsEach) {
  TempDir dir;
  RunTiny(dir, {"sweep={k_C: [500, 1500]}"});
  const std::vector<Replay> all = ReadReplays(dir / "out", 40);
  ASSERT_EQ(all.size(), 2u);
  for (int job = 0; job < 2; ++job) {
    const Replay one = ReadReplay(dir / "out", job, 40);
    const Replay& r = all[std::size_t(job)];
    EXPECT_EQ(r.job, job);
    EXPECT_EQ(r.job_label, one.job_label);
    EXPECT_EQ(r.experiment, "view-tiny");
    EXPECT_DOUBLE_EQ(r.scene.model.penalty.k_C, one.scene.model.penalty.k_C);
    EXPECT_EQ(r.stride, one.stride);
    ASSERT_EQ(r.tracks.size(), one.tracks.size());
    for (std::size_t m = 0; m < r.tracks.size(); ++m) {
      EXPECT_EQ(r.tracks[m].model, one.tracks[m].model);
      EXPECT_EQ(r.tracks[m].cycles, one.tracks[m].cycles);
      EXPECT_EQ(r.tracks[m].force, one.tracks[m].force) << "job " << job << ", model " << r.tracks[m].model;
    }
  }
  EXPECT_EQ(all[1].job_label, "k_C=1500");
  // The two jobs differ in k_C only, so they press with different forces.
  EXPECT_NE(all[0].tracks[0].force, all[1].tracks[0].force);
}

TEST(Replay, SeveralJobsPageDataEmbedsSharedArraysOnce) {
  TempDir dir;
  RunTiny(dir, {"sweep={k_C: [500, 1500]}"});
  const std::vector<Replay> replays = ReadReplays(dir / "out", 40);
  ASSERT_EQ(replays.size(), 2u);
  AssetOptions asset_options;
  asset_options.cache_dir = dir / "cache";
  asset_options.verbose = false;
  std::vector<nlohmann::json> each;
  for (const Replay& r : replays) {
    SceneAssets assets(r.scene, asset_options);
    each.push_back(ReplayViewData(r, assets, SceneViewOptions{}));
  }
  const nlohmann::json page = SeveralJobsViewData(replays, each);
  ASSERT_EQ(page["jobs"].size(), 2u);
  EXPECT_EQ(page["title"], "view-tiny");
  EXPECT_EQ(page["jobs"][1]["job"], 1);
  EXPECT_EQ(page["jobs"][1]["label"], "k_C=1500");
  EXPECT_EQ(page["jobs"][1]["title"], each[1]["title"]);
  // Each job's data comes back whole from the shared strings, and none of them is left inline.
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_LT(LongestString(page["job_data"][i]), 1024u) << "job " << i;
    EXPECT_EQ(ResolveBlobs(page["job_data"][i], page["blobs"]), each[i]) << "job " << i;
  }
  // The meshes, pointshell and slice, equal in both jobs (only k_C differs), are held once: the
  // page is well under the two jobs' data side by side.
  EXPECT_EQ(page["job_data"][0]["bodies"][0]["positions"], page["job_data"][1]["bodies"][0]["positions"]);
  const std::size_t both = each[0].dump().size() + each[1].dump().size(), shared = page.dump().size();
  EXPECT_LT(shared, 0.75 * double(both)) << shared << " bytes against " << both;
  // A mismatch of replays and data is an error.
  const std::string e = ErrorOf([&] { SeveralJobsViewData(replays, {each[0]}); });
  EXPECT_NE(e.find("one page data per replay"), std::string::npos) << e;
}

// The job's scene is expanded again only from the config of a study that replays
// (Study::replayable), whatever its name: a folder whose meta.json says a contact study wrote it
// but whose resolved config is a closed-loop one is refused, naming meta.json.
TEST(Replay, ResolvedConfigOfAStudyWithoutTrajectoriesIsRefused) {
  TempDir dir;
  RunTiny(dir);
  nlohmann::json meta = nlohmann::json::parse(ReadWholeFile(dir / "out" / "meta.json"));
  meta["study"] = "contact";
  meta["resolved_config"] = "name: view-loop\nstudy: closed-loop\nscene:\n" +
                            testing::BallOnPlate{.ball_z = 0.0215, .points = 256, .levels = 3, .seed = 3}.Yaml(2) +
                            "models: [pointshell]\n";
  WriteFileAtomically(dir / "out" / "meta.json", meta.dump(2));
  const std::string e = ErrorOf([&] { ReadReplay(dir / "out", std::nullopt); });
  EXPECT_NE(e.find((dir / "out" / "meta.json").string() + ": is a closed-loop study, which has no trajectory to replay"),
            std::string::npos)
      << e;
}

TEST(Replay, BadResultsFolderIsAClearErrorNamingTheFile) {
  TempDir dir;
  // No folder.
  std::string e = ErrorOf([&] { ReadReplay(dir / "absent", std::nullopt); });
  EXPECT_NE(e.find((dir / "absent").string() + ": results folder not found"), std::string::npos) << e;
  // A file, not a folder.
  std::ofstream(dir / "file") << "x";
  e = ErrorOf([&] { ReadReplay(dir / "file", std::nullopt); });
  EXPECT_NE(e.find("is not a results folder"), std::string::npos) << e;
  // No meta.json.
  std::filesystem::create_directories(dir / "empty");
  e = ErrorOf([&] { ReadReplay(dir / "empty", std::nullopt); });
  EXPECT_NE(e.find((dir / "empty" / "meta.json").string() + ": not found"), std::string::npos) << e;
  // A contact study's meta.json but no cycles.csv.
  RunTiny(dir);
  std::filesystem::copy_file(dir / "out" / "meta.json", dir / "empty" / "meta.json");
  e = ErrorOf([&] { ReadReplay(dir / "empty", std::nullopt); });
  EXPECT_NE(e.find((dir / "empty" / "cycles.csv").string() + ": not found"), std::string::npos) << e;
  // The results of a study without trajectories, whatever files lie beside them.
  std::filesystem::create_directories(dir / "loop");
  std::filesystem::copy_file(dir / "out" / "cycles.csv", dir / "loop" / "cycles.csv");
  WriteFileAtomically(dir / "loop" / "meta.json", R"({"study": "closed-loop", "jobs": [0]})");
  e = ErrorOf([&] { ReadReplay(dir / "loop", std::nullopt); });
  EXPECT_NE(e.find((dir / "loop").string() + ": holds a closed-loop study"), std::string::npos) << e;
  EXPECT_NE(e.find("no trajectory to replay"), std::string::npos) << e;
  // cycles.csv from before the orientation columns.
  const std::string csv = ReadWholeFile(dir / "out" / "cycles.csv");
  std::string old = csv;
  const std::size_t at = old.find(",qw,qx,qy,qz");
  ASSERT_NE(at, std::string::npos);
  old.erase(at, 12);
  WriteFileAtomically(dir / "out" / "cycles.csv", old);
  e = ErrorOf([&] { ReadReplay(dir / "out", std::nullopt); });
  EXPECT_NE(e.find("cycles.csv: has no orientation column qw"), std::string::npos) << e;
  // A cell that is not a number names the line and the column.
  std::vector<std::string> lines;
  {
    std::istringstream in(csv);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  const std::vector<std::string> header = SplitCsvLine(lines[0]);
  std::vector<std::string> cells = SplitCsvLine(lines[3]);
  const std::size_t t_col = std::find(header.begin(), header.end(), "t") - header.begin();
  ASSERT_LT(t_col, cells.size());
  cells[t_col] = "soon";
  lines[3].clear();
  for (std::size_t c = 0; c < cells.size(); ++c) lines[3] += (c ? "," : "") + cells[c];
  std::string bad;
  for (const std::string& l : lines) bad += l + "\n";
  WriteFileAtomically(dir / "out" / "cycles.csv", bad);
  e = ErrorOf([&] { ReadReplay(dir / "out", std::nullopt); });
  EXPECT_NE(e.find("cycles.csv:4: column t: soon is not a number"), std::string::npos) << e;
  // meta.json that is not JSON.
  WriteFileAtomically(dir / "out" / "cycles.csv", csv);
  WriteFileAtomically(dir / "out" / "meta.json", "{not json");
  e = ErrorOf([&] { ReadReplay(dir / "out", std::nullopt); });
  EXPECT_NE(e.find("meta.json: not valid JSON"), std::string::npos) << e;
}

}  // namespace
}  // namespace contactlab
