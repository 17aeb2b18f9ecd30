// The deformable pointshell's BD-tree bound R(q) = R_0 + sum |q_j| rho_j (paper sec. 4.1):
// every point of a node's subtree lies in the sphere of radius R(q) around the node's
// deformed point, for random q, and the bound is reasonably tight.
#include "deform/deformable_pointshell.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "beam_fixture.h"
#include "contact/test_shells.h"

namespace contactlab {
namespace {

// Random points on the surface of the beam [0,1] x [0,0.25] x [0,0.25] with inward normals,
// nested in 4 levels (16, 64, 256, 1024 points).
std::shared_ptr<Pointshell> BeamShell() {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0, 1);
  const Eigen::Vector3d size(1, 0.25, 0.25);
  const double area[3] = {2 * 0.25 * 0.25, 2 * 0.25, 2 * 0.25};  // faces normal to x, y, z
  std::vector<Eigen::Vector3d> p, n;
  while (p.size() < 1024) {
    const double pick = u(rng) * (area[0] + area[1] + area[2]);
    const int axis = pick < area[0] ? 0 : pick < area[0] + area[1] ? 1 : 2;
    Eigen::Vector3d x(u(rng) * size.x(), u(rng) * size.y(), u(rng) * size.z());
    const bool high = u(rng) < 0.5;
    x[axis] = high ? size[axis] : 0;
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    normal[axis] = high ? -1 : 1;
    p.push_back(x);
    n.push_back(normal);
  }
  return testing::MakeNestedShell(p, n, {16, 64, 256, 1024});
}

// The beam shell embedded in the beam's r = 8 StVK model.
const DeformablePointshell& BeamDeformable() {
  static const ReducedModel model =
      BuildReducedModel(testing::MakeBeam(), testing::BeamOptions(8, ReducedModelKind::kStVK), "beam");
  static const DeformablePointshell deformable(BeamShell(), model.mesh, model.basis);
  return deformable;
}

TEST(DeformablePointshell, TreeRadiiBoundEverySubtreePointAtRandomDeformations) {
  const DeformablePointshell& deformable = BeamDeformable();
  ASSERT_EQ(deformable.r(), 8);
  const Pointshell& s = deformable.shell();
  std::mt19937 rng(22);
  double slack_sum = 0;
  int slack_count = 0;
  for (double scale : {0.0, 0.05, 0.3, 1.5}) {
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::VectorXd q = testing::RandomVector(deformable.r(), scale, &rng);
      const Eigen::VectorXd abs_q = q.cwiseAbs();
      std::vector<Eigen::Vector3d> x(std::size_t(s.num_points()));
      for (int i = 0; i < s.num_points(); ++i) x[i] = deformable.points().Position(i, q.data());
      // Largest distance from each node's deformed point to a point of its subtree.
      std::vector<double> reach(std::size_t(s.num_nodes()), 0.0);
      const int deepest = s.num_levels() - 1;
      for (int leaf = s.level_node_begin[deepest]; leaf < s.level_node_begin[deepest + 1]; ++leaf) {
        for (int node = s.node_parent[leaf]; node >= 0; node = s.node_parent[node]) {
          reach[node] = std::max(reach[node], (x[s.node_point[leaf]] - x[s.node_point[node]]).norm());
        }
      }
      for (int node = 0; node < s.level_node_begin[deepest]; ++node) {
        const double R = deformable.Radius(node, abs_q.data());
        ASSERT_LE(reach[node], R * (1 + 1e-5) + 1e-7)
            << "node " << node << " scale " << scale << " trial " << trial;
        if (scale > 0 && R > 0) {
          slack_sum += (R - reach[node]) / R;
          ++slack_count;
        }
        if (scale == 0) {
          EXPECT_EQ(R, double(s.node_radius[node]));
        }
      }
    }
  }
  const double mean_slack = slack_sum / slack_count;
  std::printf("mean relative slack of R(q) over %d node samples: %.3f\n", slack_count, mean_slack);
  RecordProperty("mean_slack", std::to_string(mean_slack));
  EXPECT_LT(mean_slack, 0.6);  // a bound mostly made of its rest radius, not a blanket
}

// Deformed normals are orthogonal to the deformed surface: for neighbouring points on the same
// face, the chord between their deformed positions (a finite difference of the deformation,
// computed without the normal correction) is nearly orthogonal to the corrected normal, far
// more so than to the undeformed normal, which the deformation has rotated. (Continuity across
// tet faces is tested in embedded_points_test.cc.)
TEST(DeformablePointshell, CorrectedNormalsAreOrthogonalToTheDeformedSurface) {
  const ReducedModel model =
      BuildReducedModel(testing::MakeBeam(), testing::BeamOptions(8, ReducedModelKind::kStVK), "beam");
  const auto shell = BeamShell();
  const DeformablePointshell deformable(shell, model.mesh, model.basis);
  const Pointshell& s = *shell;
  const EmbeddedPoints& pts = deformable.points();
  std::mt19937 rng(31);
  for (double scale : {0.1, 0.3, 1.0}) {
    const Eigen::VectorXd q = testing::RandomVector(deformable.r(), scale, &rng);
    double corrected = 0, rotated = 0, exact = 0;
    int pairs = 0;
    for (int i = 0; i < s.num_points(); ++i) {
      const Eigen::Vector3d n0(s.nx[i], s.ny[i], s.nz[i]);
      const Eigen::Vector3d n = pts.CorrectedNormal(i, q.data());
      const Eigen::Vector3d ne = pts.Normal(i, q.data());
      const Eigen::Vector3d xi = pts.Position(i, q.data());
      for (int j = 0; j < s.num_points(); ++j) {
        const Eigen::Vector3d d0 = pts.rest_position(j) - pts.rest_position(i);
        if (j == i || d0.norm() > 0.06 || Eigen::Vector3d(s.nx[j], s.ny[j], s.nz[j]).dot(n0) < 0.999) continue;
        const Eigen::Vector3d chord = (pts.Position(j, q.data()) - xi).normalized();
        corrected += std::fabs(n.dot(chord));
        rotated += std::fabs(n0.dot(chord));
        exact += std::fabs(ne.dot(chord));
        ++pairs;
      }
    }
    ASSERT_GT(pairs, 1000);
    corrected /= pairs;
    rotated /= pairs;
    exact /= pairs;
    std::printf("scale %.1f: mean |n . chord| corrected %.4f, exact push-forward %.4f, undeformed normal %.4f (%d pairs)\n",
                scale, corrected, exact, rotated, pairs);
    EXPECT_GT(rotated, 0.02);                // the deformation does rotate the faces
    // The corrected normals follow them: the exact push-forward up to the chord's curvature,
    // the linear correction (the hot path's) up to its first-order error, which grows as
    // |q|^2 (about 5 degrees at a 20-degree rotation).
    EXPECT_LT(exact, 0.1 * rotated);
    EXPECT_LT(corrected, 0.3 * rotated);
  }
}

// The per-node coherence bound: between two deformations q0 and q, a node's deformed point
// moves and its radius grows by at most sum_j c_nj |q_j - q0_j| together, checked against the
// positions and radii themselves (in double); and it is tighter than the one global bound per
// mode for the nodes near the anchored end.
TEST(DeformablePointshell, NodeTravelBoundsEachNodesBallMotion) {
  const DeformablePointshell& deformable = BeamDeformable();
  const Pointshell& s = deformable.shell();
  const int r = deformable.r();
  const int stride = deformable.points().basis_stride();
  std::mt19937 rng(23);
  int tighter = 0;
  for (double scale : {0.01, 0.2, 1.0}) {
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::VectorXd q0 = testing::RandomVector(r, scale, &rng), q = testing::RandomVector(r, scale, &rng);
      std::vector<float> q0f(stride, 0.f), qf(stride, 0.f);
      for (int j = 0; j < r; ++j) q0f[j] = float(q0[j]), qf[j] = float(q[j]);
      const Eigen::VectorXd a0 = q0.cwiseAbs(), a = q.cwiseAbs();
      double global = 0;
      for (int j = 0; j < r; ++j) global += deformable.mode_travel(j) * std::abs(q[j] - q0[j]);
      for (int node = 0; node < s.num_nodes(); ++node) {
        const int c = s.node_point[node];
        const double moved = (deformable.points().Position(c, q.data()) - deformable.points().Position(c, q0.data())).norm();
        const double grown = deformable.Radius(node, a.data()) - deformable.Radius(node, a0.data());
        const double bound = deformable.NodeTravelF(node, qf.data(), q0f.data());
        ASSERT_LE(moved + grown, bound * (1 + 1e-5) + 1e-9) << "node " << node << " scale " << scale;
        tighter += bound < 0.5 * global;
      }
    }
  }
  EXPECT_GT(tighter, 0);
}

}  // namespace
}  // namespace contactlab
