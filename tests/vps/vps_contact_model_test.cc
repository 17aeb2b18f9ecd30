// Tests of the VPS contact model's 1999 surface layer (McNeely et al. 1999 sec. 4.3 tangent-
// plane forces, `voxmap: surface`) and of what both voxmap models share (2006 sec. 3 temporal
// coherence): analytic plate forces, the voxel-boundary force jump against the continuous
// pointshell model, halfspace gradients by finite differences, coherence on = off, no
// allocation, and registration through the model factory. The distance-layered voxmap (the
// default) has its own tests in vps_layered_test.cc.
#include "allocation_counter.h"
#include "baselines/vps/vps_contact_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "contact/register_contact_models.h"
#include "baselines/vps/vps_pointshell.h"
#include "pointshell_contact/pointshell_contact_model.h"
#include "contact/test_shells.h"
#include "scene/scene_assets.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::MakeNestedShell;
using testing::SampleField;
using testing::SphereShell;

constexpr double kH = 0.004;  // field spacing = voxel size, metres

// The halfspace z < Z0 with Z0 = kH / 2: the plane runs through the middle of the voxel layer
// [0, kH], so that layer is surface, [-kH, 0] interior, [kH, 2 kH] proximity.
constexpr double kZ0 = 0.5 * kH;
std::shared_ptr<DistanceField> PlateField() {
  return SampleField([](const Eigen::Vector3d& p) { return p.z() - kZ0; }, Eigen::Vector3d(-0.1, -0.1, -8 * kH),
                     Eigen::Vector3d(0.1, 0.1, 8 * kH), kH);
}

// A 7 x 7 grid of points (spacing 3.7 mm, not a multiple of the voxel size) in A's plane
// z = 0 with inward normal N (normalised here).
std::shared_ptr<Pointshell> PointGrid(const Eigen::Vector3d& N) {
  std::vector<Eigen::Vector3d> p, n;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b) {
      p.emplace_back(0.0037 * a + 0.00011, 0.0037 * b - 0.00023, 0.0);
      n.push_back(N.normalized());
    }
  return MakeNestedShell(p, n, {int(p.size())});
}

std::shared_ptr<Pointshell> OnePoint(const Eigen::Vector3d& N) {
  return MakeNestedShell({Eigen::Vector3d::Zero()}, {N.normalized()}, {1});
}

Pose RandomPose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  return {RotationFromVector(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.5),
          spread * Eigen::Vector3d(u(rng), u(rng), u(rng))};
}

// The time budget counts the points looked at; past it the points reached stand for all. On a
// plate pressed flat every point has the same depth, so any sample stands for the whole exactly:
// the force is the closed form k_C L depth at every budget, with the L / l scaling on (L = 10)
// and off (L = 0: k_C depth n). The stat counts the halvings of the share looked at, and a
// budget of n or more changes nothing.
TEST(VpsContactModel, ABudgetLooksAtAPrefixThatStandsForTheWholeShell) {
  auto shell = PointGrid(Eigen::Vector3d::UnitZ());
  const int n = shell->num_points();  // 49
  for (const int L : {10, 0}) {
    VpsContactParams params;
    params.penalty.k_C = 2000;
    params.penalty.L = L;
    VpsContactModel model("vps", shell, PlateField(), params);
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.01, -0.007, -0.6 * kH));
    const ContactResult full = model.Evaluate(q);
    ASSERT_EQ(full.stats.points_in_contact, n);
    EXPECT_EQ(full.stats.degraded, 0);
    const double depth = -full.on_B.force.z() / (params.penalty.k_C * (L > 0 ? L : n));
    ASSERT_GT(depth, 0.5 * kH);
    for (const int budget : {n, 2 * n}) {  // the same points, summed in another order
      q.node_budget = budget;
      const ContactResult r = model.Evaluate(q);
      EXPECT_LT((r.on_B.AsVector() - full.on_B.AsVector()).norm(), 1e-12 * full.on_B.AsVector().norm());
      EXPECT_EQ(r.stats.degraded, 0);
    }
    for (const int budget : {30, 24, 12, 5, 1}) {
      q.node_budget = budget;
      const ContactResult r = model.Evaluate(q);
      EXPECT_EQ(r.stats.nodes_visited, budget);
      EXPECT_EQ(r.stats.degraded, int(std::ceil(std::log2(double(n) / budget)))) << "budget " << budget;
      EXPECT_NEAR(r.on_B.force.z(), full.on_B.force.z(), 1e-9 * std::abs(full.on_B.force.z())) << "budget " << budget;
      EXPECT_NEAR(r.on_B.force.head<2>().norm(), 0, 1e-9 * std::abs(full.on_B.force.z()));
    }
  }
}

// The points a budget reaches are spread over the shell, not its first rows: a 24 x 24 grid,
// row by row (as a level's Morton order keeps a region together), tilted so that the depth grows
// across the rows from 1 to 2 units. Its first quarter would give about 1.1 units on average;
// the points reached at a quarter of the budget give the mean depth, 1.5, within 5 %.
TEST(VpsContactModel, ABudgetsPointsAreSpreadOverTheShellNotItsFirstRows) {
  constexpr int kSide = 24;
  std::vector<Eigen::Vector3d> p, nrm;
  for (int a = 0; a < kSide; ++a) {
    for (int b = 0; b < kSide; ++b) {
      p.emplace_back(0.002 * a, 0.002 * b, 0.0);
      nrm.push_back(Eigen::Vector3d::UnitZ());
    }
  }
  auto shell = MakeNestedShell(p, nrm, {int(p.size())});
  const int n = shell->num_points();
  VpsContactParams params;
  params.penalty.k_C = 2000;
  params.penalty.L = 0;  // the force is the sum of the depths
  VpsContactModel model("vps", shell, PlateField(), params);
  // Rotated about y, a point's height falls with its x (its row a): depth kH + a kH / 23.
  const double tilt = std::atan(kH / 23 / 0.002);
  ContactQuery q;
  q.X_WA = Pose{RotationFromVector(Eigen::Vector3d(0, tilt, 0)), Eigen::Vector3d(0, 0.001, kZ0 - kH)};
  const ContactResult full = model.Evaluate(q);
  ASSERT_EQ(full.stats.points_in_contact, n);
  const double mean_depth = -full.on_B.force.z() / (params.penalty.k_C * n);
  EXPECT_NEAR(mean_depth, 1.5 * kH, 0.01 * kH);
  for (const int budget : {n / 4, n / 8}) {
    q.node_budget = budget;
    const ContactResult r = model.Evaluate(q);
    EXPECT_GE(r.stats.degraded, 2);
    EXPECT_NEAR(r.on_B.force.z(), full.on_B.force.z(), 0.05 * std::abs(full.on_B.force.z())) << "budget " << budget;
  }
}

TEST(VpsContactModel, SurfaceModelFlatPlateForceIsKLTimesTheTangentPlaneDepthAlongTheNormal) {
  auto shell = PointGrid(Eigen::Vector3d::UnitZ());
  VpsContactParams params;
  params.voxmap = VpsVoxmap::kSurface;
  params.penalty.k_C = 2000;
  params.penalty.L = 10;
  VpsContactModel model("vps", shell, PlateField(), params);
  const int n = shell->num_points();
  std::mt19937 rng(3);
  for (int trial = 0; trial < 6; ++trial) {
    // The same relative pose of A in B under a random world pose of B.
    const Pose X_WB = trial == 0 ? Pose() : RandomPose(rng, 0.1);
    const Eigen::Vector3d shift(0.01, -0.007, 0);  // A's origin in B, besides the height
    const Eigen::Matrix3d R = X_WB.R();
    // Heights of A's plane in B: surface layer below the voxel centres (depth = kZ0 - z), in
    // the interior layer (depth = half diagonal), and above the centres (no force).
    struct Case {
      double z, depth;
    };
    for (const Case& c : {Case{0.2 * kH, 0.3 * kH}, Case{0.45 * kH, 0.05 * kH}, Case{-0.4 * kH, 0.5 * std::sqrt(3.0) * kH},
                          Case{0.7 * kH, 0.0}, Case{1.5 * kH, 0.0}}) {
      ContactQuery q;
      q.X_WB = X_WB;
      q.X_WA = X_WB * Pose::FromTranslation(shift + Eigen::Vector3d(0, 0, c.z));
      const ContactResult r = model.Evaluate(q);
      // Force on B: down (-z in B), k_C L / n per point times n points times the depth.
      const Eigen::Vector3d F_B(0, 0, -params.penalty.k_C * params.penalty.L * c.depth);
      EXPECT_LT((r.on_B.force - R * F_B).norm(), 1e-4 * params.penalty.k_C * kH) << "z " << c.z;
      // Torque about B's origin: the grid's centroid (in B) cross the force.
      Eigen::Vector3d centroid_B = Eigen::Vector3d::Zero();
      for (int i = 0; i < n; ++i) centroid_B += Eigen::Vector3d(shell->x[i], shell->y[i], shell->z[i]);
      centroid_B = centroid_B / n + shift + Eigen::Vector3d(0, 0, c.z);
      EXPECT_LT((r.on_B.torque - R * centroid_B.cross(F_B)).norm(), 1e-6 * params.penalty.k_C * kH) << "z " << c.z;
      EXPECT_EQ(r.stats.points_in_contact, c.depth > 0 ? n : 0) << "z " << c.z;
      EXPECT_NEAR(r.stats.max_penetration, c.depth, 1e-4 * kH);
      EXPECT_DOUBLE_EQ(r.stats.stiffness_scale, c.depth > 0 ? double(params.penalty.L) / n : 1.0);
      EXPECT_EQ(r.stats.nodes_visited, n);
    }
  }
}

TEST(VpsContactModel, SurfaceModelForceJumpsAtVoxelFacesButThePointshellModelsForceIsContinuous) {
  // One point with a tilted normal, in the surface layer, slid along x across a voxel face:
  // the tangent plane moves with the voxel centre (by kH in x), so the depth jumps by kH N.x.
  const Eigen::Vector3d N = Eigen::Vector3d(0.3, 0.1, 1).normalized();
  auto shell = OnePoint(N);
  auto field = PlateField();
  VpsContactParams vps_params;
  vps_params.voxmap = VpsVoxmap::kSurface;
  vps_params.penalty.k_C = 2000;
  VpsContactModel vps("vps", shell, field, vps_params);
  PointshellContactParams ps_params;
  ps_params.penalty.k_C = 2000;
  PointshellContactModel pointshell(PointshellContactModel::Variant::kLinear, shell, field, ps_params);
  const double face_x = vps.voxmap().origin().x() + 25 * kH;  // a voxel face near x = 0
  const double eps = 1e-4 * kH;
  auto force = [&](ContactModel& m, double x) {
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(x, 0.0013, 0.1 * kH));
    return m.Evaluate(q).on_B.force;
  };
  const double k = vps_params.penalty.k_C;
  // Across the face: a jump of about k kH N.x, never more than k times the voxel size.
  const double vps_jump = (force(vps, face_x + eps) - force(vps, face_x - eps)).norm();
  EXPECT_NEAR(vps_jump, k * kH * N.x(), 0.01 * k * kH);
  EXPECT_GT(vps_jump, 0.2 * k * kH);
  EXPECT_LE(vps_jump, k * kH);
  // Within a voxel the VPS force is continuous (moves by k * distance * N.x at most).
  const double vps_inside = (force(vps, face_x + 3 * eps) - force(vps, face_x + eps)).norm();
  EXPECT_LE(vps_inside, k * 2 * eps + 1e-9);
  // The pointshell model's force does not jump over the same motion.
  const double ps_jump = (force(pointshell, face_x + eps) - force(pointshell, face_x - eps)).norm();
  EXPECT_GT(force(pointshell, face_x).norm(), 0.1 * k * kH);  // in contact
  EXPECT_LE(ps_jump, k * 2 * eps * 2 + 1e-6);
  EXPECT_GT(vps_jump, 100 * ps_jump);
}

TEST(VpsContactModel, SurfaceModelSlidingSphereForceStepsAreLargerThanThePointshellModels) {
  // A ball pointshell pressed into the plate and slid in tiny steps over two voxels: VPS's
  // largest step-to-step change is a voxel-face jump; the pointshell model's stays small.
  auto shell = SphereShell(0.03, 128, 2, 5);
  auto field = PlateField();
  // No L / l scaling: its jumps when a point enters contact would hide the voxel artefact.
  VpsContactParams vps_params;
  vps_params.voxmap = VpsVoxmap::kSurface;
  vps_params.penalty.L = 0;
  VpsContactModel vps("vps", shell, field, vps_params);
  PointshellContactParams ps_params;
  ps_params.penalty.L = 0;
  PointshellContactModel pointshell(PointshellContactModel::Variant::kLinear, shell, field, ps_params);
  const double step = 2e-6;  // metres per step
  double max_vps = 0, max_ps = 0;
  Eigen::Vector3d prev_vps = Eigen::Vector3d::Zero(), prev_ps = Eigen::Vector3d::Zero();
  for (int s = 0; s <= 4000; ++s) {
    ContactQuery q;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.0003 + s * step, 0.0002, 0.03 + kZ0 - 0.0015));
    const Eigen::Vector3d f_vps = vps.Evaluate(q).on_B.force, f_ps = pointshell.Evaluate(q).on_B.force;
    ASSERT_GT(f_ps.norm(), 0);
    if (s > 0) {
      max_vps = std::max(max_vps, (f_vps - prev_vps).norm());
      max_ps = std::max(max_ps, (f_ps - prev_ps).norm());
    }
    prev_vps = f_vps;
    prev_ps = f_ps;
  }
  EXPECT_GT(max_vps, 20 * max_ps) << "vps " << max_vps << " N, pointshell " << max_ps << " N";
}

// Both voxmap models, named for the failure messages.
constexpr std::pair<VpsVoxmap, const char*> kVoxmaps[] = {{VpsVoxmap::kLayered, "layered"},
                                                          {VpsVoxmap::kSurface, "surface"}};

TEST(VpsContactModel, TranslationGradientMatchesFiniteDifferencesWithinAVoxel) {
  for (const auto& [voxmap, voxmap_name] : kVoxmaps) {
    SCOPED_TRACE(voxmap_name);
    // The halfspace K_B is the derivative where the depth's gradient is the point's normal: the
    // surface model's tangent planes, and the layered model where the normal is B's (the plate's).
    auto shell = PointGrid(voxmap == VpsVoxmap::kSurface ? Eigen::Vector3d(0.2, -0.1, 1) : Eigen::Vector3d::UnitZ());
    VpsContactParams params;
    params.voxmap = voxmap;
    params.penalty.k_C = 1500;
    VpsContactModel model("vps", shell, PlateField(), params);
    std::mt19937 rng(11);
    ContactQuery q;
    q.X_WB = RandomPose(rng, 0.05);
    q.X_WA = q.X_WB * Pose::FromTranslation(Eigen::Vector3d(0.0021, 0.0013, 0.15 * kH));
    const ContactResult r = model.Evaluate(q);
    ASSERT_EQ(r.stats.points_in_contact, shell->num_points());
    const double delta = 1e-5;  // metres; every point is >= 0.17 mm from a voxel face
    for (int a = 0; a < 3; ++a) {
      ContactQuery plus = q, minus = q;
      plus.X_WB.translation[a] += delta;
      minus.X_WB.translation[a] -= delta;
      const Vector6d fd = (model.Evaluate(plus).on_B.AsVector() - model.Evaluate(minus).on_B.AsVector()) / (2 * delta);
      EXPECT_LT((fd - r.K_B.col(a)).norm(), 1e-3 * r.K_B.col(a).norm() + 1e-6) << "column " << a << "\n"
                                                                              << fd.transpose() << "\n"
                                                                              << r.K_B.col(a).transpose();
    }
  }
}

TEST(VpsContactModel, TemporalCoherenceGivesIdenticalWrenchesWithinTheSpeedBound) {
  for (const auto& [voxmap, voxmap_name] : kVoxmaps) {
    SCOPED_TRACE(voxmap_name);
    // A ball of radius 3 cm wandering in and out of contact with a ball field of radius 5 cm.
    auto shell = SphereShell(0.03, 200, 2, 9);
    auto field = SampleField([](const Eigen::Vector3d& p) { return p.norm() - 0.05; }, Eigen::Vector3d::Constant(-0.065),
                             Eigen::Vector3d::Constant(0.065), kH);
    VpsContactParams params;
    params.voxmap = voxmap;
    params.max_point_speed = 0.5;  // m/s: 0.5 mm per 1 ms cycle
    VpsContactModel plain("vps", shell, field, params);
    params.coherence = true;
    VpsContactModel coherent("vps", shell, field, params);
    ASSERT_GT(coherent.info().wide_voxmap_bytes, 0u);
    // Centre distance r(t) = 9 +- 2 cm (<= 0.13 mm per cycle) on a slowly turning direction
    // (<= 0.11 mm per cycle at 11 cm) and a tumbling orientation (0.003 rad per cycle, <= 0.09 mm
    // at 3 cm): every point moves less than 0.5 mm per cycle.
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    std::int64_t skipped = 0, visits = 0;
    int contact_cycles = 0;
    for (int cycle = 0; cycle < 1500; ++cycle) {
      const double r = 0.09 + 0.02 * std::sin(cycle * 2 * M_PI / 1000);
      const double phi = 0.001 * cycle;
      const Eigen::Vector3d centre = r * Eigen::Vector3d(std::cos(phi), std::sin(phi) * 0.6, std::sin(phi) * 0.8);
      const Eigen::Vector3d w = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
      rotation = (RotationFromVector(0.003 * w) * rotation).normalized();
      ContactQuery q;
      q.cycle = cycle;
      q.X_WA = {rotation, centre};
      const ContactResult a = plain.Evaluate(q), b = coherent.Evaluate(q);
      ASSERT_EQ(a.on_B.force, b.on_B.force) << "cycle " << cycle;
      ASSERT_EQ(a.on_B.torque, b.on_B.torque) << "cycle " << cycle;
      ASSERT_EQ(a.stats.points_in_contact, b.stats.points_in_contact) << "cycle " << cycle;
      EXPECT_EQ(b.stats.nodes_visited + b.stats.nodes_skipped_coherence, shell->num_points());
      skipped += b.stats.nodes_skipped_coherence;
      visits += shell->num_points();
      contact_cycles += a.stats.points_in_contact > 0;
    }
    EXPECT_GT(contact_cycles, 300);
    EXPECT_GT(skipped, visits / 4) << "coherence skipped too little to be tested";
    // After Reset nothing is skipped, even after a jump no speed bound allows.
    coherent.Reset();
    ContactQuery q;
    q.cycle = 1500;
    q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.075, 0, 0));
    const ContactResult a = plain.Evaluate(q), b = coherent.Evaluate(q);
    EXPECT_EQ(b.stats.nodes_skipped_coherence, 0);
    EXPECT_GT(a.stats.points_in_contact, 0);
    EXPECT_EQ(a.on_B.force, b.on_B.force);
  }
}

TEST(VpsContactModel, EvaluateAllocatesNothing) {
  for (const auto& [voxmap, voxmap_name] : kVoxmaps) {
    for (const bool coherence : {false, true}) {
      SCOPED_TRACE(std::string(voxmap_name) + (coherence ? " with coherence" : ""));
      auto shell = SphereShell(0.03, 200, 2, 9);
      auto field = SampleField([](const Eigen::Vector3d& p) { return p.norm() - 0.05; }, Eigen::Vector3d::Constant(-0.065),
                               Eigen::Vector3d::Constant(0.065), kH);
      VpsContactParams params;
      params.voxmap = voxmap;
      params.coherence = coherence;
      VpsContactModel model("vps", shell, field, params);
      std::int64_t contacts = 0;
      const long before = testing::AllocationCount();
      for (int cycle = 0; cycle < 1000; ++cycle) {
        ContactQuery q;
        q.cycle = cycle;
        q.X_WA = Pose::FromTranslation(Eigen::Vector3d(0.078 + 0.004 * std::sin(cycle * 0.01), 0, 0));
        contacts += model.Evaluate(q).stats.points_in_contact;
      }
      EXPECT_EQ(testing::AllocationCount() - before, 0);
      EXPECT_GT(contacts, 0);
    }
  }
}

TEST(VpsContactModel, InfoReportsVoxmapMemoryAndCounts) {
  auto shell = PointGrid(Eigen::Vector3d::UnitZ());
  VpsContactParams params;
  params.coherence = true;
  VpsContactModel model("vps", shell, PlateField(), params);
  params.voxmap = VpsVoxmap::kSurface;
  const VpsModelInfo surface_info = VpsContactModel("vps", shell, PlateField(), params).info();
  const VpsModelInfo info = model.info();
  // The layered voxmap holds 4 bytes a voxel; the surface model none.
  EXPECT_EQ(info.depth_map_bytes, std::size_t(4 * info.voxels));
  EXPECT_EQ(surface_info.depth_map_bytes, 0u);
  EXPECT_EQ(surface_info.voxmap_bytes, info.voxmap_bytes);
  EXPECT_EQ(info.voxels, std::int64_t(info.dims.x()) * info.dims.y() * info.dims.z());
  EXPECT_EQ(info.free + info.proximity + info.surface + info.interior, info.voxels);
  EXPECT_EQ(info.voxmap_bytes, std::size_t((info.voxels + 3) / 4));
  EXPECT_EQ(info.wide_voxmap_bytes, std::size_t(info.voxels));
  EXPECT_EQ(info.points, shell->num_points());
  EXPECT_DOUBLE_EQ(info.voxel_size, kH);
  EXPECT_NEAR(info.interior_depth, 0.5 * std::sqrt(3.0) * kH, 1e-15);
  // One voxel layer of the plate is surface: 50 x 50 voxels.
  EXPECT_EQ(info.surface, std::int64_t(info.dims.x()) * info.dims.y());
}

TEST(VpsContactModel, BadParametersThrow) {
  auto shell = PointGrid(Eigen::Vector3d::UnitZ());
  auto field = PlateField();
  VpsContactParams params;
  params.penalty.k_C = -1;
  EXPECT_THROW(VpsContactModel("vps", shell, field, params), Error);
  params = {};
  params.max_point_speed = 0;
  EXPECT_THROW(VpsContactModel("vps", shell, field, params), Error);
  params = {};
  EXPECT_THROW(VpsContactModel("vps", nullptr, field, params), Error);
  EXPECT_THROW(VpsContactModel("vps", shell, nullptr, params), Error);
  EXPECT_THROW(BuildVpsPointshell(*field, 0.0), Error);
}

TEST(VpsPointshell, PointsAreSurfaceVoxelCentresWithInwardNormals) {
  const double R = 0.03;
  auto field = SampleField([R](const Eigen::Vector3d& p) { return p.norm() - R; }, Eigen::Vector3d::Constant(-0.04),
                           Eigen::Vector3d::Constant(0.04), 0.002);
  const double v = 0.0025;
  const Pointshell shell = BuildVpsPointshell(*field, v, 3);
  ASSERT_GT(shell.num_points(), 0);
  EXPECT_EQ(shell.method, "voxel");
  EXPECT_EQ(shell.num_levels(), 1);
  // About 1.5 area / v^2 voxels are crossed by the surface.
  EXPECT_NEAR(shell.num_points() / (1.5 * 4 * M_PI * R * R / (v * v)), 1.0, 0.15);
  for (int i = 0; i < shell.num_points(); ++i) {
    const Eigen::Vector3d p(shell.x[i], shell.y[i], shell.z[i]), n(shell.nx[i], shell.ny[i], shell.nz[i]);
    // On the voxel lattice from the field box corner, within half a diagonal of the surface.
    const Eigen::Vector3d lattice = (p - Eigen::Vector3d::Constant(-0.04)) / v - Eigen::Vector3d::Constant(0.5);
    EXPECT_LT((lattice - lattice.array().round().matrix()).norm(), 1e-3);
    EXPECT_LE(std::abs(p.norm() - R), 0.5 * std::sqrt(3.0) * v + 1e-4);
    EXPECT_GT(n.dot(-p.normalized()), 0.99);  // inward
  }
}

// A ball (A) pressed 2 mm into a plate (B); procedural shapes, no cache.
Scene BallOnPlateScene() {
  Scene scene;
  scene.name = "vps-test";
  scene.pointshell_body.name = "ball";
  scene.pointshell_body.mesh = "sphere:0.03,3";
  scene.pointshell_body.role = "pointshell";
  scene.pointshell_body.pose = Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.028));
  scene.pointshell_body.pointshell.points = 1024;
  scene.pointshell_body.pointshell.levels = 2;
  scene.pointshell_body.pointshell.method = "random";
  scene.pointshell_body.field.resolution = 24;
  scene.field_body.name = "plate";
  scene.field_body.mesh = "box:0.06,0.06,0.01";
  scene.field_body.role = "field";
  scene.field_body.pose = Pose::FromTranslation(Eigen::Vector3d(0, 0, -0.01));
  scene.field_body.field.resolution = 40;
  scene.model.penalty.k_C = 2000;
  return scene;
}

TEST(VpsRegistration, BothModelsAreMadeByNameAndPushThePlateDown) {
  RegisterContactModels();
  const std::vector<std::string> names = ContactModelNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "vps"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "vps-repulsion"), names.end());
  const Scene scene = BallOnPlateScene();
  AssetOptions options;
  options.use_cache = false;
  options.verbose = false;
  SceneAssets assets(scene, options);
  ContactQuery q;
  q.X_WA = scene.pointshell_body.pose;
  q.X_WB = scene.field_body.pose;
  double fz[2];
  int slot = 0;
  for (const char* name : {"vps", "vps-repulsion"}) {
    SCOPED_TRACE(name);
    std::unique_ptr<ContactModel> model = MakeSceneContactModel(name, scene, assets);
    ASSERT_NE(model, nullptr);
    EXPECT_EQ(model->name(), name);
    auto* vps = dynamic_cast<VpsContactModel*>(model.get());
    ASSERT_NE(vps, nullptr);
    EXPECT_DOUBLE_EQ(vps->info().voxel_size, assets.B.field()->spacing());
    EXPECT_EQ(vps->shell().method, std::string(name) == "vps" ? "voxel" : "random");
    const ContactResult r = model->Evaluate(q);
    EXPECT_GT(r.stats.points_in_contact, 0);
    EXPECT_LT(r.on_B.force.z(), 0);
    EXPECT_LT(r.on_B.force.head<2>().norm(), 0.3 * std::abs(r.on_B.force.z()));
    fz[slot++] = r.on_B.force.z();
  }
  // Same order of magnitude: both are k L times a mean depth of about a millimetre.
  EXPECT_GT(fz[0] / fz[1], 0.3);
  EXPECT_LT(fz[0] / fz[1], 3.0);
}

}  // namespace
}  // namespace contactlab
