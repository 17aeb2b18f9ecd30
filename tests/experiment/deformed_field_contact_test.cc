// Deformable-versus-deformable contact (paper sec. 4.2 and 5): a deformable pointshell (a
// clamped beam) against a deformed distance field (a second clamped beam across it), checked
// against references that do not share the model's code: the tree-less traversal, a
// double-precision recomputation of the point forces and of their reduced forces (the sec. 4.2
// field and the nearest proxy by brute force, tests/deformable_references.h), the rigid model
// at q_B = 0, and the symmetry of two identical cantilevers
// pressed against each other.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "pointshell_contact/deformable_contact_models.h"
#include "contact/model_registry.h"
#include "deform/body_dynamics.h"
#include "deform/reduced_integrator.h"
#include "experiment/experiment_config.h"
#include "experiment/studies/contact/contact_study.h"
#include "scene/scene_assets.h"
#include "deformable_fixture.h"
#include "deformable_references.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// Two 20 x 2 x 2 cm beams clamped at body x <= -9 cm: "beam" along world x (A, deformable
// pointshell) and "bar" along world y (B, deformed field), crossing at body x = 7 cm of both,
// B's bottom face GAP metres above A's top face (negative: overlapping).
std::string CrossedBeams(double gap, const std::string& kind_B, int proxies, double alpha, double beta = 0, double L = 0,
                         const std::string& force_at = "nearest") {
  std::ostringstream s;
  s << "name: crossed-beams\n"
       "bodies:\n"
       "  - name: beam\n"
       "    mesh: \"box:0.1,0.01,0.01,4\"\n"
       "    role: pointshell\n"
       "    pointshell: {points: 2048, levels: 4, seed: 1}\n"
       "    field: {resolution: 96}\n"
       "    deformable: {model: linear, modes: 8, cells: 20, E: 5.0e7, nu: 0.3, rho: 1100,\n"
       "                 damping: {alpha: " << alpha << ", beta: " << beta << "}, anchor: {below: [x, -0.09]}}\n"
       "  - name: bar\n"
       "    mesh: \"box:0.1,0.01,0.01,4\"\n"
       "    pose: [0.07, -0.07, " << 0.02 + gap << ", 0.70710678, 0, 0, 0.70710678]\n"
       "    role: field\n"
       "    pointshell: {points: 2048, levels: 4, seed: 1}\n"
       "    field: {resolution: 96}\n"
       "    deformable: {model: " << kind_B << ", modes: 8, cells: 20, E: 5.0e7, nu: 0.3, rho: 1100,\n"
       "                 damping: {alpha: " << alpha << ", beta: " << beta << "}, anchor: {below: [x, -0.09]},\n"
       "                 field: {proxies: " << proxies << ", neighbours: 5, force_at: " << force_at << "}}\n"
       "model: {k_C: 1000, L: " << L << ", max_point_speed: 0.5}\n";
  return s.str();
}

Scene Parse(const std::string& text) { return ParseScene(ConfigNode::LoadString(text, "crossed.yaml")); }

using testing::Assets;
using testing::RandomState;
using testing::RunAllJobs;

TEST(DeformedFieldContact, TheTreeFindsExactlyTheLinearTraversalsContacts) {
  TempDir dir;
  const Scene scene = Parse(CrossedBeams(-0.0005, "linear", 40, 0));
  SceneAssets assets(scene, Assets(dir));
  const auto tree = MakeSceneContactModel("pointshell", scene, assets);
  const auto linear = MakeSceneContactModel("pointshell-linear", scene, assets);
  ASSERT_NE(dynamic_cast<DeformableShellDeformedFieldModel*>(tree.get()), nullptr);
  std::mt19937 rng(5);
  int touching = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const ReducedState qA = RandomState(*assets.A.reduced_model(), 0.002, &rng);
    const ReducedState qB = RandomState(*assets.B.reduced_model(), 0.002, &rng);
    ReducedVector fA[2], fB[2];
    ContactResult res[2];
    for (int m = 0; m < 2; ++m) {
      ContactQuery q;
      q.X_WA = scene.pointshell_body.pose;
      q.X_WB = scene.field_body.pose;
      const BodyDeformation dA{&qA, &fA[m]}, dB{&qB, &fB[m]};
      q.deformation_A = &dA;
      q.deformation_B = &dB;
      res[m] = (m == 0 ? tree : linear)->Evaluate(q);
    }
    EXPECT_EQ(res[0].stats.points_in_contact, res[1].stats.points_in_contact) << "trial " << trial;
    EXPECT_LT(res[0].stats.nodes_visited, res[1].stats.nodes_visited);
    const double scale = 1e-5 * (1 + res[1].on_B.force.norm());
    EXPECT_LT((res[0].on_B.force - res[1].on_B.force).norm(), scale) << "trial " << trial;
    EXPECT_LT((fA[0] - fA[1]).norm(), 1e-5 * (1 + fA[1].norm())) << "trial " << trial;
    EXPECT_LT((fB[0] - fB[1]).norm(), 1e-5 * (1 + fB[1].norm())) << "trial " << trial;
    touching += res[1].stats.points_in_contact > 0;
  }
  EXPECT_GE(touching, 6);
}

TEST(DeformedFieldContact, ReducedForcesAreUTransposeAtThePointsAndTheNearestProxies) {
  TempDir dir;
  const Scene scene = Parse(CrossedBeams(-0.0005, "stvk", 40, 0));
  SceneAssets assets(scene, Assets(dir));
  const auto model = MakeSceneContactModel("pointshell-linear", scene, assets);
  const auto dps = assets.A.deformable_pointshell();
  const auto field = assets.B.deformed_field();
  std::mt19937 rng(9);
  int checked = 0;
  for (int trial = 0; trial < 5; ++trial) {
    const ReducedState qA = RandomState(*assets.A.reduced_model(), 0.0015, &rng);
    const ReducedState qB = RandomState(*assets.B.reduced_model(), 0.0015, &rng);
    ReducedVector fA, fB;
    ContactQuery q;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WB = scene.field_body.pose;
    const BodyDeformation dA{&qA, &fA}, dB{&qB, &fB};
    q.deformation_A = &dA;
    q.deformation_B = &dB;
    const ContactResult res = model->Evaluate(q);
    // The reference in double precision (deformable_references.h): deformed points and
    // normals of A, B's deformed field at q_B by brute force, forces -k d N on A (at the point)
    // and +k d N on B (at the brute-force nearest deformed proxy). A point within float
    // rounding of the surface may fall on either side.
    testing::ReferenceBodies bodies;
    bodies.shell = &dps->shell();
    bodies.dps = dps.get();
    bodies.q_A = qA.q.data();
    bodies.deformed = field.get();
    bodies.q_B = qB.q.data();
    const testing::ReferenceSum ref = testing::ReferenceEq1Sum(bodies, q.X_WA, q.X_WB, scene.model.penalty);
    ASSERT_LE(std::abs(res.stats.points_in_contact - ref.count), testing::NearZero(ref, 1e-7)) << "trial " << trial;
    if (ref.count == 0) continue;
    ++checked;
    EXPECT_LT((Eigen::VectorXd(fA) - ref.f_A).norm(), 1e-3 * ref.f_A.norm()) << "trial " << trial;
    EXPECT_LT((Eigen::VectorXd(fB) - ref.f_B).norm(), 1e-3 * ref.f_B.norm()) << "trial " << trial;
    EXPECT_LT((res.on_B.force - ref.on_B.force).norm(), 1e-3 * ref.on_B.force.norm()) << "trial " << trial;
  }
  EXPECT_GE(checked, 3);
}

TEST(DeformedFieldContact, AtRestTheDeformedFieldRendersLikeTheRigidField) {
  TempDir dir;
  const Scene scene = Parse(CrossedBeams(-0.0005, "linear", 40, 0));
  Scene rigid = scene;
  rigid.field_body.deformable.reset();
  rigid.pointshell_body.deformable.reset();
  Scene rigid_A = scene;
  rigid_A.pointshell_body.deformable.reset();
  SceneAssets assets(rigid_A, Assets(dir)), rigid_assets(rigid, Assets(dir));
  const auto defo = MakeSceneContactModel("pointshell-linear", rigid_A, assets);
  const auto reference = MakeSceneContactModel("pointshell-linear", rigid, rigid_assets);
  ContactQuery q;
  q.X_WA = scene.pointshell_body.pose;
  q.X_WB = scene.field_body.pose;
  const ContactResult a = defo->Evaluate(q), b = reference->Evaluate(q);
  ASSERT_GT(b.stats.points_in_contact, 10);
  EXPECT_NEAR(a.stats.points_in_contact, b.stats.points_in_contact, 0.02 * b.stats.points_in_contact);
  EXPECT_LT((a.on_B.force - b.on_B.force).norm(), 0.02 * b.on_B.force.norm());
  EXPECT_LT((a.on_B.torque - b.on_B.torque).norm(), 0.02 * b.on_B.torque.norm() + 1e-9);
}

// Displacement along z (body frame) of the material point at body x = 7 cm on the beam's axis.
double DeflectionAt(const ReducedModel& model, const ReducedState& s) {
  const EmbeddedPoints p(model.mesh, model.basis, {Eigen::Vector3d(0.07, 0, 0)});
  return p.Displacement(0, s.q.data()).z();
}

void PressTogether(const std::string& force_at) {
  TempDir dir;
  const Scene scene = Parse(CrossedBeams(-0.002, "linear", 80, 50, 2e-4, 10, force_at));
  SceneAssets assets(scene, Assets(dir));
  const auto model = MakeSceneContactModel("pointshell-linear", scene, assets);
  const auto mA = assets.A.reduced_model(), mB = assets.B.reduced_model();
  const SceneDynamics dynamics = MakeSceneDynamics(assets, 1e-3);  // both deform: staggered
  ASSERT_TRUE(dynamics.A && dynamics.B && dynamics.A->staggered() && dynamics.B->staggered());
  BodyDynamics& A = *dynamics.A;
  BodyDynamics& B = *dynamics.B;
  for (int cycle = 0; cycle < 400; ++cycle) {
    ContactQuery q;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WB = scene.field_body.pose;
    q.cycle = cycle;
    q.deformation_A = A.Prepare();
    q.deformation_B = B.Prepare();
    model->Evaluate(q);
    A.Step();  // both step, each with the other held fixed
    B.Step();
  }
  const double dA = DeflectionAt(*mA, A.state()), dB = DeflectionAt(*mB, B.state());
  std::printf("deflections at the crossing: beam %.4g mm, bar %.4g mm\n", 1e3 * dA, 1e3 * dB);
  EXPECT_LT(dA, -1e-4);  // the beam is pushed down, the bar up, by about the same amount
  EXPECT_GT(dB, 1e-4);
  EXPECT_NEAR(-dA / dB, 1.0, 0.3);
  EXPECT_LT(A.KineticEnergy() + B.KineticEnergy(), 1e-9);  // settled
}

TEST(DeformedFieldContact, TwoIdenticalCantileversPressedTogetherDeflectEquallyAndOppositely) {
  PressTogether("weighted");
  PressTogether("nearest");
}

// The runner couples both bodies: the bar (B) comes down onto the beam (A) and both deform.
// A refused query (one body's deformation of the wrong size) still counts how far the other
// body's fitting deformation moved: culled nodes must not sleep through it. The beam is bent
// into the (rigid) bar during a cycle whose query hands the bar a deformation, refused; the
// next cycle, coherent or not, finds the same contacts.
TEST(DeformedFieldContact, ARefusedQueryStillAdvancesTheCoherenceClock) {
  TempDir dir;
  Scene scene = Parse(CrossedBeams(0.002, "linear", 40, 0));
  scene.field_body.deformable.reset();  // coherence is refused against a deformed field
  scene.model.coherence = true;
  SceneAssets assets(scene, Assets(dir));
  const auto coherent = MakeSceneContactModel("pointshell", scene, assets);
  scene.model.coherence = false;
  const auto plain = MakeSceneContactModel("pointshell", scene, assets);
  const auto dps = assets.A.deformable_pointshell();
  const int rA = dps->r();
  const ReducedState restA(rA), wrongB(1);
  ContactQuery q;
  q.X_WA = scene.pointshell_body.pose;
  q.X_WB = scene.field_body.pose;
  int checked = 0;
  for (int j = 0; j < rA; ++j) {
    for (const double sign : {-1.0, 1.0}) {
      // Mode j moving points by up to 6 mm: into the bar, 2 mm away, for some j and sign.
      ReducedState bent(rA);
      bent.q[j] = sign * 0.006 / dps->mode_travel(j);
      const BodyDeformation at_rest_A{&restA}, bent_A{&bent}, wrong_B{&wrongB};
      q.deformation_A = &bent_A;
      q.deformation_B = nullptr;
      q.cycle = 0;
      const ContactResult expected = plain->Evaluate(q);
      if (expected.stats.points_in_contact == 0) continue;
      coherent->Reset();
      q.deformation_A = &at_rest_A;  // cycle 0: apart, every node culled and asleep
      ASSERT_EQ(coherent->Evaluate(q).stats.points_in_contact, 0);
      q.cycle = 1;  // cycle 1: bent into the bar, the bar's deformation refused
      q.deformation_A = &bent_A;
      q.deformation_B = &wrong_B;
      ASSERT_EQ(coherent->Evaluate(q).stats.faults, 1);
      q.cycle = 2;  // cycle 2: the same bend, accepted
      q.deformation_B = nullptr;
      const ContactResult got = coherent->Evaluate(q);
      EXPECT_EQ(got.stats.points_in_contact, expected.stats.points_in_contact) << "mode " << j << " sign " << sign;
      EXPECT_LT((got.on_B.force - expected.on_B.force).norm(), 1e-5 * expected.on_B.force.norm());
      ++checked;
    }
  }
  EXPECT_GE(checked, 1);
}

// Why the paper's model refuses temporal coherence against a deformed field. The clock it would
// need bounds how far any point's distance can drop between queries. The proxies' travel
// (sum_j c_j |dq_j|, c_j the largest proxy displacement per unit q_j) does not bound it: a
// point pulled back through a proxy's deformation gradient moves by |dF| times its distance
// from that proxy, and the eq. (3) weights shift between proxies whose pull-backs disagree. Here
// small steps of q_B lower the deformed distance at points around the bar by more than the
// proxies travel: a node that slept with a margin between the two would wake after its ball
// reached the body. Measured: 9 of 7325 points, all 2-3 cm out (within 5 mm of the surface the
// worst drop was 0.6 times the travel), worst 34 times (7.4 mm for 0.22 mm of proxy travel).
TEST(DeformedFieldContact, CoherenceIsRefusedBecauseDistancesOutrunTheProxies) {
  TempDir dir;
  Scene scene = Parse(CrossedBeams(0.002, "linear", 40, 0));
  SceneAssets assets(scene, Assets(dir));
  const auto field = assets.B.deformed_field();
  const auto model = assets.B.reduced_model();
  const int r = field->r();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(-1, 1);
  DeformedFieldState before(*field), after(*field);
  double worst_ratio = 0, worst_drop = 0;
  int outrun = 0, near = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const ReducedState q0 = RandomState(*model, 0.004, &rng);
    ReducedState q1 = q0;
    double travel = 0;
    for (int j = 0; j < r; ++j) {
      q1.q[j] += 0.02 * q0.q.norm() * uniform(rng);
      travel += field->mode_travel(j) * std::abs(q1.q[j] - q0.q[j]);
    }
    before.Update(*field, q0.q.data());
    after.Update(*field, q1.q.data());
    for (int k = 0; k < 400; ++k) {
      // Points outside the bar, up to 3 cm from it (body frame: 20 x 2 x 2 cm).
      const Eigen::Vector3d x(0.12 * uniform(rng), 0.04 * uniform(rng), 0.04 * uniform(rng));
      const double d0 = field->Distance(before, x), d1 = field->Distance(after, x);
      if (!(d0 > 0 && d0 < 0.03)) continue;
      ++near;
      const double drop = d0 - d1;
      if (drop > travel) ++outrun;
      worst_ratio = std::max(worst_ratio, drop / travel);
      worst_drop = std::max(worst_drop, drop);
    }
  }
  std::printf("distance drops beyond the proxies' travel: %d of %d points, worst %.3g times the travel\n", outrun,
              near, worst_ratio);
  EXPECT_GT(near, 1000);
  EXPECT_GT(outrun, 0);
  EXPECT_GT(worst_ratio, 1.0);

  // So the model refuses coherence against a deformed field, naming it, and renders without it.
  scene.model.coherence = true;
  try {
    MakeSceneContactModel("pointshell", scene, assets);
    ADD_FAILURE() << "coherence against a deformed field was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("coherence"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("deformed distance field"), std::string::npos) << e.what();
  }
  Scene rigid_field = scene;
  rigid_field.field_body.deformable.reset();
  SceneAssets rigid_assets(rigid_field, Assets(dir));
  EXPECT_NO_THROW(MakeSceneContactModel("pointshell", rigid_field, rigid_assets));  // a deformable shell keeps it
  scene.model.coherence = false;
  EXPECT_NO_THROW(MakeSceneContactModel("pointshell", scene, assets));
}

// The runner couples both bodies: the bar (B) comes down onto the beam (A) and both deform;
// asked for temporal coherence against the bar's deformed field, the config is refused when
// it loads, naming the file.
TEST(DeformedFieldContact, TheRunnerCouplesBothBodiesAndRefusesCoherenceAgainstTheDeformedField) {
  TempDir dir;
  std::ofstream(dir / "crossed.yaml") << CrossedBeams(0.002, "stvk", 40, 20, 2e-4, 10);
  const std::string run = "name: defo-defo\nscene: crossed.yaml\nmodels: [pointshell]\n"
                          "trajectory: {type: slide, direction: [0, 0, -1], depth: 0.005, length: 0.0, "
                          "duration: 0.6}\n";
  std::ofstream(dir / "run.yaml") << run;
  const std::vector<JobResult> runs = RunAllJobs(dir);
  ASSERT_EQ(runs.size(), 1u);
  const JobResult& off = runs[0];
  ASSERT_EQ(off.summary.size(), 1u);
  EXPECT_EQ(off.summary[0].modes, 8);
  EXPECT_EQ(off.summary[0].modes_B, 8);
  EXPECT_GT(off.summary[0].median_step_B_us, 0);
  EXPECT_GT(off.summary[0].max_displacement, 1e-4);
  int touching = 0;
  for (std::size_t c = 0; c < off.cycles.size(); ++c) {
    ASSERT_FALSE(off.cycles[c].q_B.empty());
    ASSERT_TRUE(std::isfinite(off.cycles[c].elastic_energy));
    touching += off.cycles[c].contacts > 0;
  }
  EXPECT_GT(touching, 100);

  std::ofstream(dir / "run.yaml") << run << "sweep: {coherence: [true]}\n";
  try {
    RunAllJobs(dir);
    ADD_FAILURE() << "coherence against a deformed field was run";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("run.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("coherence"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace contactlab
