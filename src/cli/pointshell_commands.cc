// `contactlab pointshell`, `pointshell-info` and `pointshell-export`: build a nested
// multiresolution pointshell by particle repulsion (or an alternative sampling) from a mesh or
// a distance field, summarise a pointshell file, and export one level (Barbič & James 2008,
// sec. 2.2 and 2.4).
#include <algorithm>
#include <cctype>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/command_registry.h"
#include "geometry/mesh_io.h"
#include "pointshell/build_pointshell.h"
#include "pointshell/pointshell_export.h"
#include "pointshell/pointshell_io.h"
#include "pointshell/pointshell_quality.h"
#include "sdf/build_distance_field.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/output_target.h"

namespace contactlab::cli {
namespace {

struct PointshellArgs {
  std::string input;
  int points = 0;
  int levels = 0;
  std::optional<double> offset;
  std::string method = "repulsion";
  std::uint64_t seed = 1;
  int resolution = 128;
  double scale = 1.0;
  int branching = 4;
  std::string report;
  std::string out;
};

bool HasExtension(const std::filesystem::path& path, const std::string& ext) {
  std::string e = path.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e == ext;
}

void RunPointshell(const PointshellArgs& args) {
  const std::filesystem::path path = RequireDataFile(args.input);
  CheckOutputWritable(args.out, "--out");
  CheckOutputIsNotInput(args.out, path, "--out");
  if (!args.report.empty()) {
    CheckOutputWritable(args.report, "--report");
    CheckOutputIsNotInput(args.report, path, "--report");
    CheckOutputIsNotInput(args.report, args.out, "--report");
  }
  PointshellOptions options;
  options.method = ParsePointshellMethod(args.method, "--method");
  options.num_points = args.points;
  options.num_levels = args.levels;
  options.branching = args.branching;
  options.offset = args.offset;
  options.seed = args.seed;
  options.show_progress = true;
  // The field: loaded from a .sdf file, or built from the mesh.
  std::optional<TriangleMesh> mesh;
  DistanceField field;
  if (HasExtension(path, ".sdf")) {
    if (options.method == PointshellMethod::kVertices) {
      Fail(path.string(), "the vertices method needs a mesh input, not a distance field");
    }
    field = LoadDistanceField(path);
  } else {
    MeshLoadOptions load;
    load.scale = args.scale;
    mesh = LoadMesh(path, load);
    mesh->name = path.filename().string();
    DistanceFieldOptions field_options;
    field_options.resolution = args.resolution;
    field_options.show_progress = true;
    field = BuildDistanceField(*mesh, field_options);
    std::cout << DescribeDistanceField(field);
  }
  PointshellBuildReport report;
  const Pointshell shell = BuildPointshell(field, options, mesh ? &*mesh : nullptr, &report);
  SavePointshell(shell, args.out);
  for (std::size_t i = 0; i < report.levels.size(); ++i) {
    const auto& l = report.levels[i];
    std::cout << "repulsion level " << i << ": " << l.free_points << " new points (" << l.frozen_points
              << " frozen), kernel width " << l.kernel_width << " m, " << l.iterations << " iterations"
              << (l.converged ? " (converged)" : " (iteration limit)") << ", " << l.seconds << " s\n";
  }
  std::cout << "built " << shell.num_points() << " points in " << shell.num_levels() << " levels in "
            << report.seconds << " s\n";
  const PointshellQuality quality = AssessPointshell(shell, &field);
  std::cout << QualityToText(quality) << "written to " << args.out << "\n";
  if (!args.report.empty()) {
    nlohmann::json j = QualityToJson(quality);
    j["build_seconds"] = report.seconds;
    j["seed"] = shell.seed;
    WriteFileAtomically(args.report, j.dump(2) + "\n");
  }
}

struct InfoArgs {
  std::string shell;
  std::string field;
  bool json = false;
};

void RunInfo(const InfoArgs& args) {
  const Pointshell shell = LoadPointshell(args.shell);
  std::optional<DistanceField> field;
  if (!args.field.empty()) field = LoadDistanceField(args.field);
  const PointshellQuality quality = AssessPointshell(shell, field ? &*field : nullptr);
  if (args.json) {
    nlohmann::json j = QualityToJson(quality);
    j["file"] = args.shell;
    j["seed"] = shell.seed;
    j["points"] = shell.num_points();
    j["nodes"] = shell.num_nodes();
    j["level_point_end"] = shell.level_point_end;
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << args.shell << ": " << shell.num_points() << " points, " << shell.num_levels() << " levels, "
            << shell.num_nodes() << " tree nodes, seed " << shell.seed << "\n"
            << QualityToText(quality);
}

struct ExportArgs {
  std::string shell;
  std::optional<int> level;
  std::string out;
};

const CommandRegistration kPointshellCommands([](CLI::App& app) {
  auto ps = std::make_shared<PointshellArgs>();
  CLI::App* build = app.add_subcommand(
      "pointshell", "Build a nested multiresolution pointshell on the offset level set d = offset of a mesh's "
                    "distance field (particle repulsion, or voxel / vertices / random sampling) and save it");
  build->add_option("INPUT", ps->input, "mesh file (a distance field is built first) or field file (.sdf)")
      ->required();
  build->add_option("--points", ps->points, "points of the deepest level (voxel: approximate), at most 2^24")
      ->required()
      ->check(CLI::Range(1, 1 << 24));
  build->add_option("--levels", ps->levels, "tree levels, 1 to 12")->required()->check(CLI::Range(1, 12));
  build->add_option("--offset", ps->offset, "level-set offset in metres (default: half the field spacing)");
  build->add_option("--method", ps->method, "repulsion (default) | voxel | vertices (mesh input) | random");
  build->add_option("--seed", ps->seed, "random seed (default 1)");
  build->add_option("--branching", ps->branching, "growth of the point count per level (default 4)")
      ->check(CLI::Range(2, 64));
  build->add_option("--resolution", ps->resolution, "mesh input: field cells along the longest box side")
      ->check(CLI::Range(8, 1024));
  build->add_option("--scale", ps->scale, "mesh input: scale applied on load (file units -> metres)")
      ->check(CLI::PositiveNumber);
  build->add_option("--report", ps->report, "also write the quality report as JSON to this file");
  build->add_option("--out", ps->out, "output pointshell file (.ps)")->required();
  build->callback([ps] { RunPointshell(*ps); });

  auto info = std::make_shared<InfoArgs>();
  CLI::App* inf = app.add_subcommand("pointshell-info", "Print the per-level summary of a pointshell file");
  inf->add_option("SHELL", info->shell, "pointshell file (.ps)")->required();
  inf->add_option("--field", info->field,
                  "the field it was built on (.sdf): adds covering radius, normal error, level-set distance");
  inf->add_flag("--json", info->json, "print JSON instead of text");
  inf->callback([info] { RunInfo(*info); });

  auto ex = std::make_shared<ExportArgs>();
  CLI::App* exp = app.add_subcommand(
      "pointshell-export", "Write the points of one tree level as ASCII PLY with normals or CSV "
                           "(x,y,z,nx,ny,nz,level,parent,radius)");
  exp->add_option("SHELL", ex->shell, "pointshell file (.ps)")->required();
  exp->add_option("--level", ex->level, "tree level (default: the deepest)");
  exp->add_option("--out", ex->out, "output file, .ply or .csv")->required();
  exp->callback([ex] {
    CheckOutputWritable(ex->out, "--out");
    CheckOutputIsNotInput(ex->out, ex->shell, "--out");
    const Pointshell shell = LoadPointshell(ex->shell);
    const int level = ex->level.value_or(shell.num_levels() - 1);
    ExportPointshell(shell, level, ex->out);
    std::cout << "level " << level << ": " << shell.level_point_end[std::clamp(level, 0, shell.num_levels() - 1)]
              << " points written to " << ex->out << "\n";
  });
});

}  // namespace
}  // namespace contactlab::cli
