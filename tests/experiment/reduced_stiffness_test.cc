// The reduced contact stiffness of the paper's model (Barbič & James 2008, sec. 4 and 5) against
// central differences of the reduced contact force f(q). The model returns f and K = -df/dq
// under the sec. 5 halfspace rule, K = k sum_i w_i w_i^T with w_i = U_i^T N_i
// (contact/reduced_force_sum.h). For a deformable pointshell A on a rigid flat plate the rule
// is nearly exact (the field's gradient is the plate normal, which the bottom points' normals
// equal; what it leaves out is the turn of the normals, k d dN/dq, and the points near the
// bottom's edges, whose normals lean: 4 % here).
// For a rigid pointshell on a deformed field B it is an approximation: it leaves out how the
// pull-back's gradients and the eq. (3) weights change with q_B, and with force_at: nearest the
// force acts at one proxy while d depends on k of them. L = 0 keeps k fixed, so f is
// continuous in q and the differences see no jump of the L / l scaling.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>

#include "contact/model_registry.h"
#include "deformable_fixture.h"
#include "deformable_references.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "test_support.h"
#include "util/config_node.h"

namespace contactlab {
namespace {

using testing::Assets;
using testing::TempDir;

// A flat-bottomed block (6 x 6 x 1 cm, A) DEPTH into a wider plate (12 x 12 x 0.8 cm, B, top
// face at z = 4 mm), yawed so nothing is axis-aligned in the plate's frame. DEFORMABLE: "A" or
// "B" carries a small reduced model (linear modal, 6 modes, 10 cells, free). The block's
// pointshell samples its level set at random: particle repulsion settles a row of points on
// the block's bottom edges, whose bisector normals (45 degrees off the plate normal) touch at
// any depth and put some 12 % of the stiffness where the halfspace rule does not hold; random
// samples seldom lie within a voxel of an edge, and the 128-cell field keeps that voxel small.
std::string BlockOnPlate(double depth, const std::string& deformable, const std::string& force_at = "nearest") {
  const std::string small = "{model: linear, modes: 6, cells: 10, E: 1.0e6, nu: 0.4, rho: 1000";
  std::ostringstream s;
  s << "name: block-on-plate\nbodies:\n"
       "  - name: block\n"
       "    mesh: \"box:0.03,0.03,0.005,6\"\n"
       "    pose: [0.003, -0.002, "
    << 0.009 - depth
    << ", 0.98768834, 0, 0, 0.15643447]\n"
       "    role: pointshell\n"
       "    pointshell: {points: 2048, levels: 3, seed: 1, method: random}\n"
       "    field: {resolution: 128}\n";
  if (deformable == "A") s << "    deformable: " << small << "}\n";
  s << "  - name: plate\n"
       "    mesh: \"box:0.06,0.06,0.004,6\"\n"
       "    role: field\n"
       "    field: {resolution: 64}\n";
  if (deformable == "B") s << "    deformable: " << small << ", field: {proxies: 40, neighbours: 5, force_at: " << force_at << "}}\n";
  s << "model: {k_C: 1000, L: 0, coherence: false}\n";
  return s.str();
}

Scene Parse(const std::string& text) { return ParseScene(ConfigNode::LoadString(text, "block-on-plate.yaml")); }

struct Reduced {
  Eigen::VectorXd f;
  Eigen::MatrixXd K;
  int contacts = 0;
};

// The model's reduced force and stiffness of the deformable body (A when ON_A) at Q.
Reduced Evaluate(ContactModel& model, const Scene& scene, bool on_A, const ReducedState& q) {
  ReducedVector f;
  ReducedMatrix K;
  const BodyDeformation d{&q, &f, &K};
  ContactQuery query;
  query.X_WA = scene.pointshell_body.pose;
  query.X_WB = scene.field_body.pose;
  (on_A ? query.deformation_A : query.deformation_B) = &d;
  model.Reset();
  const ContactResult r = model.Evaluate(query);
  return {Eigen::VectorXd(f), Eigen::MatrixXd(K), r.stats.points_in_contact};
}

struct Comparison {
  double error = 0;            // |K - K_fd|_F / |K_fd|_F
  double symmetric_error = 0;  // |K - sym(K_fd)|_F / |K|_F
  double asymmetry = 0;        // |K_fd - K_fd^T|_F / |K_fd|_F
  double min_eigenvalue = 0;   // of K, relative to its largest
  double K_asymmetry = 0;      // |K - K^T|_F / |K|_F
  int contacts = 0;
  int flips = 0;               // points changing side of the surface over all steps
  int proxy_switches = 0;      // points in contact whose nearest proxy changes over all steps
};

// K at Q against -df/dq by central differences, column j with the step moving any point by
// about STEP metres (h_j = STEP / mode_travel_j). Flips and nearest-proxy switches counted by
// the double-precision reference (deformable_references.h) at q +- h_j e_j.
Comparison CompareWithFiniteDifferences(ContactModel& model, const Scene& scene, SceneAssets& assets, bool on_A,
                                        const ReducedState& q, double step) {
  const Reduced at = Evaluate(model, scene, on_A, q);
  const int r = int(at.f.size());
  testing::ReferenceBodies bodies;
  bodies.shell = assets.A.pointshell().get();
  std::shared_ptr<const DeformablePointshell> dps;
  std::shared_ptr<const DeformedDistanceField> deformed;
  if (on_A) {
    dps = assets.A.deformable_pointshell();
    bodies.dps = dps.get();
    bodies.field = assets.B.field().get();
  } else {
    deformed = assets.B.deformed_field();
    bodies.deformed = deformed.get();
    bodies.weighted = deformed->force_at() == DeformedFieldOptions::ForceAt::kWeightedProxies;
  }
  auto reference = [&](const ReducedState& s, std::vector<int>* nearest) {
    (on_A ? bodies.q_A : bodies.q_B) = s.q.data();
    const testing::ReferenceSum sum = testing::ReferenceEq1Sum(bodies, scene.pointshell_body.pose,
                                                               scene.field_body.pose, scene.model.penalty);
    if (nearest != nullptr && deformed) {
      const Pose X_BA = scene.field_body.pose.Inverse() * scene.pointshell_body.pose;
      nearest->assign(sum.d.size(), -1);
      for (std::size_t i = 0; i < sum.d.size(); ++i) {
        if (sum.d[i] >= 0) continue;
        const Eigen::Vector3d x_B = X_BA * Eigen::Vector3d(bodies.shell->x[i], bodies.shell->y[i], bodies.shell->z[i]);
        testing::ReferenceDeformedDistance(*deformed, s.q.data(), x_B, &(*nearest)[i]);
      }
    }
    return sum;
  };
  Comparison c;
  c.contacts = at.contacts;
  Eigen::MatrixXd J(r, r);
  for (int j = 0; j < r; ++j) {
    const double travel = on_A ? dps->mode_travel(j) : deformed->mode_travel(j);
    const double h = step / travel;
    ReducedState plus = q, minus = q;
    plus.q[j] += h;
    minus.q[j] -= h;
    J.col(j) = (Evaluate(model, scene, on_A, plus).f - Evaluate(model, scene, on_A, minus).f) / (2 * h);
    std::vector<int> near_plus, near_minus;
    const testing::ReferenceSum sp = reference(plus, &near_plus), sm = reference(minus, &near_minus);
    for (std::size_t i = 0; i < sp.d.size(); ++i) {
      if ((sp.d[i] < 0) != (sm.d[i] < 0)) {
        ++c.flips;
      } else if (sp.d[i] < 0 && !near_plus.empty() && near_plus[i] != near_minus[i]) {
        ++c.proxy_switches;
      }
    }
  }
  const Eigen::MatrixXd K_fd = -J;
  const Eigen::MatrixXd sym = 0.5 * (K_fd + K_fd.transpose());
  c.error = (at.K - K_fd).norm() / K_fd.norm();
  c.symmetric_error = (at.K - sym).norm() / at.K.norm();
  c.asymmetry = (K_fd - K_fd.transpose()).norm() / K_fd.norm();
  c.K_asymmetry = (at.K - at.K.transpose()).norm() / at.K.norm();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (at.K + at.K.transpose()));
  c.min_eigenvalue = eig.eigenvalues().minCoeff() / eig.eigenvalues().maxCoeff();
  return c;
}

void Print(const char* what, const Comparison& c) {
  std::printf("%s: %d contacts; |K - K_fd|/|K_fd| = %.3g, |K - sym K_fd|/|K| = %.3g, asymmetry of K_fd %.3g, "
              "of K %.3g, smallest eigenvalue of K %.3g of the largest; %d points flipped, %d nearest proxies "
              "switched\n",
              what, c.contacts, c.error, c.symmetric_error, c.asymmetry, c.K_asymmetry, c.min_eigenvalue, c.flips,
              c.proxy_switches);
}

// What every comparison checks besides the error against the differences: the model's K is
// symmetric positive semidefinite (k sum w w^T), and the differences measured a derivative (at
// most 1 % of the points in contact changed side or nearest proxy over the steps).
void ExpectWellFormed(const char* what, const Comparison& c) {
  EXPECT_GT(c.contacts, 100) << what;
  EXPECT_LT(c.K_asymmetry, 1e-12) << what;
  EXPECT_GT(c.min_eigenvalue, -1e-9) << what;
  EXPECT_LE(c.flips + c.proxy_switches, c.contacts / 100) << what;
}

// Steps of the differences: moving any point by about 1 and 10 micrometres, far below the
// 0.1 mm depth (no point changes side; the two agree, so neither is rounding noise).
constexpr double kSteps[] = {1e-6, 1e-5};

// A deformable flat-bottomed block pressed 0.1 mm into a rigid plate, at rest and bent: the
// halfspace rule is the derivative of f but for the turn of the normals (k sum d U^T dN/dq)
// and for the few points within a voxel of the block's bottom edges, whose field normals lean
// off the plate normal.
TEST(ReducedStiffness, DeformablePointshellOnARigidPlateMatchesFiniteDifferences) {
  TempDir dir;
  const Scene scene = Parse(BlockOnPlate(1e-4, "A"));
  SceneAssets assets(scene, Assets(dir));
  const auto model = MakeSceneContactModel("pointshell-linear", scene, assets);
  std::mt19937 rng(4);
  const ReducedState rest(assets.A.reduced_model()->r());
  const ReducedState bent = testing::RandomState(*assets.A.reduced_model(), 2e-4, &rng);
  for (const double step : kSteps) {
    for (const ReducedState* q : {&rest, &bent}) {
      const Comparison c = CompareWithFiniteDifferences(*model, scene, assets, true, *q, step);
      char what[120];
      std::snprintf(what, sizeof what, "A at %s, step %.0e m", q == &rest ? "rest" : "q (0.2 mm)", step);
      Print(what, c);
      ExpectWellFormed(what, c);
      // Measured (Release, 757 and 754 contacts, no point flipped): |K - K_fd| / |K_fd| 0.039
      // and 0.040 at both steps, of which about 0.025 the edge points and 0.025 the normals'
      // turn (found by forming both terms in double precision); sym(K_fd) within 0.040 of K,
      // K_fd asymmetric by 0.012-0.015. With repulsion sampling (edge rows) it was 0.18.
      EXPECT_LT(c.error, 0.06) << what;
      EXPECT_LT(c.symmetric_error, 0.06) << what;
    }
  }
}

// A rigid flat-bottomed block pressed 0.1 mm into a deformable plate's deformed field, at rest
// and bent, with the plate's force at its nearest proxy and spread over the query's k proxies.
// The rule is an approximation here: it leaves out how the pull-back moves with q beyond the
// proxies' own displacement (the gradient F_j times the lever x - p_j) and, away from rest, how
// the weights change; with force_at: nearest the force acts through one proxy while d moves
// with k of them. The bound is one a wrong sign (error 2) or a factor k off by 2 (0.5 or more)
// fails.
TEST(ReducedStiffness, RigidPointshellOnADeformedFieldIsApproximatedByTheHalfspaceRule) {
  for (const char* force_at : {"nearest", "weighted"}) {
    TempDir dir;
    const Scene scene = Parse(BlockOnPlate(1e-4, "B", force_at));
    SceneAssets assets(scene, Assets(dir));
    const auto model = MakeSceneContactModel("pointshell-linear", scene, assets);
    std::mt19937 rng(4);
    const ReducedState rest(assets.B.reduced_model()->r());
    const ReducedState bent = testing::RandomState(*assets.B.reduced_model(), 2e-4, &rng);
    for (const double step : kSteps) {
      for (const ReducedState* q : {&rest, &bent}) {
        const Comparison c = CompareWithFiniteDifferences(*model, scene, assets, false, *q, step);
        char what[120];
        std::snprintf(what, sizeof what, "B (%s) at %s, step %.0e m", force_at, q == &rest ? "rest" : "q (0.2 mm)", step);
        Print(what, c);
        ExpectWellFormed(what, c);
        // Measured (Release, 757 contacts, no point flipped, no nearest proxy switched):
        // nearest |K - K_fd| / |K_fd| 0.084, sym(K_fd) within 0.085 of K, K_fd asymmetric by
        // 0.048; weighted 0.16, 0.19 and 0.018 (more symmetric, since force and distance use
        // the same weights, but farther from the differences). The same at 0.5 mm depth.
        EXPECT_LT(c.error, 0.25) << what;
        EXPECT_LT(c.symmetric_error, 0.25) << what;
      }
    }
  }
}

}  // namespace
}  // namespace contactlab
