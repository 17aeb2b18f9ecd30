// `contactlab reduce`, `reduce-info` and `reduce-export`: precompute a reduced deformable model
// (coarse voxel tet mesh, linear modes, modal derivatives, reduced StVK polynomials) from a
// mesh or field, summarise a model file, export its mode shapes (Barbič & James 2008, sec. 4.1).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/command_registry.h"
#include "deform/mode_export.h"
#include "deform/reduced_model.h"
#include "geometry/mesh_io.h"
#include "sdf/build_distance_field.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/output_target.h"

namespace contactlab::cli {
namespace {

struct ReduceArgs {
  std::string mesh;
  int modes = 15;
  int linear_modes = 0;
  int cells = 16;
  int resolution = 96;
  int split = 6;
  bool all_components = false;
  double scale = 1.0;
  double youngs = 1e6;
  double poisson = 0.45;
  double density = 1000;
  std::vector<double> fix_below;  // one value: y
  std::vector<double> fix_box;    // six values
  bool linear = false;
  bool consistent_mass = false;
  std::string out;
};

void RunReduce(const ReduceArgs& args) {
  const std::filesystem::path path = RequireDataFile(args.mesh);
  CheckOutputWritable(args.out, "--out");
  CheckOutputIsNotInput(args.out, path, "--out");
  const std::string source = path.filename().string();
  StVKMaterial material;
  material.youngs_modulus = args.youngs;
  material.poisson_ratio = args.poisson;
  material.density = args.density;
  material.Validate("reduce " + source);  // fail before the slow field build
  // Distance field: loaded from a .sdf file, or built from the mesh.
  DistanceField field;
  if (path.extension() == ".sdf") {
    field = LoadDistanceField(path);
  } else {
    MeshLoadOptions load;
    load.scale = args.scale;
    TriangleMesh mesh = LoadMesh(path, load);
    mesh.name = source;
    DistanceFieldOptions options;
    options.resolution = args.resolution;
    field = BuildDistanceField(mesh, options);
  }
  VoxelMeshOptions voxel;
  voxel.cells = args.cells;
  if (args.split != 5 && args.split != 6) Fail("--split", "must be 5 or 6, got " + std::to_string(args.split));
  voxel.split = args.split == 5 ? TetSplit::kFive : TetSplit::kSix;
  voxel.largest_component = !args.all_components;
  const TetMesh tets = BuildVoxelTetMesh(field, voxel);

  ReducedModelOptions options;
  options.modes = args.modes;
  options.linear_modes = args.linear_modes;
  options.kind = args.linear ? ReducedModelKind::kLinear : ReducedModelKind::kStVK;
  options.material = material;
  options.mass = args.consistent_mass ? MassKind::kConsistent : MassKind::kLumped;
  if (!args.fix_below.empty() && !args.fix_box.empty()) Fail("--fix-below/--fix-box", "give at most one anchoring");
  if (!args.fix_below.empty()) options.anchoring = Anchoring::BelowY(args.fix_below[0]);
  if (!args.fix_box.empty()) {
    Aabb box;
    box.min = Eigen::Vector3d(args.fix_box[0], args.fix_box[1], args.fix_box[2]);
    box.max = Eigen::Vector3d(args.fix_box[3], args.fix_box[4], args.fix_box[5]);
    if (box.empty()) Fail("--fix-box", "min must not exceed max");
    options.anchoring = Anchoring::InBox(box);
  }
  std::cerr << "simulation mesh: " << tets.num_vertices() << " vertices, " << tets.num_tets() << " tets\n";
  const ReducedModel model = BuildReducedModel(tets, options, source);
  SaveReducedModel(model, args.out);
  std::cout << DescribeReducedModel(model) << "written to " << args.out << "\n";
}

nlohmann::json ModelJson(const ReducedModel& model, const std::string& file) {
  int fixed = 0;
  for (auto f : model.fixed) fixed += f;
  const Aabb b = model.mesh.Bounds();
  const Eigen::VectorXd freq = ModeFrequencies(model);
  return {
      {"file", file},
      {"source", model.source},
      {"kind", model.kind() == ReducedModelKind::kStVK ? "stvk" : "linear"},
      {"modes", model.r()},
      {"vertices", model.mesh.num_vertices()},
      {"tets", model.mesh.num_tets()},
      {"cell_size", model.mesh.cell_size},
      {"volume", model.mesh.Volume()},
      {"box_min", {b.min.x(), b.min.y(), b.min.z()}},
      {"box_max", {b.max.x(), b.max.y(), b.max.z()}},
      {"anchoring", model.anchoring.Describe()},
      {"fixed_vertices", fixed},
      {"youngs_modulus", model.material.youngs_modulus},
      {"poisson_ratio", model.material.poisson_ratio},
      {"density", model.material.density},
      {"mass", model.mass == MassKind::kLumped ? "lumped" : "consistent"},
      {"frequencies_hz", std::vector<double>(freq.data(), freq.data() + freq.size())},
      {"eigen_residual", model.eigen_residual},
      {"build_seconds", model.build_seconds},
  };
}

struct ExportArgs {
  std::string model;
  std::string out;
  double scale = 1.0;
};

const CommandRegistration kDeformCommands([](CLI::App& app) {
  auto args = std::make_shared<ReduceArgs>();
  CLI::App* reduce = app.add_subcommand(
      "reduce", "Precompute a reduced deformable model (reduced StVK or linear modal) on a voxel tet mesh embedding "
                "the mesh, and save it (.rm)");
  reduce->add_option("MESH", args->mesh, "mesh file, .sdf field file, or a name on the data search path")->required();
  reduce->add_option("--modes", args->modes, "reduced coordinates r")->required()->check(CLI::Range(1, kMaxReducedModes));
  reduce->add_option("--linear-modes", args->linear_modes, "linear modes whose derivatives enter the basis (0: auto)")
      ->check(CLI::NonNegativeNumber);
  reduce->add_option("--cells", args->cells, "voxel cells along the longest side of the object")->check(CLI::Range(1, 256));
  reduce->add_option("--resolution", args->resolution, "distance-field resolution when building from a mesh")
      ->check(CLI::Range(8, 1024));
  reduce->add_option("--split", args->split, "tets per voxel: 5 or 6");
  reduce->add_flag("--all-components", args->all_components, "keep every connected set of cells, not only the largest");
  reduce->add_option("--scale", args->scale, "scale applied on load (file units -> metres)")->check(CLI::PositiveNumber);
  reduce->add_option("--E", args->youngs, "Young's modulus, Pa");
  reduce->add_option("--nu", args->poisson, "Poisson's ratio, in (-1, 0.5)");
  reduce->add_option("--rho", args->density, "density, kg/m^3");
  reduce->add_option("--fix-below", args->fix_below, "anchor vertices with y <= Y (metres)")->expected(1);
  reduce->add_option("--fix-box", args->fix_box, "anchor vertices inside the box XMIN YMIN ZMIN XMAX YMAX ZMAX")
      ->expected(6);
  reduce->add_flag("--linear", args->linear, "linear modal model (constant stiffness) instead of reduced StVK");
  reduce->add_flag("--consistent-mass", args->consistent_mass, "consistent instead of lumped mass matrix");
  reduce->add_option("--out", args->out, "output model file (.rm)")->required();
  reduce->callback([args] { RunReduce(*args); });

  auto info_path = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* info = app.add_subcommand("reduce-info", "Print the summary of a reduced model file");
  info->add_option("MODEL", *info_path, "model file (.rm)")->required();
  info->add_flag("--json", *json, "print JSON");
  info->callback([info_path, json] {
    const ReducedModel model = LoadReducedModel(*info_path);
    if (*json) {
      std::cout << ModelJson(model, *info_path).dump(2) << "\n";
    } else {
      std::cout << DescribeReducedModel(model);
    }
  });

  auto ex = std::make_shared<ExportArgs>();
  CLI::App* exp = app.add_subcommand(
      "reduce-export", "Export the simulation mesh and one displacement field per basis vector (VTK legacy)");
  exp->add_option("MODEL", ex->model, "model file (.rm)")->required();
  exp->add_option("--out", ex->out, "output .vtk file")->required();
  exp->add_option("--scale", ex->scale, "displacement per unit reduced coordinate (multiplies the basis)");
  exp->callback([ex] {
    CheckOutputWritable(ex->out, "--out");
    CheckOutputIsNotInput(ex->out, ex->model, "--out");
    const ReducedModel model = LoadReducedModel(ex->model);
    ExportModesVtk(model, ex->out, ex->scale);
    std::cout << "wrote " << model.r() << " mode fields to " << ex->out << "\n";
  });
});

}  // namespace
}  // namespace contactlab::cli
