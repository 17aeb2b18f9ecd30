// `contactlab contact SCENE.yaml [--model NAME] [--pose-a ...] [--pose-b ...] [--touch DEPTH] [--q-a Q] [--q-b Q]
// [--contacts] [--json]`: evaluates one contact query of a scene (Barbič & James 2008, sec. 2.1
// and 3) and prints the wrench on the field body, points in contact, nodes visited and level
// rendered; --contacts also the model's contacts (ContactModel::LatestContacts).
// A scene of many bodies (docs/scenes.md, "Many bodies"): the wrench on the tool summed over its
// pairs, what was built for each body and one line per pair near the tool (--json: a "pairs"
// array, each pair's bodies in its model's A/B order with the keys of a two-body query).
// --touch first moves the field body toward the pointshell body until it is DEPTH deep, as
// `session --touch` does (scene/contact_placement.h).
// `contactlab models`: the registered contact models, what each needs and what it is.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_registry.h"
#include "contact/contact_stats_fields.h"
#include "contact/model_registry.h"
#include "scene/contact_placement.h"
#include "scene/reduced_coordinates.h"
#include "scene/scene_assets.h"
#include "scene/scene.h"
#include "scene/scene_query.h"
#include "scene/scene_world.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab::cli {
namespace {

struct ContactArgs {
  std::string scene;
  std::string model;
  std::string pose_a, pose_b;
  std::string pose_tool;  // a scene of many bodies: the tool's pose
  std::string q_a, q_b;
  std::string cache;
  bool no_cache = false;
  bool json = false;
  bool contacts = false;  // --contacts: list the model's contacts
  long long budget = -1;
  double touch = -1;  // --touch: penetration depth to move the field body to, metres (<= 0: not given)
  std::string slide;  // --slide dx,dy,dz: the field body's slide before the query, metres
};

// --contacts as text: one row per contact, world frame.
void PrintContacts(const std::string& model_name, bool has_contacts, const ContactList& contacts) {
  if (!has_contacts) {
    std::printf("contacts: model %s has no contact list (its force is not a sum over discrete contacts)\n",
                model_name.c_str());
    return;
  }
  const bool surface = !contacts.areas.empty();
  const bool friction = !contacts.tangential.empty();
  std::printf("contacts: %d (world frame; normal: direction of the force on the field body)\n", contacts.size());
  if (contacts.not_kept > 0) std::printf("  (%lld more not listed)\n", static_cast<long long>(contacts.not_kept));
  if (contacts.size() == 0) return;
  std::printf("%14s %14s %14s %10s %10s %10s %14s%s%s\n", "x [m]", "y [m]", "z [m]", "nx", "ny", "nz", "depth [m]",
              surface ? "      area [m^2]  pressure [Pa]" : "",
              friction ? "      ft_x [N]       ft_y [N]       ft_z [N] friction" : "");
  for (int i = 0; i < contacts.size(); ++i) {
    const Eigen::Vector3d& p = contacts.points[std::size_t(i)];
    const Eigen::Vector3d& n = contacts.normals[std::size_t(i)];
    std::printf("%+14.7e %+14.7e %+14.7e %+10.6f %+10.6f %+10.6f %14.7e", p.x(), p.y(), p.z(), n.x(), n.y(), n.z(),
                contacts.depths[std::size_t(i)]);
    if (surface) std::printf(" %15.7e %14.7e", contacts.areas[std::size_t(i)], contacts.pressures[std::size_t(i)]);
    if (friction) {
      const Eigen::Vector3d& t = contacts.tangential[std::size_t(i)];
      std::printf(" %+14.7e %+14.7e %+14.7e %8s", t.x(), t.y(), t.z(), contacts.sticking[std::size_t(i)] ? "sticks" : "slides");
    }
    std::printf("\n");
  }
}

// --contacts --json: the contacts as {points, normals, depths[, areas, pressures][, tangential,
// sticking], not_kept}.
nlohmann::json ContactsJson(const ContactList& contacts) {
  auto rows = [](const std::vector<Eigen::Vector3d>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (const Eigen::Vector3d& x : v) a.push_back({x.x(), x.y(), x.z()});
    return a;
  };
  nlohmann::json c;
  c["points"] = rows(contacts.points);
  c["normals"] = rows(contacts.normals);
  c["depths"] = contacts.depths;
  if (!contacts.areas.empty()) {
    c["areas"] = contacts.areas;
    c["pressures"] = contacts.pressures;
  }
  if (!contacts.tangential.empty()) {
    c["tangential"] = rows(contacts.tangential);
    nlohmann::json sticking = nlohmann::json::array();
    for (const std::uint8_t s : contacts.sticking) sticking.push_back(s != 0);
    c["sticking"] = sticking;
  }
  c["not_kept"] = contacts.not_kept;
  return c;
}

nlohmann::json Vec3(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json Matrix6Json(const Matrix6d& K) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 6; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int c = 0; c < 6; ++c) row.push_back(K(i, c));
    rows.push_back(row);
  }
  return rows;
}

// A query's stats under their column names (contact/contact_stats_fields.h).
void AddStats(const ContactStats& stats, nlohmann::json* j) {
  for (const ContactStatField& f : kContactStatFields) {
    if (f.count) {
      (*j)[f.name] = std::int64_t(f.value(stats));
    } else {
      (*j)[f.name] = f.value(stats);
    }
  }
}

std::string Joined(const std::vector<std::string>& parts) {
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? "" : ", ") + p;
  return s.empty() ? "nothing" : s;
}

// A scene of many bodies: one cycle over every pair, the tool at its scene pose or --pose-tool.
void RunWorldContact(const ContactArgs& args, const Scene& scene, const AssetOptions& options) {
  const std::string where = args.scene;
  if (!args.pose_a.empty() || !args.pose_b.empty() || args.touch > 0 || !args.q_a.empty() || !args.q_b.empty() ||
      !args.slide.empty()) {
    Fail(where, "a scene of many bodies takes --pose-tool (the tool's pose; the other bodies stay at theirs), not "
                "--pose-a, --pose-b, --touch, --slide, --q-a or --q-b");
  }
  if (!args.json) {
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  const std::string model_name = args.model.empty() ? scene.models.front() : args.model;
  SceneWorld world(scene, model_name, options);
  const BodySpec& tool = scene.bodies[std::size_t(scene.tool)];
  const Pose X_tool = args.pose_tool.empty() ? tool.pose : ParsePose(args.pose_tool, "--pose-tool");
  constexpr int kMaxContacts = 1 << 20;
  std::vector<std::uint8_t> has_contacts(std::size_t(world.pair_count()), 0);
  if (args.contacts) {
    for (int p = 0; p < world.pair_count(); ++p) has_contacts[std::size_t(p)] = world.model(p).KeepContacts(kMaxContacts);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const WorldResult r = world.Evaluate(X_tool, 0, args.budget);
  const double micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  if (r.stats.sum.faults > 0) Fail(where, "a pair's model refused the query; no wrench");
  if (!r.on_tool.force.allFinite() || !r.on_tool.torque.allFinite() || !r.K_tool.allFinite()) {
    Fail(where, "a pair's model gave a non-finite wrench or stiffness at these poses; nothing printed");
  }
  auto name = [&](int body) { return scene.bodies[std::size_t(body)].name; };
  if (args.json) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["model"] = model_name;
    j["tool"] = tool.name;
    nlohmann::json bodies = nlohmann::json::array();
    for (int b = 0; b < world.body_count(); ++b) bodies.push_back({{"name", name(b)}, {"built", world.body(b).Built()}});
    j["bodies"] = bodies;
    j["force"] = Vec3(r.on_tool.force);
    j["torque"] = Vec3(r.on_tool.torque);
    j["K_tool"] = Matrix6Json(r.K_tool);
    j["pairs_near"] = r.stats.pairs_near;
    j["pairs_touching"] = r.stats.pairs_touching;
    j["pairs_degraded"] = r.stats.pairs_degraded;
    j["points_in_contact"] = r.stats.sum.points_in_contact;
    j["nodes_visited"] = r.stats.sum.nodes_visited;
    j["evaluate_microseconds"] = micros;
    nlohmann::json pairs = nlohmann::json::array();
    for (int p = 0; p < world.pair_count(); ++p) {
      const OrderedPair& pair = world.pair(p);
      const PairOutcome& o = world.outcome(p);
      nlohmann::json e;
      e["bodies"] = {name(pair.A), name(pair.B)};
      e["model"] = pair.model;
      e["near"] = o.near;
      e["node_budget"] = o.budget;
      e["force"] = Vec3(o.result.on_B.force);
      e["torque"] = Vec3(o.result.on_B.torque);
      AddStats(o.result.stats, &e);
      e["K_B"] = Matrix6Json(o.result.K_B);
      if (args.contacts) {
        ContactList contacts;
        if (has_contacts[std::size_t(p)]) world.model(p).LatestContacts(&contacts);
        e["contacts"] = has_contacts[std::size_t(p)] ? ContactsJson(contacts) : nlohmann::json(nullptr);
      }
      pairs.push_back(e);
    }
    j["pairs"] = pairs;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("scene %s: %d bodies, tool %s, %d pairs (model %s unless the pair names its own)\n", scene.name.c_str(),
              world.body_count(), tool.name.c_str(), world.pair_count(), model_name.c_str());
  for (int b = 0; b < world.body_count(); ++b) {
    std::printf("  built for %s: %s\n", name(b).c_str(), Joined(world.body(b).Built()).c_str());
  }
  std::printf("force on %s  [N]:   %+.6g %+.6g %+.6g\n", tool.name.c_str(), r.on_tool.force.x(), r.on_tool.force.y(),
              r.on_tool.force.z());
  std::printf("torque on %s [N m]: %+.6g %+.6g %+.6g (about its origin, world frame)\n", tool.name.c_str(),
              r.on_tool.torque.x(), r.on_tool.torque.y(), r.on_tool.torque.z());
  std::printf("pairs near %d, touching %d, degraded %d; points in contact %d, nodes visited %lld, %.1f us\n",
              r.stats.pairs_near, r.stats.pairs_touching, r.stats.pairs_degraded, r.stats.sum.points_in_contact,
              static_cast<long long>(r.stats.sum.nodes_visited), micros);
  for (int p = 0; p < world.pair_count(); ++p) {
    const OrderedPair& pair = world.pair(p);
    const PairOutcome& o = world.outcome(p);
    if (!o.near) continue;
    const ContactResult& c = o.result;
    std::printf("pair %s / %s (%s): force on %s %+.6g %+.6g %+.6g N, points in contact %d, nodes visited %lld, level "
                "rendered %d, degraded %d, max penetration %.3g m\n",
                name(pair.A).c_str(), name(pair.B).c_str(), pair.model.c_str(), name(pair.B).c_str(),
                c.on_B.force.x(), c.on_B.force.y(), c.on_B.force.z(), c.stats.points_in_contact,
                static_cast<long long>(c.stats.nodes_visited), c.stats.level_rendered, c.stats.degraded,
                c.stats.max_penetration);
    if (args.contacts) {
      ContactList contacts;
      if (has_contacts[std::size_t(p)]) world.model(p).LatestContacts(&contacts);
      PrintContacts(pair.model, has_contacts[std::size_t(p)], contacts);
    }
  }
  if (r.stats.pairs_near < world.pair_count()) {
    std::printf("(%d pairs not near: their boxes do not overlap)\n", world.pair_count() - r.stats.pairs_near);
  }
}

void RunContact(const ContactArgs& args) {
  const Scene scene = LoadScene(RequireDataFile(args.scene));
  AssetOptions options;
  options.cache_dir = args.cache;
  options.use_cache = !args.no_cache;
  options.verbose = !args.json;
  if (scene.many_bodies()) {
    RunWorldContact(args, scene, options);
    return;
  }
  if (!args.pose_tool.empty()) Fail(args.scene, "--pose-tool is for a scene of many bodies (with `tool:`); give --pose-a or --pose-b");
  SceneAssets assets(scene, options);
  const std::string model_name = args.model.empty() ? scene.models.front() : args.model;
  std::unique_ptr<ReducedState> q_A, q_B;
  if (!args.q_a.empty()) q_A = std::make_unique<ReducedState>(ParseReducedCoordinates(args.q_a, assets.A, "--q-a"));
  if (!args.q_b.empty()) q_B = std::make_unique<ReducedState>(ParseReducedCoordinates(args.q_b, assets.B, "--q-b"));
  auto model = MakeSceneContactModel(model_name, scene, assets);
  ReducedVector reduced_force;

  ContactQuery q = SceneContactQuery(scene, args.pose_a.empty() ? scene.pointshell_body.pose : ParsePose(args.pose_a, "--pose-a"),
                                     args.pose_b.empty() ? scene.field_body.pose : ParsePose(args.pose_b, "--pose-b"));
  // --touch: the field body moved along the line from its origin to the pointshell body's.
  if (args.touch > 0) {
    const Eigen::Vector3d toward = q.X_WA.translation - q.X_WB.translation;
    if (!(toward.norm() > 0)) {
      Fail(args.scene + ": --touch", "the two bodies' origins coincide, so there is no direction to move the field body in");
    }
    q.X_WB = TouchAlong(scene, assets, true, q.X_WA, q.X_WB, toward, args.touch, args.scene + ": --touch");
  }
  if (args.budget >= 0) q.node_budget = args.budget;
  ReducedVector reduced_force_B;
  const BodyDeformation deformation_A{q_A.get(), &reduced_force}, deformation_B{q_B.get(), &reduced_force_B};
  if (assets.A.deformable()) q.deformation_A = &deformation_A;
  if (assets.B.deformable()) q.deformation_B = &deformation_B;
  // --contacts: room for every contact a query of these scenes makes (more are counted).
  constexpr int kMaxContacts = 1 << 20;
  const bool has_contacts = args.contacts && model->KeepContacts(kMaxContacts);
  // --slide: the field body moved by the slide from where it is, a query per step of at most
  // kSlideStep, so that the models' friction anchors follow it; the query reported is the last.
  if (!args.slide.empty()) {
    const std::vector<double> v = ParseNumberList(args.slide, "--slide");
    if (v.size() != 3) Fail("--slide", "needs 3 numbers dx,dy,dz (metres); got " + std::to_string(v.size()));
    const Eigen::Vector3d slide(v[0], v[1], v[2]);
    constexpr double kSlideStep = 1e-6, kMaxSlide = 0.1;
    if (!(slide.norm() <= kMaxSlide)) Fail("--slide", "must be at most 0.1 m long (a query per micrometre)");
    const int steps = std::max(1, int(std::ceil(slide.norm() / kSlideStep)));
    const Eigen::Vector3d start = q.X_WB.translation;
    for (int i = 0; i < steps; ++i) {
      q.X_WB.translation = start + slide * (double(i) / steps);
      q.cycle = i;
      model->Evaluate(q);
    }
    q.X_WB.translation = start + slide;
    q.cycle = steps;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const ContactResult r = model->Evaluate(q);
  const double micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  // A refused query or a non-finite wrench is an error, never a zero or "nan" printed as a result.
  if (r.stats.faults > 0) Fail(model_name, "refused the query (a deformation that does not fit its body); no wrench");
  if (!r.on_B.force.allFinite() || !r.on_B.torque.allFinite() || !r.K_B.allFinite()) {
    Fail(model_name, "gave a non-finite wrench or stiffness at these poses and coordinates; nothing printed");
  }
  ContactList contacts;
  if (has_contacts) model->LatestContacts(&contacts);

  if (args.json) {
    nlohmann::json j;
    j["scene"] = scene.name;
    j["model"] = model_name;
    j["force"] = {r.on_B.force.x(), r.on_B.force.y(), r.on_B.force.z()};
    j["torque"] = {r.on_B.torque.x(), r.on_B.torque.y(), r.on_B.torque.z()};
    AddStats(r.stats, &j);
    j["evaluate_microseconds"] = micros;
    j["K_B"] = Matrix6Json(r.K_B);
    if (q.deformation_A != nullptr) {
      j["reduced_force_A"] = std::vector<double>(reduced_force.data(), reduced_force.data() + reduced_force.size());
    }
    if (q.deformation_B != nullptr) {
      j["reduced_force_B"] = std::vector<double>(reduced_force_B.data(), reduced_force_B.data() + reduced_force_B.size());
    }
    if (args.contacts) j["contacts"] = has_contacts ? ContactsJson(contacts) : nlohmann::json(nullptr);
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::printf("scene %s, model %s\n", scene.name.c_str(), model_name.c_str());
  std::printf("force on %s  [N]:   %+.6g %+.6g %+.6g\n", scene.field_body.name.c_str(), r.on_B.force.x(),
              r.on_B.force.y(), r.on_B.force.z());
  std::printf("torque on %s [N m]: %+.6g %+.6g %+.6g (about its origin, world frame)\n", scene.field_body.name.c_str(),
              r.on_B.torque.x(), r.on_B.torque.y(), r.on_B.torque.z());
  std::printf("points in contact %d, nodes visited %lld, level rendered %d, max penetration %.3g m, %.1f us\n",
              r.stats.points_in_contact, static_cast<long long>(r.stats.nodes_visited), r.stats.level_rendered,
              r.stats.max_penetration, micros);
  if (r.stats.patches > 0) {
    std::printf("contact surface %.6g m^2 in %d patch%s\n", r.stats.contact_area, r.stats.patches,
                r.stats.patches == 1 ? "" : "es");
  }
  if (q.deformation_A != nullptr) {
    std::printf("reduced contact force on %s (U^T F, r = %d):", scene.pointshell_body.name.c_str(),
                int(reduced_force.size()));
    for (int j = 0; j < reduced_force.size(); ++j) std::printf(" %+.6g", reduced_force[j]);
    std::printf("\n");
  }
  if (q.deformation_B != nullptr) {
    std::printf("reduced contact force on %s (U^T F at its proxies, r = %d):", scene.field_body.name.c_str(),
                int(reduced_force_B.size()));
    for (int j = 0; j < reduced_force_B.size(); ++j) std::printf(" %+.6g", reduced_force_B[j]);
    std::printf("\n");
  }
  if (args.contacts) PrintContacts(model_name, has_contacts, contacts);
}

const CommandRegistration kContactCommands([](CLI::App& app) {
  auto args = std::make_shared<ContactArgs>();
  CLI::App* cmd = app.add_subcommand("contact", "Evaluate one contact query of a scene and print the wrench on the "
                                                "field body, points in contact, nodes visited and level rendered");
  cmd->add_option("SCENE", args->scene, "scene YAML file")->required();
  cmd->add_option("--model", args->model, "contact model name (default: the scene's first model)");
  cmd->add_option("--pose-a", args->pose_a, "pose of the pointshell body: x,y,z,qw,qx,qy,qz (metres)");
  cmd->add_option("--pose-b", args->pose_b, "pose of the field body: x,y,z,qw,qx,qy,qz (metres)");
  cmd->add_option("--pose-tool", args->pose_tool,
                  "a scene of many bodies: the tool's pose, x,y,z,qw,qx,qy,qz (metres); every pair is queried and "
                  "the wrench on the tool printed with one line per pair near it");
  cmd->add_option("--touch", args->touch,
                  "first move the field body toward the pointshell body until this deep, metres (from --pose-b or "
                  "the scene's pose)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--slide", args->slide,
                  "then slide the field body by dx,dy,dz (metres, world frame, at most 0.1 m) in steps of 1 um, a "
                  "query each, and report the last: the friction a scene's `friction:` block asks for loads and "
                  "slips along the way");
  cmd->add_option("--q-a", args->q_a, "deformation of body A held fixed: q1,...,qr or @FILE (default: rest)");
  cmd->add_option("--q-b", args->q_b, "deformation of body B: q1,...,qr or @FILE");
  cmd->add_option("--budget", args->budget, "node budget (warm threshold, >= 0); overrides the scene's")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--cache", args->cache, "cache folder for fields and pointshells");
  cmd->add_flag("--no-cache", args->no_cache, "neither read nor write cached fields and pointshells");
  cmd->add_flag("--json", args->json, "print JSON (with the 6x6 gradient K_B)");
  cmd->add_flag("--contacts", args->contacts,
                "also list the model's contacts (point, normal, depth; area and pressure for pressure-field), world "
                "frame; with --json under the key \"contacts\" (null for a model without a contact list)");
  cmd->callback([args] { RunContact(*args); });
});

// One line per registered model: name, what it needs of the bodies, description.
void ListModels() {
  std::vector<std::string> names = ContactModelNames();
  for (const std::string& name : ReferenceModelNames()) names.push_back(name);
  for (const std::string& name : names) {
    const ContactModelEntry& e = *FindContactModel(name);
    std::string needs;
    auto add = [&](bool need, const char* what) {
      if (need) needs += (needs.empty() ? "" : ", ") + std::string(what);
    };
    add(e.needs.pointshell_A, "A pointshell");
    add(e.needs.field_A, "A field");
    add(e.needs.mesh_A, "A mesh");
    add(e.needs.field_B, "B field");
    add(e.needs.mesh_B, e.needs.closed_mesh_B ? "B closed mesh" : "B mesh");
    const char* friction = e.friction == FrictionSupport::kRigidBodies ? " [friction: rigid bodies]" : " [frictionless]";
    std::printf("%-18s needs %-28s %s%s%s%s\n", name.c_str(), needs.c_str(), e.description.c_str(),
                e.reference_only ? " [reference only]" : "", e.allocates ? " [allocates in its queries]" : "", friction);
  }
}

const CommandRegistration kModelsCommand([](CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("models", "List the registered contact models, what each needs of the two "
                                               "bodies (A: pointshell role, B: field role) and what it is");
  cmd->callback([] { ListModels(); });
});

}  // namespace
}  // namespace contactlab::cli
