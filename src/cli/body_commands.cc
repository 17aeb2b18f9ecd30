// `contactlab body-export SCENE.yaml --body NAME [--q Q] (--mesh OUT.obj | --pointshell OUT.csv
// [--level L])`: one body of a scene in its body frame (after scale and centring), deformed by
// reduced coordinates Q when the body is deformable (paper sec. 4.1): its surface mesh, or its
// pointshell with normals and the BD-tree radius at Q, for checking against other tools.
#include <cstdio>
#include <memory>
#include <string>

#include "cli/command_registry.h"
#include "deform/deformable_pointshell.h"
#include "experiment/reduced_coordinates.h"
#include "experiment/scene_assets.h"
#include "geometry/mesh_io.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/output_target.h"

namespace contactlab::cli {
namespace {

struct BodyExportArgs {
  std::string scene, body, q, mesh_out, pointshell_out, cache;
  int level = -1;
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

// x,y,z,nx,ny,nz,level,parent,radius per tree node of levels 0..LEVEL; parent is the row of
// the parent node (-1 on level 0).
void ExportPointshell(BodyAssets& body, const ReducedState* q, int level, const std::string& out) {
  const auto shell = body.pointshell();
  const Pointshell& s = *shell;
  if (level < -1 || level >= s.num_levels()) {
    Fail("--level", std::to_string(level) + " is out of range (the pointshell has " +
                        std::to_string(s.num_levels()) + " levels)");
  }
  const int last = level < 0 ? s.num_levels() - 1 : level;
  std::shared_ptr<const DeformablePointshell> dps;
  std::vector<double> abs_q;
  if (q != nullptr) {
    dps = body.deformable_pointshell();
    for (int j = 0; j < q->size(); ++j) abs_q.push_back(std::fabs(q->q[j]));
  }
  std::string text = "x,y,z,nx,ny,nz,level,parent,radius\n";
  char line[320];
  int lev = 0;
  for (int n = 0; n < s.level_node_begin[last + 1]; ++n) {
    while (n >= s.level_node_begin[lev + 1]) ++lev;
    const int i = s.node_point[n];
    Eigen::Vector3d x(s.x[i], s.y[i], s.z[i]), nrm(s.nx[i], s.ny[i], s.nz[i]);
    double radius = s.node_radius[n];
    if (dps) {
      x = dps->points().Position(i, q->q.data());
      nrm = dps->points().CorrectedNormal(i, q->q.data());
      radius = lev == s.num_levels() - 1 ? 0.0 : dps->Radius(n, abs_q.data());
    }
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.7g,%.7g,%.7g,%d,%d,%.9g\n", x.x(), x.y(), x.z(), nrm.x(),
                  nrm.y(), nrm.z(), lev, s.node_parent[n], radius);
    text += line;
  }
  WriteFileAtomically(out, text);
  std::fprintf(stderr, "%s: %d nodes of levels 0..%d%s\n", out.c_str(), s.level_node_begin[last + 1], last,
               q ? ", deformed" : "");
}

void RunBodyExport(const BodyExportArgs& args) {
  if (args.mesh_out.empty() == args.pointshell_out.empty()) Fail("body-export", "give exactly one of --mesh and --pointshell");
  // The output is checked first: never a device or folder, never the scene or a body's mesh file.
  const std::string& out = args.mesh_out.empty() ? args.pointshell_out : args.mesh_out;
  const char* out_option = args.mesh_out.empty() ? "--pointshell" : "--mesh";
  CheckOutputTarget(out, out_option);
  const std::filesystem::path scene_file = RequireDataFile(args.scene);
  CheckOutputIsNotInput(out, scene_file, out_option);
  const Scene scene = LoadScene(scene_file);
  for (const BodySpec* b : {&scene.field_body, &scene.pointshell_body}) {
    if (const auto mesh_file = FindDataFile(b->mesh, FolderOf(scene_file))) CheckOutputIsNotInput(out, *mesh_file, out_option);
  }
  AssetOptions options;
  options.cache_dir = args.cache;
  SceneAssets assets(scene, options);
  BodyAssets* body = nullptr;
  for (BodyAssets* b : {&assets.A, &assets.B})
    if (b->spec().name == args.body) body = b;
  if (body == nullptr) {
    Fail("--body", "no body '" + args.body + "' in " + args.scene + " (bodies: " + assets.A.spec().name + ", " +
                       assets.B.spec().name + ")");
  }
  std::unique_ptr<ReducedState> q;
  if (!args.q.empty()) q = std::make_unique<ReducedState>(ParseReducedCoordinates(args.q, *body, "--q"));
  if (!args.mesh_out.empty()) {
    ExportMesh(*body, q.get(), args.mesh_out);
  } else {
    ExportPointshell(*body, q.get(), args.level, args.pointshell_out);
  }
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

}  // namespace
}  // namespace contactlab::cli
