// Scenes of many bodies: what a scene file may say (tool, pairs, roles, the bound on bodies)
// and the errors it gets, and the world's cycle checked against independent references: every
// pair's two-body query made apart, brute force over every pair without the broad phase, finite
// differences of the tool's wrench, and an allocation count over 256 bodies.
#include "scene/scene_world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>
#include <string>

#include "allocation_counter.h"
#include "scene/pair_contact_marks.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "scene/scene_query.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;

// A ball of radius 2 cm (the tool, pointshell) and plates of 4 x 4 x 1 cm half-extents (fields)
// around it: one below, one to its +x side, and EXTRA more far off along +y.
std::string ToolAmongPlates(int extra = 0, const std::string& model = "{k_C: 1000, L: 0}",
                            const std::string& tail = "") {
  std::ostringstream os;
  os << "name: tool-among-plates\n"
     << "tool: ball\n"
     << "bodies:\n"
     << "  - name: ball\n"
     << "    mesh: \"sphere:0.02,3\"\n"
     << "    pose: [0, 0, 0.0195, 1, 0, 0, 0]\n"
     << "    role: pointshell\n"
     << "    pointshell: {points: 512, levels: 3, seed: 2}\n"
     << "    field: {resolution: 24}\n"
     << "  - name: floor\n"
     << "    mesh: \"box:0.04,0.04,0.01,2\"\n"
     << "    pose: [0, 0, -0.01, 1, 0, 0, 0]\n"
     << "    role: field\n"
     << "    field: {resolution: 24}\n"
     << "  - name: wall\n"
     << "    mesh: \"box:0.01,0.04,0.04,2\"\n"
     << "    pose: [0.0295, 0, 0.03, 1, 0, 0, 0]\n"
     << "    role: field\n"
     << "    field: {resolution: 24}\n";
  for (int i = 0; i < extra; ++i) {
    os << "  - name: far" << i << "\n"
       << "    mesh: \"box:0.01,0.01,0.01,1\"\n"
       << "    pose: [" << 0.05 * (i % 16) << ", " << 0.2 + 0.05 * (i / 16) << ", 0, 1, 0, 0, 0]\n"
       << "    role: field\n"
       << "    field: {resolution: 16}\n";
  }
  os << "model: " << model << "\n" << tail;
  return os.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

Scene Parse(const std::string& text) { return ParseScene(ConfigNode::LoadString(text, "many.yaml")); }

std::string ParseError(const std::string& text) {
  return testing::ErrorOf([&] { Parse(text); });
}

AssetOptions Quiet(const TempDir& cache) {
  AssetOptions o;
  o.cache_dir = cache.path();
  o.verbose = false;
  return o;
}

TEST(ManyBodies, TheToolPairsWithEveryOtherBodyAndPairsAddAndOverride) {
  const Scene s = Parse(ToolAmongPlates(2, "{k_C: 1000, L: 0}",
                                        "pairs:\n"
                                        "  - {bodies: [floor, wall], model: fcl}\n"
                                        "  - {bodies: [wall, ball], model: fcl, params: {k_C: 300}}\n"
                                        "  - {bodies: [ball, far1], model: none}\n"));
  ASSERT_TRUE(s.many_bodies());
  EXPECT_EQ(s.bodies.size(), 5u);
  EXPECT_EQ(s.bodies[std::size_t(s.tool)].name, "ball");
  // ball-floor, ball-wall (overridden), ball-far0, floor-wall; ball-far1 removed.
  ASSERT_EQ(s.pairs.size(), 4u);
  auto names = [&](const PairSpec& p) {
    return s.bodies[std::size_t(p.bodies[0])].name + "/" + s.bodies[std::size_t(p.bodies[1])].name;
  };
  EXPECT_EQ(names(s.pairs[0]), "ball/floor");
  EXPECT_EQ(s.pairs[0].model, "");
  EXPECT_EQ(names(s.pairs[1]), "wall/ball");
  EXPECT_EQ(s.pairs[1].model, "fcl");
  ASSERT_TRUE(s.pairs[1].has_params);
  EXPECT_DOUBLE_EQ(s.pairs[1].params.penalty.k_C, 300);
  EXPECT_EQ(names(s.pairs[2]), "ball/far0");
  EXPECT_EQ(names(s.pairs[3]), "floor/wall");
  // far1 is in no pair: a warning naming its place, not an error.
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("many.yaml:"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("far1"), std::string::npos) << s.warnings[0];
  // Each pair in its model's A/B order: the paper's model takes the ball's pointshell.
  const OrderedPair ball_floor = OrderPair(s, s.pairs[0], "pointshell");
  EXPECT_EQ(s.bodies[std::size_t(ball_floor.A)].name, "ball");
  EXPECT_EQ(s.bodies[std::size_t(ball_floor.B)].name, "floor");
  // A two-body scene keeps its meaning: no tool, no pairs.
  const Scene two = Parse(R"(bodies:
  - {name: a, mesh: "sphere:0.02", role: field}
  - {name: b, mesh: "sphere:0.02", role: pointshell}
)");
  EXPECT_FALSE(two.many_bodies());
  EXPECT_EQ(two.pointshell_body.name, "b");
  EXPECT_TRUE(two.pairs.empty());
}

TEST(ManyBodies, BadScenesAreRefusedWithTheFileLineAndKey) {
  struct Case {
    std::string text;
    std::string says;
  };
  std::string no_tool = ToolAmongPlates(1);
  no_tool.erase(no_tool.find("tool: ball\n"), 11);
  std::ostringstream too_many;
  too_many << "tool: b0\nbodies:\n";
  for (int i = 0; i <= kMaxSceneBodies; ++i) too_many << "  - {name: b" << i << ", mesh: \"sphere:0.01\"}\n";
  const std::string both_in_two = "bodies:\n  - {mesh: \"sphere:0.02\", role: both}\n  - {mesh: \"sphere:0.03\", "
                                  "role: field}\n";
  const std::vector<Case> cases = {
      {no_tool, "tool: NAME"},
      {Replace(ToolAmongPlates(), "tool: ball", "tool: hammer"), "many.yaml:2"},
      {Replace(ToolAmongPlates(), "tool: ball", "tool: hammer"), "'hammer' is none of the scene's bodies"},
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, roof]}\n"), "'roof' is none"},
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, wall]}\n  - {bodies: [wall, floor]}\n"),
       "named twice"},
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, floor]}\n"), "with itself"},
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor]}\n"), "names two bodies"},
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, wall], model: magic}\n"),
       "unknown contact model 'magic'"},
      // Both plates may only be fields: the paper's model between them has no pointshell body.
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, wall], model: pointshell}\n"),
       "can take the role"},
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, wall], params: {node_budget: 5}}\n"),
       "shared by every pair"},
      {ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, wall], colour: red}\n"), "colour"},
      {Replace(ToolAmongPlates(), "  - name: wall", "  - name: floor"), "a second body named 'floor'"},
      {too_many.str(), "at most 1024 bodies, got 1025"},
      {both_in_two, "'both' is for a scene of many bodies"},
  };
  for (const Case& c : cases) {
    const std::string e = ParseError(c.text);
    EXPECT_NE(e.find(c.says), std::string::npos) << "expected '" << c.says << "' in: " << e;
    EXPECT_NE(e.find("many.yaml"), std::string::npos) << e;
  }
  // The pair's own line is named.
  const std::string e = ParseError(ToolAmongPlates(0, "{k_C: 1000}", "pairs:\n  - {bodies: [floor, floor]}\n"));
  EXPECT_NE(e.find("many.yaml:22"), std::string::npos) << e;
}

// The pairs' two-body scenes: the tool as pointshell body at X_W_TOOL, the other body as field.
Vector6d WrenchOnToolFromTwoBodyScenes(const Scene& many, const Pose& X_W_tool, const TempDir& cache, int* touching) {
  Vector6d total = Vector6d::Zero();
  *touching = 0;
  for (const PairSpec& p : many.pairs) {
    Scene two;
    two.file = many.file;
    two.pointshell_body = many.bodies[std::size_t(many.tool)];
    two.pointshell_body.role = "pointshell";
    two.field_body = many.bodies[std::size_t(p.bodies[0] == many.tool ? p.bodies[1] : p.bodies[0])];
    two.field_body.role = "field";
    two.model = many.model;
    two.model_params = many.model_params;
    SceneAssets assets(two, Quiet(cache));
    auto model = MakeSceneContactModel("pointshell", two, assets);
    const ContactResult r = model->Evaluate(SceneContactQuery(two, X_W_tool, two.field_body.pose));
    if (r.stats.points_in_contact > 0) ++*touching;
    // Newton's third law and the torque moved from B's origin to the tool's.
    const Eigen::Vector3d r_AB = two.field_body.pose.translation - X_W_tool.translation;
    total.head<3>() -= r.on_B.force;
    total.tail<3>() -= r.on_B.torque + r_AB.cross(r.on_B.force);
  }
  return total;
}

TEST(SceneWorld, TheToolsWrenchIsTheSumOfItsPairsAsTwoBodyScenes) {
  TempDir cache;
  const Scene s = Parse(ToolAmongPlates(3));
  SceneWorld world(s, "pointshell", Quiet(cache));
  ASSERT_EQ(world.pair_count(), 5);
  // Pressed into the floor and against the wall, turned a little.
  const Pose X{RotationFromVector(Eigen::Vector3d(0.1, -0.2, 0.3)), Eigen::Vector3d(0.003, 0.001, 0.018)};
  const WorldResult& r = world.Evaluate(X, 0);
  int touching = 0;
  const Vector6d reference = WrenchOnToolFromTwoBodyScenes(s, X, cache, &touching);
  ASSERT_EQ(touching, 2);
  EXPECT_EQ(r.stats.pairs_touching, 2);
  EXPECT_EQ(r.stats.pairs_near, 2) << "the far plates are culled";
  ASSERT_GT(reference.head<3>().norm(), 1.0);
  EXPECT_LT((r.on_tool.AsVector() - reference).norm(), 1e-9 * reference.norm())
      << r.on_tool.AsVector().transpose() << "\n" << reference.transpose();
}

TEST(SceneWorld, BroadPhaseNeverCullsAPairInContactAndCullsTheFarOnes) {
  TempDir cache;
  const Scene s = Parse(ToolAmongPlates(32));
  SceneWorld world(s, "pointshell", Quiet(cache));
  // Brute force: every pair's model of its own, asked at every pose.
  std::vector<std::unique_ptr<ContactModel>> alone;
  for (int p = 0; p < world.pair_count(); ++p) {
    const OrderedPair& pair = world.pair(p);
    alone.push_back(MakeContactModel(
        "pointshell", ContactModelInputs{world.body(pair.A), world.body(pair.B), s.model, s.model_params}, "alone"));
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int touched = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // Poses over the floor, the wall and the first row of the far plates.
    const Pose X{RotationFromVector(Eigen::Vector3d(u(rng), u(rng), u(rng))),
                 Eigen::Vector3d(0.4 * (u(rng) + 1), 0.15 + 0.1 * u(rng), 0.03 * u(rng))};
    const Pose X_near{X.rotation, Eigen::Vector3d(0.03 * u(rng), 0.03 * u(rng), 0.02 + 0.01 * u(rng))};
    for (const Pose& pose : {X, X_near}) {
      world.Evaluate(pose, trial);
      for (int p = 0; p < world.pair_count(); ++p) {
        ContactQuery q;
        q.X_WA = pose;
        q.X_WB = s.bodies[std::size_t(world.pair(p).B)].pose;
        alone[std::size_t(p)]->Reset();
        const ContactResult r = alone[std::size_t(p)]->Evaluate(q);
        if (r.stats.points_in_contact > 0) {
          ++touched;
          EXPECT_TRUE(world.outcome(p).near) << "pair " << p << " touches at trial " << trial << " but was culled";
        }
      }
      // The tool is 4 cm across, the far plates 5 cm apart: a handful are near at most.
      EXPECT_LE(int(world.near_pairs().size()), 8) << "trial " << trial << " of " << world.pair_count() << " pairs";
    }
  }
  EXPECT_GT(touched, 50);
}

// Central differences of the world's wrench on the tool with respect to the tool's pose.
Matrix6d FiniteDifferenceOfTheTool(SceneWorld& world, const Pose& X, double eps) {
  Matrix6d K;
  for (int c = 0; c < 6; ++c) {
    Pose plus = X, minus = X;
    if (c < 3) {
      plus.translation[c] += eps;
      minus.translation[c] -= eps;
    } else {
      Eigen::Vector3d w = Eigen::Vector3d::Zero();
      w[c - 3] = eps;
      plus.rotation = (RotationFromVector(w) * X.rotation).normalized();
      minus.rotation = (RotationFromVector(-w) * X.rotation).normalized();
    }
    const Vector6d up = world.Evaluate(plus, 0).on_tool.AsVector();
    world.Reset();
    const Vector6d down = world.Evaluate(minus, 0).on_tool.AsVector();
    world.Reset();
    K.col(c) = (up - down) / (2 * eps);
  }
  return K;
}

TEST(SceneWorld, TheToolsGradientMatchesFiniteDifferencesWhicheverSideItIsOn) {
  TempDir cache;
  // The ball as pointshell against the floor (the tool is A), and as field against a box probe
  // that is only a pointshell (the tool is B).
  const std::string text = ToolAmongPlates(0, "{k_C: 1000, L: 0, gradient: field}");
  std::string with_probe = Replace(text, "    role: pointshell\n", "    role: both\n");
  with_probe = Replace(with_probe, "  - name: wall\n    mesh: \"box:0.01,0.04,0.04,2\"\n    pose: [0.0295, 0, 0.03, 1, 0, 0, 0]\n    role: field\n",
                       "  - name: wall\n    mesh: \"box:0.01,0.04,0.04,2\"\n    pose: [0.0295, 0, 0.03, 1, 0, 0, 0]\n    role: pointshell\n    pointshell: {points: 1024, levels: 1, seed: 3}\n");
  const Scene s = Parse(with_probe);
  SceneWorld world(s, "pointshell-linear", Quiet(cache));
  ASSERT_EQ(world.pair_count(), 2);
  EXPECT_EQ(world.pair(0).A, s.tool);
  EXPECT_EQ(world.pair(1).B, s.tool);
  const Pose X{RotationFromVector(Eigen::Vector3d(0.2, -0.1, 0.4)), Eigen::Vector3d(0.003, 0.002, 0.0185)};
  const WorldResult r = world.Evaluate(X, 0);
  world.Reset();
  ASSERT_EQ(r.stats.pairs_touching, 2);
  const Matrix6d fd = FiniteDifferenceOfTheTool(world, X, 2e-5);
  EXPECT_LT((r.K_tool - fd).norm(), 3e-2 * fd.norm()) << "analytic\n" << r.K_tool << "\nfd\n" << fd;
}

TEST(SceneWorld, OneBudgetIsSharedSoNoContactSiteStarves) {
  TempDir cache;
  const Scene s = Parse(ToolAmongPlates(0, "{k_C: 1000, L: 0, node_budget: 60}"));
  SceneWorld world(s, "pointshell", Quiet(cache));
  const Pose X = Pose::FromTranslation(Eigen::Vector3d(0.0055, 0, 0.016));
  const WorldResult r = world.Evaluate(X, 0);
  ASSERT_EQ(r.stats.pairs_near, 2);
  EXPECT_EQ(r.stats.pairs_touching, 2) << "the second site keeps its share";
  EXPECT_GE(world.outcome(0).budget, 30);
  EXPECT_GE(world.outcome(1).budget, 30);
  EXPECT_GT(r.stats.pairs_degraded, 0);
  // Without a budget nothing degrades and more nodes are visited.
  world.Reset();
  const WorldResult all = world.Evaluate(X, 0, 0);
  EXPECT_EQ(all.stats.pairs_touching, 2);
  EXPECT_EQ(all.stats.pairs_degraded, 0);
  EXPECT_GT(all.stats.sum.nodes_visited, r.stats.sum.nodes_visited);
}

TEST(SceneWorld, APairThatLeavesStartsAfreshAndNearPairsKeepTheirState) {
  TempDir cache;
  const Scene s = Parse(ToolAmongPlates(0, "{k_C: 1000, L: 0, coherence: true}"));
  SceneWorld world(s, "pointshell", Quiet(cache));
  const Pose on_floor = Pose::FromTranslation(Eigen::Vector3d(-0.03, 0, 0.0195));
  world.Evaluate(on_floor, 0);
  EXPECT_TRUE(world.outcome(0).near);
  EXPECT_FALSE(world.outcome(1).near) << "the wall is 3 cm off";
  // Staying near, coherence skips nodes it trusts asleep.
  const WorldResult& again = world.Evaluate(on_floor, 1);
  EXPECT_GT(world.outcome(0).result.stats.nodes_skipped_coherence, 0);
  EXPECT_GT(again.on_tool.force.z(), 0);
  // Lifted clear: no pair near, no force, and the floor's pair forgot its state.
  world.Evaluate(Pose::FromTranslation(Eigen::Vector3d(-0.03, 0, 0.2)), 2);
  EXPECT_EQ(world.near_pairs().size(), 0u);
  EXPECT_FALSE(world.outcome(0).near);
  world.Evaluate(on_floor, 3);
  EXPECT_EQ(world.outcome(0).result.stats.nodes_skipped_coherence, 0) << "a pair coming near starts afresh";
}

// The floor made deformable and pressed by two pairs at once: the ball from above (the floor's
// deformed field) and the wall standing on it (the floor's deformable pointshell). PAIRS: the
// scene's pairs block.
std::string DeformableFloorPressedTwice(const std::string& pairs) {
  std::string text = ToolAmongPlates(0, "{k_C: 1000, L: 0, max_point_speed: 0.5}", pairs);
  text = Replace(text, "pose: [0.0295, 0, 0.03,", "pose: [0.0295, 0, 0.0395,");
  text = Replace(text,
                 "    role: field\n    field: {resolution: 24}\n  - name: wall",
                 "    role: both\n    field: {resolution: 24}\n    pointshell: {points: 1024, levels: 3, seed: 4}\n"
                 "    deformable: {model: linear, modes: 6, cells: 10, E: 2.0e5, nu: 0.3, rho: 1100,\n"
                 "                 anchor: {outside: [-0.035, -0.035, -1, 0.035, 0.035, 1]}, field: {proxies: 20}}\n"
                 "  - name: wall");
  return text;
}

TEST(SceneWorld, ADeformableBodyStepsOnceWithTheForcesOfAllItsPairs) {
  TempDir cache;
  const Pose X{Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0.0195)};
  const double dt = 1e-3;
  // The floor's reduced force in the first cycle from rest, with the given pairs, TOUCHING of them
  // in contact.
  auto first_cycle = [&](const std::string& pairs, int touching) {
    auto world = std::make_unique<SceneWorld>(Parse(DeformableFloorPressedTwice(pairs)), "pointshell", Quiet(cache));
    world->EnableDynamics(dt);
    const WorldResult& r = world->Evaluate(X, 0);
    EXPECT_EQ(r.stats.sum.faults, 0);
    EXPECT_EQ(r.stats.pairs_touching, touching) << pairs;
    return world;
  };
  const auto w_both = first_cycle("pairs:\n  - {bodies: [floor, wall]}\n", 3);
  const auto w_ball = first_cycle("", 2);
  const auto w_wall = first_cycle("pairs:\n  - {bodies: [floor, wall]}\n  - {bodies: [ball, floor], model: none}\n", 2);
  const BodyDeformation* both = w_both->contact_deformation(1);
  const BodyDeformation* ball_only = w_ball->contact_deformation(1);
  const BodyDeformation* wall_only = w_wall->contact_deformation(1);
  ASSERT_NE(both, nullptr);
  ASSERT_NE(ball_only, nullptr);
  ASSERT_NE(wall_only, nullptr);
  EXPECT_EQ(w_both->dynamics(0), nullptr) << "the rigid ball has no dynamics";
  EXPECT_EQ(w_both->dynamics(2), nullptr) << "nor the rigid wall";
  // Superposition: at rest each pair's force is its own, and the floor takes their sum.
  ASSERT_GT(ball_only->force->norm(), 0.0);
  ASSERT_GT(wall_only->force->norm(), 0.0);
  EXPECT_LT((*both->force - (*ball_only->force + *wall_only->force)).norm(), 1e-9 * both->force->norm());
  if (both->stiffness != nullptr) {
    EXPECT_LT((*both->stiffness - (*ball_only->stiffness + *wall_only->stiffness)).norm(),
              1e-9 * both->stiffness->norm() + 1e-12);
  }
  // One step with that force, not one per pair: the floor's state is a body of its own stepped
  // once from rest with it.
  std::unique_ptr<BodyDynamics> alone = MakeBodyDynamics(w_both->body(1), dt, false);
  const BodyDeformation* d = alone->Prepare();
  *d->force = *both->force;
  if (d->stiffness != nullptr) *d->stiffness = *both->stiffness;
  alone->Step();
  const ReducedState& q = w_both->dynamics(1)->state();
  ASSERT_GT(alone->state().qdot.norm(), 0.0);
  EXPECT_LT((q.q - alone->state().q).norm(), 1e-12 + 1e-9 * alone->state().q.norm());
  EXPECT_LT((q.qdot - alone->state().qdot).norm(), 1e-9 * alone->state().qdot.norm());
  // And the cycles after it, the floor stepping under both, allocate nothing.
  const long before = testing::AllocationCount();
  for (int i = 1; i < 50; ++i) w_both->Evaluate(X, i);
  EXPECT_EQ(testing::AllocationCount() - before, 0);
  EXPECT_GT(w_both->dynamics(1)->MaxDisplacement(), 0.0);
}

TEST(SceneWorld, CountsTheBodiesDisplacedPastTheirDeformationBound) {
  TempDir cache;
  const Pose X{Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0.0195)};
  // The floor pressed by the ball and the wall, with BOUND (m) as its deformation bound: each
  // cycle counts it exactly when its largest vertex displacement is past the bound.
  auto beyond = [&](double bound) {
    char row[64];
    std::snprintf(row, sizeof row, "    role: both\n    deformation_bound: %.3g\n", bound);
    const std::string text = Replace(DeformableFloorPressedTwice("pairs:\n  - {bodies: [floor, wall]}\n"), "    role: both\n", row);
    SceneWorld world(Parse(text), "pointshell", Quiet(cache));
    world.EnableDynamics(1e-3);
    int counted = 0, past = 0;
    for (int i = 0; i < 40; ++i) {
      const WorldStats& st = world.Evaluate(X, i).stats;
      const int n = st.bodies_beyond_bound;
      EXPECT_GT(st.sum.step_ns, 0) << "the floor's step is timed inside the cycle";
      const BodyDynamics& d = *world.dynamics(1);
      // The reference: every vertex's displacement U_v q, from the basis.
      const Eigen::VectorXd u = world.body(1).reduced_model()->basis * d.state().q;
      double largest = 0;
      for (Eigen::Index v = 0; v + 2 < u.size(); v += 3) largest = std::max(largest, u.segment<3>(v).norm());
      EXPECT_LE(n, 1);
      EXPECT_EQ(n == 1, largest > bound) << "cycle " << i << ": " << largest << " m against " << bound << " m";
      counted += n;
      past += largest > bound;
    }
    return std::pair{counted, past};
  };
  const auto [tight_counted, tight_past] = beyond(1e-9);
  EXPECT_GT(tight_past, 30) << "pressed, the floor moves more than a nanometre";
  EXPECT_EQ(tight_counted, tight_past);
  const auto [loose_counted, loose_past] = beyond(0.01);
  EXPECT_EQ(loose_past, 0);
  EXPECT_EQ(loose_counted, 0);
}

TEST(SceneWorld, PairContactMarksCarryEveryTouchingPairsContactsWithoutAllocating) {
  TempDir cache;
  SceneWorld world(Parse(ToolAmongPlates(6)), "pointshell", Quiet(cache));
  PairContactMarks marks(4096, 3);
  world.SetPairContactMarks(&marks);
  const Pose X{Eigen::Quaterniond::Identity(), Eigen::Vector3d(0, 0, 0.0195)};  // 0.5 mm into floor and wall
  world.Evaluate(X, 0);
  PairContactFrame frame;
  ASSERT_TRUE(marks.TakeLatest(&frame));
  EXPECT_EQ(frame.cycle, 0);
  EXPECT_EQ(frame.pairs_touching, 2);
  EXPECT_EQ(frame.not_kept, 0);
  // One entry per point in contact, per pair (the paper's model: a contact is a point with d < 0).
  int floor_contacts = 0, wall_contacts = 0;
  for (int i = 0; i < frame.size(); ++i) {
    const OrderedPair& pair = world.pair(frame.pair[std::size_t(i)]);
    const std::string& other = world.scene().bodies[std::size_t(pair.A == world.tool() ? pair.B : pair.A)].name;
    const Eigen::Vector3d p(frame.points[3 * std::size_t(i)], frame.points[3 * std::size_t(i) + 1],
                            frame.points[3 * std::size_t(i) + 2]);
    // Each contact lies inside the body it touches, below the floor's top (z = 0) or past the
    // wall's face (x = 0.0195), no deeper than its pair's deepest penetration.
    const double deepest = world.outcome(frame.pair[std::size_t(i)]).result.stats.max_penetration;
    if (other == "floor") {
      ++floor_contacts;
      EXPECT_LE(p.z(), 1e-4) << i;
      EXPECT_GE(p.z(), -deepest - 1e-4) << i;
    } else {
      ASSERT_EQ(other, "wall");
      ++wall_contacts;
      EXPECT_GE(p.x(), 0.0195 - 1e-4) << i;
      EXPECT_LE(p.x(), 0.0195 + deepest + 1e-4) << i;
    }
  }
  for (const int p : world.near_pairs()) {
    const std::string& other = world.scene().bodies[std::size_t(world.pair(p).B)].name;
    const int in_contact = world.outcome(p).result.stats.points_in_contact;
    if (other == "floor") EXPECT_EQ(floor_contacts, in_contact);
    if (other == "wall") EXPECT_EQ(wall_contacts, in_contact);
  }
  EXPECT_GT(floor_contacts, 0);
  EXPECT_GT(wall_contacts, 0);
  // Frames every third cycle only, and the cycles that take them allocate nothing.
  const long before = testing::AllocationCount();
  for (int i = 1; i <= 7; ++i) world.Evaluate(X, i);
  EXPECT_EQ(testing::AllocationCount() - before, 0);
  ASSERT_TRUE(marks.TakeLatest(&frame));
  EXPECT_EQ(frame.cycle, 6);
  EXPECT_FALSE(marks.TakeLatest(&frame)) << "nothing newer";
}

TEST(SceneWorld, ACycleAmong256BodiesAllocatesNothing) {
  TempDir cache;
  const Scene s = Parse(ToolAmongPlates(254));
  ASSERT_EQ(s.bodies.size(), 257u);
  SceneWorld world(s, "pointshell", Quiet(cache));
  auto pose = [](int i) {
    const double t = 0.01 * i;
    return Pose{RotationFromVector(Eigen::Vector3d(0, 0, t)),
                Eigen::Vector3d(0.3 * std::sin(t), 0.2 + 0.15 * std::sin(0.7 * t), 0.019)};
  };
  for (int i = 0; i < 400; ++i) world.Evaluate(pose(i), i);  // the path once, each model's first query made
  int touching = 0, near = 0;
  const long before = testing::AllocationCount();
  for (int i = 0; i < 400; ++i) {
    const WorldStats& st = world.Evaluate(pose(i), 400 + i).stats;
    touching += st.pairs_touching;
    near += st.pairs_near;
  }
  EXPECT_EQ(testing::AllocationCount() - before, 0);
  EXPECT_GT(touching, 0);
  EXPECT_GT(near, touching);
}

}  // namespace
}  // namespace contactlab
