// `contactlab body-export SCENE.yaml --body NAME [--q Q] (--mesh OUT.obj | --pointshell OUT.csv
// [--level L])`: one body of a scene in its body frame (after scale and centring), deformed by
// reduced coordinates Q when the body is deformable (paper sec. 4.1): its surface mesh, or its
// pointshell with normals and the BD-tree radius at Q, for checking against other tools.
//
// `contactlab body-eval SCENE.yaml --body NAME [--q Q] --points IN.csv --out OUT.csv`: the
// body's signed distance at points of its body frame, x,y,z,d: its rest field for a rigid body
// (as sdf-eval), its deformed distance field at Q for a deformable one (paper sec. 4.2).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli/command_registry.h"
#include "deform/deformable_pointshell.h"
#include "deform/deformed_distance_field.h"
#include "scene/reduced_coordinates.h"
#include "scene/scene_assets.h"
#include "geometry/mesh_io.h"
#include "sdf/point_csv.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/number_text.h"
#include "util/output_target.h"

namespace contactlab::cli {
namespace {

struct BodyExportArgs {
  std::string scene, body, q, mesh_out, pointshell_out, cache;
  std::optional<int> level;  // --level, when given
};

void ExportMesh(BodyAssets& body, const ReducedState* q, const std::string& out) {
  TriangleMesh mesh = *body.mesh();
  if (q != nullptr) {
    const auto model = body.reduced_model();
    const EmbeddedPoints points(model->mesh, model->basis, mesh.vertices, {}, GradientScheme::kSmooth);
    for (int v = 0; v < mesh.num_vertices(); ++v) mesh.vertices[v] = points.Position(v, q->q.data());
  }
  SaveMesh(mesh, out);
  std::fprintf(stderr, "%s: %d vertices, %d triangles%s\n", out.c_str(), mesh.num_vertices(), mesh.num_triangles(),
               q ? ", deformed" : "");
}

// x,y,z,nx,ny,nz,level,parent,radius per tree node of levels 0..LEVEL (every level when not
// given); parent is the row of the parent node (-1 on level 0).
void ExportPointshell(BodyAssets& body, const ReducedState* q, std::optional<int> level, const std::string& out) {
  const auto shell = body.pointshell();
  const Pointshell& s = *shell;
  if (level && (*level < 0 || *level >= s.num_levels())) {
    Fail("--level", std::to_string(*level) + " is out of range: the pointshell has levels 0.." +
                        std::to_string(s.num_levels() - 1) + " (leave --level out for all of them)");
  }
  const int last = level ? *level : s.num_levels() - 1;
  std::shared_ptr<const DeformablePointshell> dps;
  std::vector<double> abs_q;
  if (q != nullptr) {
    dps = body.deformable_pointshell();
    for (int j = 0; j < q->size(); ++j) abs_q.push_back(std::fabs(q->q[j]));
  }
  // Deformed values are doubles, rest values the pointshell's floats: each written as the
  // shortest text that reads back exactly (util/number_text.h); a non-finite one writes nothing.
  WriteFileAtomically(out, [&](std::ostream& stream) {
    std::string text = "x,y,z,nx,ny,nz,level,parent,radius\n";
    int lev = 0;
    for (int n = 0; n < s.level_node_begin[last + 1]; ++n) {
      while (n >= s.level_node_begin[lev + 1]) ++lev;
      const int i = s.node_point[n];
      const std::string what = "node " + std::to_string(n);
      if (dps) {
        const Eigen::Vector3d x = dps->points().Position(i, q->q.data());
        const Eigen::Vector3d nrm = dps->points().CorrectedNormal(i, q->q.data());
        for (int c = 0; c < 3; ++c) AppendNumber(x[c], &text, what + " position"), text += ',';
        for (int c = 0; c < 3; ++c) AppendNumber(nrm[c], &text, what + " normal"), text += ',';
      } else {
        for (const float v : {s.x[i], s.y[i], s.z[i]}) AppendNumber(v, &text, what + " position"), text += ',';
        for (const float v : {s.nx[i], s.ny[i], s.nz[i]}) AppendNumber(v, &text, what + " normal"), text += ',';
      }
      text += std::to_string(lev) + ',' + std::to_string(s.node_parent[n]) + ',';
      if (dps) {
        AppendNumber(lev == s.num_levels() - 1 ? 0.0 : dps->Radius(n, abs_q.data()), &text, what + " radius");
      } else {
        AppendNumber(s.node_radius[n], &text, what + " radius");
      }
      text += '\n';
    }
    stream << text;
  });
  std::fprintf(stderr, "%s: %d nodes of levels 0..%d%s\n", out.c_str(), s.level_node_begin[last + 1], last,
               q ? ", deformed" : "");
}

// A scene loaded for one of its bodies, with OUT (the command's output, option OUT_OPTION)
// checked first: never a device or folder, never the scene or a body's mesh file.
struct SceneBody {
  Scene scene;
  std::unique_ptr<SceneAssets> assets;
  BodyAssets* body = nullptr;
  std::unique_ptr<ReducedState> q;  // --q, when given
};

SceneBody LoadSceneBody(const std::string& scene_arg, const std::string& body_name, const std::string& q_text,
                        const std::string& cache, const std::string& out, const char* out_option,
                        const std::vector<std::filesystem::path>& other_inputs = {}) {
  CheckOutputWritable(out, out_option);
  const std::filesystem::path scene_file = RequireDataFile(scene_arg);
  CheckOutputIsNotInput(out, scene_file, out_option);
  for (const auto& in : other_inputs) CheckOutputIsNotInput(out, in, out_option);
  SceneBody sb;
  sb.scene = LoadScene(scene_file);
  if (sb.scene.many_bodies()) {
    // A scene of many bodies: the named body, held as the two-body fields' pointshell body.
    std::string names;
    for (const BodySpec* b : sb.scene.AllBodies()) {
      names += (names.empty() ? "" : ", ") + b->name;
      if (b->name == body_name) sb.scene.pointshell_body = *b;
    }
    if (sb.scene.pointshell_body.name != body_name) Fail("--body", "no body '" + body_name + "' in " + scene_arg + " (bodies: " + names + ")");
  }
  for (const BodySpec* b : sb.scene.AllBodies()) {
    if (const auto mesh_file = FindDataFile(b->mesh, FolderOf(scene_file))) CheckOutputIsNotInput(out, *mesh_file, out_option);
  }
  AssetOptions options;
  options.cache_dir = cache;
  sb.assets = std::make_unique<SceneAssets>(sb.scene, options);
  for (BodyAssets* b : {&sb.assets->A, &sb.assets->B})
    if (b->spec().name == body_name) sb.body = b;
  if (sb.body == nullptr) {
    Fail("--body", "no body '" + body_name + "' in " + scene_arg + " (bodies: " + sb.assets->A.spec().name + ", " +
                       sb.assets->B.spec().name + ")");
  }
  if (!q_text.empty()) sb.q = std::make_unique<ReducedState>(ParseReducedCoordinates(q_text, *sb.body, "--q"));
  return sb;
}

void RunBodyExport(const BodyExportArgs& args) {
  if (args.mesh_out.empty() == args.pointshell_out.empty()) Fail("body-export", "give exactly one of --mesh and --pointshell");
  const std::string& out = args.mesh_out.empty() ? args.pointshell_out : args.mesh_out;
  SceneBody sb = LoadSceneBody(args.scene, args.body, args.q, args.cache, out,
                               args.mesh_out.empty() ? "--pointshell" : "--mesh");
  if (!args.mesh_out.empty()) {
    ExportMesh(*sb.body, sb.q.get(), args.mesh_out);
  } else {
    ExportPointshell(*sb.body, sb.q.get(), args.level, args.pointshell_out);
  }
}

struct BodyEvalArgs {
  std::string scene, body, q, points, out, cache;
};

void RunBodyEval(const BodyEvalArgs& args) {
  const std::filesystem::path points_file = RequireDataFile(args.points);
  SceneBody sb = LoadSceneBody(args.scene, args.body, args.q, args.cache, args.out, "--out", {points_file});
  const std::vector<Eigen::Vector3d> points = ReadPointsCsv(points_file);
  std::vector<double> d(points.size());
  if (sb.body->deformable()) {
    const auto field = sb.body->deformed_field();
    DeformedFieldState state(*field);
    state.Update(*field, sb.q ? sb.q->q.data() : nullptr);
    for (std::size_t i = 0; i < points.size(); ++i) d[i] = field->Distance(state, points[i]);
  } else {
    const auto field = sb.body->field();
    for (std::size_t i = 0; i < points.size(); ++i) d[i] = field->Distance(points[i]);
  }
  WritePointDistancesCsv(args.out, points, d);
  std::fprintf(stderr, "%s: %zu points, %s\n", args.out.c_str(), points.size(),
               sb.body->deformable() ? (sb.q ? "deformed field at --q" : "deformed field at rest") : "rigid field");
}

const CommandRegistration kBodyExport([](CLI::App& app) {
  auto args = std::make_shared<BodyExportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "body-export", "Write one body of a scene in its body frame, deformed by --q: its surface mesh (--mesh) or its "
                     "pointshell with normals and BD-tree radii (--pointshell)");
  cmd->add_option("SCENE", args->scene, "scene YAML file")->required();
  cmd->add_option("--body", args->body, "body name")->required();
  cmd->add_option("--q", args->q, "reduced coordinates: q1,q2,...,qr or @FILE (deformable bodies)");
  cmd->add_option("--mesh", args->mesh_out, "write the surface mesh (.obj, .off, .stl, .ply)");
  cmd->add_option("--pointshell", args->pointshell_out, "write x,y,z,nx,ny,nz,level,parent,radius CSV");
  cmd->add_option("--level", args->level, "with --pointshell: deepest tree level written (default: all)");
  cmd->add_option("--cache", args->cache, "cache folder for fields, pointshells and reduced models");
  cmd->callback([args] { RunBodyExport(*args); });
});

const CommandRegistration kBodyEval([](CLI::App& app) {
  auto args = std::make_shared<BodyEvalArgs>();
  CLI::App* cmd = app.add_subcommand(
      "body-eval", "Signed distance of one body of a scene at points of its body frame: its field when rigid, its "
                   "deformed distance field at --q when deformable");
  cmd->add_option("SCENE", args->scene, "scene YAML file")->required();
  cmd->add_option("--body", args->body, "body name")->required();
  cmd->add_option("--q", args->q, "reduced coordinates: q1,q2,...,qr or @FILE (deformable bodies; default: at rest)");
  cmd->add_option("--points", args->points, "points CSV (x,y,z per row, body frame, metres)")->required();
  cmd->add_option("--out", args->out, "output CSV x,y,z,d")->required();
  cmd->add_option("--cache", args->cache, "cache folder for fields, pointshells and reduced models");
  cmd->callback([args] { RunBodyEval(*args); });
});

}  // namespace
}  // namespace contactlab::cli
