// `contactlab sdf`, `sdf-info` and `sdf-eval`: build a signed distance field from a mesh or a
// polygon soup, summarise a field file, and evaluate a field at CSV points (Barbič & James
// 2008, sec. 2.3).
#include <iostream>
#include <memory>
#include <string>

#include "cli/command_registry.h"
#include "geometry/mesh_io.h"
#include "sdf/build_distance_field.h"
#include "sdf/point_csv.h"
#include "sdf/sparse_field.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/output_target.h"

namespace contactlab::cli {
namespace {

struct SdfArgs {
  std::string mesh;
  int resolution = 128;
  std::string mode = "auto";
  double scale = 1.0;
  double offset = -1;
  double padding = 0.1;
  std::string storage = "dense";
  int band = 3;
  std::string out;
};

void RunSdf(const SdfArgs& args) {
  const std::filesystem::path path = RequireDataFile(args.mesh);
  CheckOutputWritable(args.out, "--out");
  CheckOutputIsNotInput(args.out, path, "--out");
  DistanceFieldOptions options;
  options.resolution = args.resolution;
  options.mode = ParseFieldMode(args.mode, "--mode");
  options.padding = args.padding;
  options.soup_offset = args.offset;
  options.storage = ParseFieldStorage(args.storage, "--storage");
  options.band_voxels = args.band;
  options.show_progress = true;
  MeshLoadOptions load;
  load.scale = args.scale;
  TriangleMesh mesh = LoadMesh(path, load);
  mesh.name = path.filename().string();
  const DistanceField field = BuildDistanceField(mesh, options);
  SaveDistanceField(field, args.out);
  std::cout << DescribeDistanceField(field) << "written to " << args.out << "\n";
}

struct SdfEvalArgs {
  std::string field;
  std::string points;
  std::string out;
};

void RunSdfEval(const SdfEvalArgs& args) {
  CheckOutputWritable(args.out, "--out");
  CheckOutputIsNotInput(args.out, args.field, "--out");
  CheckOutputIsNotInput(args.out, args.points, "--out");
  const DistanceField field = LoadDistanceField(args.field);
  const std::vector<Eigen::Vector3d> points = ReadPointsCsv(args.points);
  std::vector<double> d(points.size());
  for (std::size_t n = 0; n < points.size(); ++n) d[n] = field.DistanceAndGradient(points[n], nullptr);
  WritePointDistancesCsv(args.out, points, d);
  std::cout << "evaluated " << points.size() << " points, written to " << args.out << "\n";
}

const CommandRegistration kSdfCommands([](CLI::App& app) {
  auto sdf = std::make_shared<SdfArgs>();
  CLI::App* build = app.add_subcommand(
      "sdf", "Build a signed distance field from a mesh (closed meshes: exact; polygon soups: the zero level set "
             "is the offset surface at distance --offset from the soup) and save it");
  build->add_option("MESH", sdf->mesh, "mesh file, or a name on the data search path (e.g. dragon.obj)")
      ->required();
  build->add_option("--resolution", sdf->resolution, "grid cells along the longest side of the padded box [8, 1024]")
      ->required();
  build->add_option("--mode", sdf->mode, "auto (closed when watertight, else soup) | closed | soup");
  build->add_option("--scale", sdf->scale, "scale applied on load (file units -> metres)")
      ->check(CLI::PositiveNumber);
  build->add_option("--offset", sdf->offset, "soup iso-offset in metres (default: 1.5 voxel spacings)")
      ->check(CLI::PositiveNumber);
  build->add_option("--padding", sdf->padding, "box margin per side, fraction of the largest extent, 0 to 4")
      ->check(CLI::Range(0.0, kMaxFieldPadding));
  build->add_option("--storage", sdf->storage,
                    "dense (every sample) | sparse (fine samples in a band around the surface over a "
                    "1/8-resolution field; closed meshes, resolution a multiple of 8, at least 64)");
  build->add_option("--band", sdf->band, "sparse: voxels of fine samples on each side of the surface [1, 16]")
      ->check(CLI::Range(1, SparseFieldStorage::kMaxBand));
  build->add_option("--out", sdf->out, "output field file (.sdf)")->required();
  build->callback([sdf] { RunSdf(*sdf); });

  auto info_path = std::make_shared<std::string>();
  CLI::App* info = app.add_subcommand("sdf-info", "Print the summary of a distance-field file");
  info->add_option("FIELD", *info_path, "field file (.sdf)")->required();
  info->callback([info_path] { std::cout << DescribeDistanceField(LoadDistanceField(*info_path)); });

  auto eval = std::make_shared<SdfEvalArgs>();
  CLI::App* ev = app.add_subcommand(
      "sdf-eval", "Evaluate a distance field at points read from CSV (x,y,z rows, optional header); writes x,y,z,d");
  ev->add_option("FIELD", eval->field, "field file (.sdf)")->required();
  ev->add_option("--points", eval->points, "input CSV of points, metres")->required();
  ev->add_option("--out", eval->out, "output CSV x,y,z,d")->required();
  ev->callback([eval] { RunSdfEval(*eval); });
});

}  // namespace
}  // namespace contactlab::cli
