// A deformable pointshell in contact (paper sec. 4.1 and 5), checked against references that
// do not share its code: Euler–Bernoulli beam theory for a cantilever pressed by a probe, the
// tree-less traversal for the BD-tree culling, a double-precision recomputation of the point
// forces for the reduced force and Newton's third law, and energy bookkeeping for the
// two-way coupling.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "pointshell_contact/deformable_contact_models.h"
#include "pointshell_contact/pointshell_contact_model.h"
#include "contact/model_registry.h"
#include "deform/reduced_integrator.h"
#include "experiment/experiment_config.h"
#include "experiment/studies/contact/contact_study.h"
#include "scene/scene_assets.h"
#include "deformable_fixture.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// A 20 x 2 x 2 cm beam clamped at x <= -9 cm (body A, deformable) and a 1 cm probe above its
// free end (body B). CELLS, KIND and the damping are filled in per test.
std::string BeamScene(int cells, const std::string& kind, double alpha, double beta, double probe_z = 0.0205,
                      double L = 10, double max_point_speed = 0.5) {
  std::ostringstream s;
  s << "name: beam-probe\n"
       "bodies:\n"
       "  - name: beam\n"
       "    mesh: \"box:0.1,0.01,0.01,4\"\n"
       "    role: pointshell\n"
       "    pointshell: {points: 2048, levels: 4, seed: 1}\n"
       "    field: {resolution: 96}\n"
       "    deformable: {model: "
    << kind << ", modes: 10, cells: " << cells
    << ", E: 5.0e7, nu: 0.3, rho: 1100, damping: {alpha: " << alpha << ", beta: " << beta
    << "}, anchor: {below: [x, -0.09]}}\n"
       "  - name: probe\n"
       "    mesh: \"sphere:0.01,3\"\n"
       "    pose: [0.07, 0, "
    << probe_z
    << ", 1, 0, 0, 0]\n"
       "    role: field\n"
       "    field: {resolution: 48}\n"
       "model: {k_C: 1000, L: "
    << L << ", max_point_speed: " << max_point_speed << "}\n";
  return s.str();
}

Scene ParseBeam(const std::string& text) { return ParseScene(ConfigNode::LoadString(text, "beam.yaml")); }

using testing::Assets;
using testing::RandomState;
using testing::RunAllJobs;

TEST(DeformableContact, TheTreeFindsExactlyTheLinearTraversalsContactsAtDeformedStates) {
  TempDir dir;
  const Scene scene = ParseBeam(BeamScene(20, "stvk", 0, 0, 0.0195));
  SceneAssets assets(scene, Assets(dir));
  const auto tree = MakeSceneContactModel("pointshell", scene, assets);
  const auto linear = MakeSceneContactModel("pointshell-linear", scene, assets);
  ASSERT_NE(dynamic_cast<DeformablePointshellContactModel*>(tree.get()), nullptr);
  std::mt19937 rng(5);
  int touching = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const ReducedState state = RandomState(*assets.A.reduced_model(), 0.004, &rng);
    ReducedVector f_tree, f_linear;
    ContactQuery q;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WB = scene.field_body.pose;
    const BodyDeformation d_tree{&state, &f_tree}, d_linear{&state, &f_linear};
    q.deformation_A = &d_tree;
    const ContactResult a = tree->Evaluate(q);
    q.deformation_A = &d_linear;
    const ContactResult b = linear->Evaluate(q);
    // The BD-tree bound culls only subtrees with no point in contact: same points, same sums.
    EXPECT_EQ(a.stats.points_in_contact, b.stats.points_in_contact) << "trial " << trial;
    EXPECT_LT(a.stats.nodes_visited, b.stats.nodes_visited);
    const double scale = 1e-5 * (1 + b.on_B.force.norm());
    EXPECT_LT((a.on_B.force - b.on_B.force).norm(), scale) << "trial " << trial;
    EXPECT_LT((a.on_B.torque - b.on_B.torque).norm(), scale * 0.1) << "trial " << trial;
    EXPECT_LT((f_tree - f_linear).norm(), 1e-5 * (1 + f_linear.norm())) << "trial " << trial;
    touching += b.stats.points_in_contact > 0;
  }
  EXPECT_GE(touching, 10);  // the deformations move the beam into and out of the probe
}

TEST(DeformableContact, ReducedForceIsUTransposeOfThePointForcesAndOppositeForcesBalance) {
  TempDir dir;
  const Scene scene = ParseBeam(BeamScene(20, "stvk", 0, 0, 0.0195, 0));
  SceneAssets assets(scene, Assets(dir));
  const auto model = MakeSceneContactModel("pointshell-linear", scene, assets);
  const auto dps = assets.A.deformable_pointshell();
  const auto field = assets.B.field();
  const Pointshell& s = dps->shell();
  std::mt19937 rng(9);
  for (int trial = 0; trial < 5; ++trial) {
    const ReducedState state = RandomState(*assets.A.reduced_model(), 0.003, &rng);
    ReducedVector f_q;
    ContactQuery q;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WB = scene.field_body.pose;
    const BodyDeformation d{&state, &f_q};
    q.deformation_A = &d;
    const ContactResult res = model->Evaluate(q);
    // The reference, in double precision: every point at X + U q, its corrected normal, the
    // penalty force -k d N on A, summed as point forces and as U^T F.
    const Pose X_BA = q.X_WB.Inverse() * q.X_WA;
    Eigen::VectorXd f_ref = Eigen::VectorXd::Zero(dps->r());
    Eigen::Vector3d F_on_A = Eigen::Vector3d::Zero();
    int contacts = 0;
    for (int i = 0; i < s.level_point_end.back(); ++i) {
      const Eigen::Vector3d x_A = dps->points().Position(i, state.q.data());
      const double d = field->Distance(X_BA * x_A);
      if (d >= 0) continue;
      ++contacts;
      const Eigen::Vector3d F_A = -scene.model.penalty.k_C * d * dps->points().CorrectedNormal(i, state.q.data());
      f_ref += dps->points().Basis(i).transpose() * F_A;
      F_on_A += q.X_WA.R() * F_A;
    }
    ASSERT_EQ(res.stats.points_in_contact, contacts) << "trial " << trial;
    if (contacts == 0) continue;
    EXPECT_LT((Eigen::VectorXd(f_q) - f_ref).norm(), 1e-3 * f_ref.norm()) << "trial " << trial;
    EXPECT_LT((F_on_A + res.on_B.force).norm(), 1e-3 * F_on_A.norm()) << "trial " << trial;
  }
}

// A deformation of another size than the body's is refused where it enters the model: no force,
// one fault, for each pair of sides and each variant; the right size after it renders again.
TEST(DeformableContact, ADeformationOfTheWrongSizeIsAFaultNotARestState) {
  TempDir dir;
  const Scene scene = ParseBeam(BeamScene(20, "stvk", 0, 0, 0.0195));
  SceneAssets assets(scene, Assets(dir));
  const Scene swapped = scene.Swapped();
  SceneAssets swapped_assets(swapped, Assets(dir));
  const int r = assets.A.reduced_model()->r();
  const ReducedState rest(r), wrong(r + 1);
  for (const char* name : {"pointshell", "pointshell-linear"}) {
    for (const bool field_side : {false, true}) {
      const Scene& sc = field_side ? swapped : scene;
      const auto model = MakeSceneContactModel(name, sc, field_side ? swapped_assets : assets);
      ContactQuery q;
      q.X_WA = sc.pointshell_body.pose;
      q.X_WB = sc.field_body.pose;
      ReducedVector f;
      const BodyDeformation at_rest{&rest, &f}, bad{&wrong, &f};
      (field_side ? q.deformation_B : q.deformation_A) = &at_rest;
      const ContactResult good = model->Evaluate(q);
      ASSERT_GT(good.stats.points_in_contact, 0) << name << " field side " << field_side;
      EXPECT_EQ(good.stats.faults, 0);
      (field_side ? q.deformation_B : q.deformation_A) = &bad;
      const ContactResult refused = model->Evaluate(q);
      EXPECT_EQ(refused.stats.faults, 1) << name << " field side " << field_side;
      EXPECT_EQ(refused.stats.points_in_contact, 0);
      EXPECT_EQ(refused.on_B.force.norm(), 0.0);
      (field_side ? q.deformation_B : q.deformation_A) = &at_rest;
      const ContactResult again = model->Evaluate(q);
      EXPECT_EQ(again.stats.points_in_contact, good.stats.points_in_contact);
    }
  }
}

// Elastic + kinetic energy plus the penalty contact's potential (1/2) k sum d^2 (L = 0: k fixed).
struct CoupledRun {
  double initial = 0, max_total = 0, final_kinetic = 0, peak_kinetic = 0;
  bool finite = true;
};

CoupledRun RunCoupled(double alpha, double beta, double seconds, bool implicit_contact = true) {
  TempDir dir;
  const Scene scene = ParseBeam(BeamScene(20, "stvk", alpha, beta, 0.0185, 0));
  SceneAssets assets(scene, Assets(dir));
  const auto model = MakeSceneContactModel("pointshell-linear", scene, assets);
  const auto rm = assets.A.reduced_model();
  IntegratorOptions io;
  io.mass_damping = alpha;
  io.stiffness_damping = beta;
  ReducedIntegrator integrator(rm->forces, io);
  const auto dps = assets.A.deformable_pointshell();
  const auto field = assets.B.field();
  const Pose X_BA = scene.field_body.pose.Inverse() * scene.pointshell_body.pose;
  const auto contact_energy = [&](const ReducedState& st) {
    double e = 0;
    for (int i = 0; i < dps->shell().level_point_end.back(); ++i) {
      const double d = field->Distance(X_BA * dps->points().Position(i, st.q.data()));
      if (d < 0) e += 0.5 * scene.model.penalty.k_C * d * d;
    }
    return e;
  };
  CoupledRun run;
  ReducedVector f;
  ReducedMatrix K;
  const int cycles = int(std::lround(seconds / io.time_step));
  for (int k = 0; k <= cycles; ++k) {
    const ReducedState& st = integrator.state();
    const double total = integrator.PotentialEnergy() + integrator.KineticEnergy() +
                         (k % 50 == 0 || k == cycles ? contact_energy(st) : 0.0);
    if (k == 0) run.initial = total;
    if (k % 50 == 0) run.max_total = std::max(run.max_total, total);
    run.peak_kinetic = std::max(run.peak_kinetic, integrator.KineticEnergy());
    run.finite = run.finite && std::isfinite(total);
    if (k == cycles) break;
    ContactQuery q;
    q.X_WA = scene.pointshell_body.pose;
    q.X_WB = scene.field_body.pose;
    q.cycle = k;
    const BodyDeformation d{&st, &f, implicit_contact ? &K : nullptr};
    q.deformation_A = &d;
    model->Evaluate(q);
    integrator.Step(f, implicit_contact ? &K : nullptr);
  }
  run.final_kinetic = integrator.KineticEnergy();
  return run;
}

TEST(DeformableContact, UndampedCouplingGainsNoEnergyAndDampedCouplingSettles) {
  // The probe starts 2.5 mm deep in the beam at rest; all the energy is the contact's.
  const CoupledRun undamped = RunCoupled(0, 0, 10.0);
  EXPECT_TRUE(undamped.finite);
  EXPECT_GT(undamped.initial, 0);
  EXPECT_LE(undamped.max_total, 1.02 * undamped.initial) << "initial " << undamped.initial;
  std::printf("undamped 10 s: initial %.6g J, largest total %.6g J\n", undamped.initial, undamped.max_total);
  // The paper's explicit order (contact force alone, computed at the step's start) on the
  // same undamped beam pumps energy in: why the implicit coupling is the default.
  const CoupledRun explicit_run = RunCoupled(0, 0, 2.0, false);
  EXPECT_GT(explicit_run.max_total, 2 * explicit_run.initial);
  std::printf("undamped, explicit contact: initial %.6g J, largest total %.6g J within 2 s\n", explicit_run.initial,
              explicit_run.max_total);
  const CoupledRun damped = RunCoupled(8, 5e-4, 3.0);
  EXPECT_TRUE(damped.finite);
  EXPECT_LT(damped.final_kinetic, 1e-6 * damped.peak_kinetic);
}

// The cantilever's quasi-static tip deflection under the probe's contact load, against
// Euler–Bernoulli: delta = F a^2 (3 l - a) / (6 E I) for a load at distance a from the clamp,
// tip at l. The simulation mesh is made of whole voxels that enclose the beam, so its
// section is larger than the nominal 2 x 2 cm; the reference uses the mesh's own section.
// Linear tets lock in bending: the deflection approaches the reference from below as cells
// grow.
TEST(DeformableContact, CantileverDeflectionApproachesEulerBernoulliAsCellsGrow) {
  TempDir dir;
  std::vector<double> ratios;
  std::printf("cells  section [mm]  clamp x [mm]  F [N]   tip [mm]  EB mesh [mm]  ratio  EB nominal [mm]\n");
  for (int cells : {20, 40, 60}) {
    const std::string scene_text = BeamScene(cells, "stvk", 8, 5e-4);
    std::ofstream(dir / "beam.yaml") << scene_text;
    std::ofstream(dir / "run.yaml") << "name: cantilever\nscene: beam.yaml\nmodels: [pointshell]\n"
                                       "moving_body: probe\n"
                                       "trajectory: {type: slide, direction: [0, 0, -1], depth: 0.004, length: 0, "
                                       "duration: 3.0}\n";
    const JobResult result = RunAllJobs(dir).at(0);
    // Middle of the hold (the press ends at 0.6 s, the release starts at 2.4 s).
    const CycleRow& row = result.cycles.at(2300);
    ASSERT_TRUE(row.deformable);
    const double F = row.force.z();  // on the probe, up; the beam gets -F
    ASSERT_GT(F, 0.5);
    const std::vector<double> qv(row.q.begin(), row.q.end());
    const Scene scene = LoadScene(dir / "beam.yaml");
    SceneAssets assets(scene, Assets(dir));
    const auto rm = assets.A.reduced_model();
    ASSERT_EQ(int(qv.size()), rm->r());
    const EmbeddedPoints tip(rm->mesh, rm->basis, {Eigen::Vector3d(0.1, 0, 0)});
    const double deflection = -tip.Displacement(0, qv.data()).z();
    // Clamp: the largest x of the fixed vertices; section: the mesh's extent in y and z.
    double clamp = -1;
    for (std::size_t v = 0; v < rm->fixed.size(); ++v)
      if (rm->fixed[v]) clamp = std::max(clamp, rm->mesh.vertices[v].x());
    const Aabb box = rm->mesh.Bounds();
    const double b = box.size().y(), h = box.size().z();
    const double E = 5e7, a = 0.07 - clamp, l = 0.1 - clamp;
    const auto eb = [&](double I) { return F * a * a * (3 * l - a) / (6 * E * I); };
    const double reference = eb(b * h * h * h / 12);
    const double nominal = eb(0.02 * 0.02 * 0.02 * 0.02 / 12);
    ratios.push_back(deflection / reference);
    std::printf("%5d  %5.1f x %5.1f  %12.1f  %6.3f  %8.3f  %12.3f  %5.3f  %15.3f\n", cells, 1e3 * b, 1e3 * h,
                1e3 * clamp, F, 1e3 * deflection, 1e3 * reference, ratios.back(), 1e3 * nominal);
  }
  // Stiffer than the beam theory (locking) but converging toward it.
  EXPECT_GT(ratios[1], ratios[0] + 0.05);
  EXPECT_GT(ratios[2], ratios[1]);
  for (double r : ratios) {
    EXPECT_GT(r, 0.5);
    EXPECT_LT(r, 1.25);  // the mesh-section reference itself is approximate (bounding-box section)
  }
}

// Temporal coherence under deformation: the coupled cantilever run with coherence on skips
// nodes, yet renders the same contacts every cycle as the run without it (the sleeping clock
// counts the distance the deformation may have closed), so the two runs are the same run.
TEST(DeformableContact, TemporalCoherenceSkipsNodesButNeverAContact) {
  TempDir dir;
  // The probe moves at most 3 cm/s, so the rigid bound is tight and the deformation's own
  // speed (the free end swings faster) must be accounted for.
  std::ofstream(dir / "beam.yaml") << BeamScene(20, "stvk", 2, 2e-4, 0.0205, 10, 0.03);
  std::ofstream(dir / "run.yaml") << "name: coherence\nscene: beam.yaml\nmodels: [pointshell]\n"
                                     "moving_body: probe\n"
                                     "trajectory: {type: slide, direction: [0, 0, -1], depth: 0.004, length: 0.01, "
                                     "tangent: [1, 0, 0], duration: 2.0}\n"
                                     "sweep: {coherence: [false, true]}\n";
  const std::vector<JobResult> runs = RunAllJobs(dir);
  ASSERT_EQ(runs.size(), 2u);
  const JobResult& off = runs[0];
  const JobResult& on = runs[1];
  ASSERT_EQ(off.cycles.size(), on.cycles.size());
  double nodes_off = 0, nodes_on = 0, max_q = 0;
  int touching = 0;
  for (std::size_t k = 0; k < off.cycles.size(); ++k) {
    const CycleRow& a = off.cycles[k];
    const CycleRow& b = on.cycles[k];
    ASSERT_EQ(a.contacts, b.contacts) << "cycle " << k;
    ASSERT_LT((a.force - b.force).norm(), 1e-9 * (1 + a.force.norm())) << "cycle " << k;
    ASSERT_TRUE(std::ranges::equal(a.q, b.q)) << "cycle " << k;
    nodes_off += double(a.nodes);
    nodes_on += double(b.nodes);
    touching += a.contacts > 0;
    max_q = std::max(max_q, a.max_displacement);
  }
  EXPECT_GT(touching, 500);
  EXPECT_GT(max_q, 1e-3);  // the beam did deform
  EXPECT_LT(nodes_on, 0.9 * nodes_off);
  std::printf("mean nodes visited: %.1f without coherence, %.1f with\n", nodes_off / double(off.cycles.size()),
              nodes_on / double(on.cycles.size()));
}

// A free deformable body (no anchor: its reduced basis has no rigid modes, so it deforms
// relative to its own frame, decoupled from the rigid motion the trajectory gives it): a soft
// ball pressed onto a plate flattens while pressed and springs back when lifted.
TEST(DeformableContact, AFreeDeformableBallFlattensOnAPlateAndSpringsBack) {
  TempDir dir;
  std::ofstream(dir / "ball.yaml") << R"(name: ball-plate
bodies:
  - name: ball
    mesh: "sphere:0.02,3"
    pose: [0, 0, 0.0205, 1, 0, 0, 0]
    role: pointshell
    pointshell: {points: 1024, levels: 3, seed: 2}
    field: {resolution: 48}
    deformable: {model: stvk, modes: 12, cells: 12, E: 2.0e5, nu: 0.4, rho: 1000,
                 damping: {alpha: 10.0, beta: 0.001}, anchor: none}
  - name: plate
    mesh: "box:0.05,0.05,0.01,2"
    pose: [0, 0, -0.01, 1, 0, 0, 0]
    role: field
    field: {resolution: 48}
model: {k_C: 1000, L: 10}
)";
  std::ofstream(dir / "run.yaml") << "name: free\nscene: ball.yaml\nmodels: [pointshell]\nmoving_body: ball\n"
                                     "trajectory: {type: approach-press, direction: [0, 0, -1], approach: 0.0, "
                                     "depth: 0.003, duration: 3.0}\n";
  const JobResult r = RunAllJobs(dir).at(0);
  double peak = 0;
  for (const CycleRow& row : r.cycles) {
    ASSERT_TRUE(std::isfinite(row.elastic_energy) && std::isfinite(row.max_displacement));
    peak = std::max(peak, row.max_displacement);
  }
  const CycleRow& deepest = r.cycles.at(1500);
  EXPECT_GT(deepest.max_displacement, 2e-4);  // flattened while pressed
  EXPECT_GT(deepest.force.z(), 0);            // the plate pushes the ball up
  EXPECT_LT(r.cycles.back().max_displacement, 0.1 * peak);  // back to round once lifted
  std::printf("free ball: deflection %.3f mm at the deepest press, %.4f mm at the end\n",
              1e3 * deepest.max_displacement, 1e3 * r.cycles.back().max_displacement);
}

TEST(DeformableContact, ModelsThatTreatTheBodyAsRigidRefuseADeformableBody) {
  TempDir dir;
  Scene scene = ParseBeam(BeamScene(20, "stvk", 0, 0));
  SceneAssets assets(scene, Assets(dir));
  // A model that declares no deformable_A, as every baseline does.
  ContactModelEntry rigid_only;
  rigid_only.name = "test-rigid-only";
  rigid_only.needs.pointshell_A = true;
  rigid_only.needs.field_B = true;
  rigid_only.make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
    return std::make_unique<PointshellContactModel>(PointshellContactModel::Variant::kLinear, in.A.pointshell(),
                                                    in.B.field(),
                                                    PointshellParamsOf(in.params, in.Params(PointshellOwnParamTable())));
  };
  RegisterContactModel(rigid_only);
  try {
    MakeSceneContactModel("test-rigid-only", scene, assets);
    ADD_FAILURE() << "a rigid-only model accepted a deformable body";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'beam' is deformable"), std::string::npos) << e.what();
  }
  // With the roles swapped the beam is a deformable field body: the paper's models render it
  // through its deformed field, a rigid-only model refuses it.
  const Scene swapped = scene.Swapped();
  SceneAssets swapped_assets(swapped, Assets(dir));
  EXPECT_NE(dynamic_cast<RigidShellDeformedFieldModel*>(MakeSceneContactModel("pointshell", swapped, swapped_assets).get()),
            nullptr);
  ContactModelEntry rigid_B = rigid_only;
  rigid_B.name = "test-rigid-B";
  rigid_B.needs.deformable_A = true;
  RegisterContactModel(rigid_B);
  try {
    MakeSceneContactModel("test-rigid-B", swapped, swapped_assets);
    ADD_FAILURE() << "a rigid-only model accepted a deformable field body";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("treats body B as rigid"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contactlab
