// Tests of VPS's distance-layered voxmap (the default `voxmap: layered`, after DLR's VPS,
// Sagardia, Hulin et al.): on a plane the depth it renders is the plane's exact depth at every
// height, through the whole interior; pressed into a plate (the sphere-on-plate scene) or
// another shape, the force is non-zero from the first quarter millimetre and never steps down
// as the depth grows, and it matches the brute-force sum of the same points' exact depths. The
// 1999 surface layer (`voxmap: surface`) is checked against the same references to show the
// key selects it: it saturates in the interior and has a dead band on sphere-on-plate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "baselines/vps/voxel_depths.h"
#include "baselines/vps/vps_contact_model.h"
#include "baselines/vps/vps_params.h"
#include "contact/register_contact_models.h"
#include "contact/test_shells.h"
#include "scene/scene_assets.h"

namespace contactlab {
namespace {

using testing::MakeNestedShell;
using testing::SampleField;

constexpr double kH = 0.004;       // field spacing = voxel size, metres
constexpr double kZ0 = 0.37 * kH;  // the plate's top, off the voxel centres and faces

// The halfspace z < kZ0, 8 voxels deep.
std::shared_ptr<DistanceField> PlateField() {
  return SampleField([](const Eigen::Vector3d& p) { return p.z() - kZ0; }, Eigen::Vector3d(-0.1, -0.1, -8 * kH),
                     Eigen::Vector3d(0.1, 0.1, 8 * kH), kH);
}

TEST(VoxelDepthMap, OctahedralNormalsAreWithinOneDegreeAndAxesExact) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g;
  double worst = 0;
  for (int t = 0; t < 20000; ++t) {
    const Eigen::Vector3d n = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    float m[3];
    VoxelDepthMap::Normal({0, VoxelDepthMap::EncodeNormal(n)}, m);
    const Eigen::Vector3d back(m[0], m[1], m[2]);
    EXPECT_NEAR(back.norm(), 1.0, 1e-6);
    worst = std::max(worst, std::acos(std::clamp(back.dot(n), -1.0, 1.0)) * 180 / M_PI);
  }
  EXPECT_LT(worst, 1.0);
  for (int a = 0; a < 3; ++a)
    for (const double s : {-1.0, 1.0}) {
      float m[3];
      VoxelDepthMap::Normal({0, VoxelDepthMap::EncodeNormal(s * Eigen::Vector3d::Unit(a))}, m);
      EXPECT_EQ(Eigen::Vector3d(m[0], m[1], m[2]), s * Eigen::Vector3d::Unit(a)) << "axis " << a;
    }
}

TEST(VpsLayered, PlateDepthIsThePlanesExactDepthAtEveryHeightWhereTheSurfaceModelSaturates) {
  const Eigen::Vector3d kN = Eigen::Vector3d(0.3, -0.2, 1).normalized();
  // A 7 x 7 grid of points with tilted normals (the force's direction; the depth is B's) under
  // a random world pose of B, lowered from above the plate to 6 voxels into it.
  std::vector<Eigen::Vector3d> p, n;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b) {
      p.emplace_back(0.0037 * a + 0.00011, 0.0037 * b - 0.00023, 0.0);
      n.push_back(kN);
    }
  auto shell = MakeNestedShell(p, n, {int(p.size())});
  const int count = shell->num_points();
  VpsContactParams params;
  params.penalty.k_C = 2000;
  params.penalty.L = 10;
  VpsContactModel layered("vps", shell, PlateField(), params);
  params.voxmap = VpsVoxmap::kSurface;
  VpsContactModel surface("vps", shell, PlateField(), params);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const Pose X_WB{RotationFromVector(Eigen::Vector3d(u(rng), u(rng), u(rng))), Eigen::Vector3d(0.02, -0.01, 0.03)};
  const Eigen::Matrix3d R = X_WB.R();
  const double kL = params.penalty.k_C * params.penalty.L;
  double surface_deep_max = 0, surface_deep_min = 1e9;
  for (double z = 0.9 * kH; z > -6 * kH; z -= 0.0371 * kH) {
    ContactQuery q;
    q.X_WB = X_WB;
    q.X_WA = X_WB * Pose::FromTranslation(Eigen::Vector3d(0.01, -0.007, z));
    // Every point is kZ0 - z deep: F_B = -k_C L (kZ0 - z) N (L / l scaling, l = all points).
    const double depth = std::max(0.0, kZ0 - z);
    const ContactResult r = layered.Evaluate(q);
    const Eigen::Vector3d F_B = -kL * depth * kN;
    EXPECT_LT((r.on_B.force - R * F_B).norm(), kL * kH / 64 + 1e-9) << "z " << z / kH << " voxels";
    if (depth > kH / 64) EXPECT_EQ(r.stats.points_in_contact, count) << "z " << z;
    if (depth == 0) EXPECT_EQ(r.stats.points_in_contact, 0) << "z " << z;
    // The 1999 model's interior (a voxel below the plate's surface layer) renders a fixed depth.
    if (z < kZ0 - 2 * kH) {
      const double f = surface.Evaluate(q).on_B.force.norm();
      surface_deep_max = std::max(surface_deep_max, f);
      surface_deep_min = std::min(surface_deep_min, f);
    }
  }
  EXPECT_NEAR(surface_deep_max, kL * 0.5 * std::sqrt(3.0) * kH, 1e-5 * kL * kH);
  EXPECT_NEAR(surface_deep_min, surface_deep_max, 1e-5 * kL * kH);
}

// A scene of body A pressed into body B, procedural shapes, no cache.
struct Press {
  Scene scene;
  // A's pose in the world when its deepest point is DEPTH (metres) into B.
  std::function<Pose(double depth)> pose_A;
  // The exact depth of a point in B's frame below B's surface (> 0 inside): the brute-force
  // reference.
  std::function<double(const Eigen::Vector3d& p_B)> depth_B;
};

Scene TwoBodies(const std::string& mesh_A, int resolution_A, const std::string& mesh_B, int resolution_B) {
  Scene scene;
  scene.name = "vps-layered-test";
  scene.pointshell_body.name = "A";
  scene.pointshell_body.mesh = mesh_A;
  scene.pointshell_body.role = "pointshell";
  scene.pointshell_body.field.resolution = resolution_A;
  scene.field_body.name = "B";
  scene.field_body.mesh = mesh_B;
  scene.field_body.role = "field";
  scene.field_body.field.resolution = resolution_B;
  scene.model.penalty.k_C = 2000;
  scene.model.penalty.L = 10;
  return scene;
}

// data/scenes/sphere-on-plate.yaml: a 5 cm ball (64-cell field) on a 20 x 20 x 4 cm plate
// (96-cell field, 2.5 mm voxels; its top at z = 0 lies on a voxel face).
Press SphereOnPlate() {
  Press press;
  press.scene = TwoBodies("sphere:0.05", 64, "box:0.1,0.1,0.02", 96);
  press.scene.field_body.pose = Pose::FromTranslation(Eigen::Vector3d(0, 0, -0.02));
  press.pose_A = [](double depth) { return Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.05 - depth)); };
  press.depth_B = [](const Eigen::Vector3d& p) { return 0.02 - p.z(); };
  return press;
}

// A 3 cm ball into a 5 cm ball along a skew direction.
Press SphereOnSphere() {
  Press press;
  press.scene = TwoBodies("sphere:0.03", 48, "sphere:0.05", 64);
  const Eigen::Vector3d dir = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  press.pose_A = [dir](double depth) {
    return Pose{RotationFromVector(Eigen::Vector3d(0.2, 0.1, -0.3)), (0.08 - depth) * dir};
  };
  press.depth_B = [](const Eigen::Vector3d& p) { return 0.05 - p.norm(); };
  return press;
}

// A 4 x 3 x 2 cm box, tilted, corner first into the plate.
Press TiltedBoxOnPlate() {
  Press press;
  press.scene = TwoBodies("box:0.02,0.015,0.01", 48, "box:0.1,0.1,0.02", 96);
  press.scene.field_body.pose = Pose::FromTranslation(Eigen::Vector3d(0, 0, -0.02));
  const Eigen::Quaterniond R = RotationFromVector(Eigen::Vector3d(0.35, -0.25, 0.1));
  // The lowest corner's height below the box's centre.
  const Eigen::Matrix3d M = R.toRotationMatrix();
  const double low = std::abs(M(2, 0)) * 0.02 + std::abs(M(2, 1)) * 0.015 + std::abs(M(2, 2)) * 0.01;
  press.pose_A = [R, low](double depth) { return Pose{R, Eigen::Vector3d(0.003, -0.002, low - depth)}; };
  press.depth_B = [](const Eigen::Vector3d& p) { return 0.02 - p.z(); };
  return press;
}

// The brute-force reference: every point of MODEL's pointshell at A's pose, its exact depth
// in B along its normal N, summed under the penalty law (F_B = -k sum depth N, k = k_C scaled
// by L / l when l >= L points are inside).
Eigen::Vector3d BruteForce(const VpsContactModel& model, const Press& press, const ContactQuery& q) {
  const Pointshell& s = model.shell();
  const Pose X_BA = q.X_WB.Inverse() * q.X_WA;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int l = 0;
  for (int i = 0; i < s.num_points(); ++i) {
    const Eigen::Vector3d p_B = X_BA * Eigen::Vector3d(s.x[i], s.y[i], s.z[i]);
    const double depth = press.depth_B(p_B);
    if (depth <= 0) continue;
    sum -= depth * (X_BA.rotation * Eigen::Vector3d(s.nx[i], s.ny[i], s.nz[i]));
    ++l;
  }
  const PenaltyParams& pen = press.scene.model.penalty;
  const double k = pen.L > 0 && l >= pen.L ? pen.k_C * pen.L / l : pen.k_C;
  return q.X_WB.R() * (k * sum);
}

struct PressRun {
  std::vector<double> depth, force, reference;  // metres, |F| newtons, brute force |F|
};

// |F| of MODEL_NAME (with the `voxmap` key VOXMAP) pressed DEPTHS into B.
PressRun RunPress(Press& press, const std::string& model_name, VpsVoxmap voxmap, const std::vector<double>& depths) {
  RegisterContactModels();
  press.scene.model_params.Mutable(VpsOwnParamTable()).voxmap = voxmap;
  AssetOptions options;
  options.use_cache = false;
  options.verbose = false;
  SceneAssets assets(press.scene, options);
  std::unique_ptr<ContactModel> model = MakeSceneContactModel(model_name, press.scene, assets);
  auto* vps = dynamic_cast<VpsContactModel*>(model.get());
  EXPECT_NE(vps, nullptr);
  if (!vps) return {};
  EXPECT_EQ(vps->params().voxmap, voxmap) << "the scene key did not reach the model";
  PressRun run;
  for (const double depth : depths) {
    ContactQuery q;
    q.X_WB = press.scene.field_body.pose;
    q.X_WA = press.pose_A(depth);
    run.depth.push_back(depth);
    run.force.push_back(model->Evaluate(q).on_B.force.norm());
    run.reference.push_back(BruteForce(*vps, press, q).norm());
  }
  return run;
}

std::vector<double> Depths(double from, double to, double step) {
  std::vector<double> d;
  for (int i = 0; from + i * step <= to + 1e-12; ++i) d.push_back(from + i * step);
  return d;
}

// The property the layered voxmap promises: |F| > 0 at every depth and no step down of more
// than 10 % as the depth grows; and |F| within REL of the brute-force sum from MIN_DEPTH on.
void ExpectNonZeroNonDecreasingAndNearReference(const PressRun& run, double rel, double min_depth) {
  for (std::size_t i = 0; i < run.force.size(); ++i) {
    const double mm = 1e3 * run.depth[i];
    EXPECT_GT(run.force[i], 0.0) << "no force at " << mm << " mm";
    if (i > 0) EXPECT_GE(run.force[i], 0.9 * run.force[i - 1]) << "force steps down at " << mm << " mm";
    if (run.depth[i] >= min_depth) {
      EXPECT_NEAR(run.force[i], run.reference[i], rel * run.reference[i]) << "at " << mm << " mm";
    }
  }
}

void PrintRun(const char* what, const PressRun& run) {
  std::printf("%s |F| (N) at depth (mm):", what);
  for (std::size_t i = 0; i < run.force.size(); ++i) std::printf(" %.2f:%.1f", 1e3 * run.depth[i], run.force[i]);
  std::printf("\n");
}

TEST(VpsLayered, SphereOnPlateForceIsNonZeroAndNonDecreasingFromAQuarterMillimetreToSix) {
  const std::vector<double> depths = Depths(0.00025, 0.006, 0.00005);
  // The ball turned to a generic orientation (a sphere: the same contact), under the scene's
  // penalty law (k_C 2000, L 10). The plate is a plane: the layered depth is exact but for
  // its 1/64-voxel steps, so the force is the brute force's within 3 %.
  Press turned = SphereOnPlate();
  const auto at_scene_pose = turned.pose_A;
  const Eigen::Quaterniond R = RotationFromVector(Eigen::Vector3d(0.3, -0.5, 0.81).normalized() * 0.7);
  turned.pose_A = [at_scene_pose, R](double depth) {
    Pose X = at_scene_pose(depth);
    X.rotation = R;
    X.translation += Eigen::Vector3d(0.0011, -0.0007, 0);
    return X;
  };
  ExpectNonZeroNonDecreasingAndNearReference(RunPress(turned, "vps", VpsVoxmap::kLayered, depths), 0.03, 0);
  // At the scene's own pose the voxel-centre pointshell is symmetric about the push: whole
  // rings of 4-12 points enter at once, and the L / l law (the mean depth once l >= L) steps
  // down by l / (l + m) as they do, by up to 18 % (at 0.85 mm), exactly as the brute-force sum
  // over the same points does. The sum of depths itself (L = 0) never steps down.
  Press press = SphereOnPlate();
  const PressRun scaled = RunPress(press, "vps", VpsVoxmap::kLayered, depths);
  for (std::size_t i = 0; i < depths.size(); ++i) {
    EXPECT_GT(scaled.force[i], 0.0) << "no force at " << 1e3 * depths[i] << " mm";
    EXPECT_NEAR(scaled.force[i], scaled.reference[i], 0.03 * scaled.reference[i]) << 1e3 * depths[i] << " mm";
  }
  press.scene.model.penalty.L = 0;
  ExpectNonZeroNonDecreasingAndNearReference(RunPress(press, "vps", VpsVoxmap::kLayered, depths), 0.03, 0);
  // The measured table (docs/models.md, baselines/README.md).
  press.scene.model.penalty.L = 10;
  const std::vector<double> table = {0.00025, 0.0005, 0.001, 0.0015, 0.002, 0.0025, 0.003, 0.004, 0.005, 0.006};
  PrintRun("sphere-on-plate vps layered", RunPress(press, "vps", VpsVoxmap::kLayered, table));
  PrintRun("sphere-on-plate vps surface", RunPress(press, "vps", VpsVoxmap::kSurface, table));
}

TEST(VpsLayered, SurfaceKeySelectsThe1999ModelAndItsDeadBandOnSphereOnPlate) {
  // The 1999 surface layer on the same scene: the plate's top lies on a voxel face, the
  // voxel-centre pointshell's lattice has the voxmap's spacing and phase, so from half a
  // voxel (1.25 mm) to a voxel (2.5 mm) deep every point in a surface voxel sits above its
  // centre and none has reached the interior: no force, though the brute force over the same
  // points (voxel centres, the lowest 1.25 mm above the ball's bottom) finds them inside.
  Press press = SphereOnPlate();
  const PressRun run = RunPress(press, "vps", VpsVoxmap::kSurface, Depths(0.0014, 0.0024, 0.0001));
  for (std::size_t i = 0; i < run.force.size(); ++i) {
    EXPECT_EQ(run.force[i], 0.0) << "at " << 1e3 * run.depth[i] << " mm";
    EXPECT_GT(run.reference[i], 2.0) << "at " << 1e3 * run.depth[i] << " mm";
  }
  // The layered default renders the same poses within 3 % of the brute force over its points.
  const PressRun layered = RunPress(press, "vps", VpsVoxmap::kLayered, run.depth);
  for (std::size_t i = 0; i < layered.force.size(); ++i) {
    EXPECT_GT(layered.force[i], 0.0) << "at " << 1e3 * layered.depth[i] << " mm";
    EXPECT_NEAR(layered.force[i], layered.reference[i], 0.03 * layered.reference[i]) << 1e3 * layered.depth[i] << " mm";
  }
}

TEST(VpsLayered, SphereIntoSphereForceIsNonZeroAndNonDecreasing) {
  Press press = SphereOnSphere();
  const PressRun run = RunPress(press, "vps", VpsVoxmap::kLayered, Depths(0.00025, 0.006, 0.00005));
  // B's field is that of an icosphere on a 64-cell grid, the reference the true sphere.
  ExpectNonZeroNonDecreasingAndNearReference(run, 0.1, 0.001);
}

TEST(VpsLayered, TiltedBoxCornerIntoPlateForceIsNonZeroAndNonDecreasing) {
  // The sum of depths (L = 0) never steps down; under L = 10 the force is the brute force's,
  // whose L / l law steps down by up to 10 % where a face's row of points enters at once.
  Press press = TiltedBoxOnPlate();
  const std::vector<double> depths = Depths(0.00025, 0.006, 0.00005);
  const PressRun scaled = RunPress(press, "vps", VpsVoxmap::kLayered, depths);
  for (std::size_t i = 0; i < depths.size(); ++i) {
    EXPECT_GT(scaled.force[i], 0.0) << "no force at " << 1e3 * depths[i] << " mm";
    EXPECT_NEAR(scaled.force[i], scaled.reference[i], 0.03 * scaled.reference[i]) << 1e3 * depths[i] << " mm";
  }
  press.scene.model.penalty.L = 0;
  ExpectNonZeroNonDecreasingAndNearReference(RunPress(press, "vps", VpsVoxmap::kLayered, depths), 0.03, 0);
}

}  // namespace
}  // namespace contactlab
