// `contactlab mesh-info MESH [--json] [--scale S]`: loads a mesh (OBJ, OFF, STL, PLY) found
// through the data search path and prints its validation report (geometry/mesh_validation.h).
#include <iostream>
#include <memory>
#include <string>

#include "cli/command_registry.h"
#include "geometry/mesh_io.h"
#include "geometry/mesh_validation.h"
#include "util/data_path.h"

namespace contactlab::cli {
namespace {

struct MeshInfoArgs {
  std::string mesh;
  bool json = false;
  double scale = 1.0;
};

void RunMeshInfo(const MeshInfoArgs& args) {
  const std::filesystem::path path = RequireDataFile(args.mesh);
  MeshLoadOptions options;
  options.scale = args.scale;
  const TriangleMesh mesh = LoadMesh(path, options);
  const MeshReport report = ValidateMesh(mesh);
  if (args.json) {
    std::cout << report.ToJson() << "\n";
  } else {
    std::cout << "mesh:                    " << path.string() << "\n";
    if (args.scale != 1.0) std::cout << "scale:                   " << args.scale << "\n";
    std::cout << report.ToText();
  }
}

const CommandRegistration kMeshCommands([](CLI::App& app) {
  auto args = std::make_shared<MeshInfoArgs>();
  CLI::App* info = app.add_subcommand(
      "mesh-info", "Load a mesh (.obj .off .stl .ply) and print its validation report: counts, boundary and "
                   "non-manifold edges, orientation, components, watertightness, area, volume, bounds");
  info->add_option("MESH", args->mesh, "mesh file, or a name on the data search path (e.g. dragon.obj)")->required();
  info->add_flag("--json", args->json, "print the report as a JSON object");
  info->add_option("--scale", args->scale, "scale applied on load (file units -> metres), > 0");
  info->callback([args] { RunMeshInfo(*args); });
});

}  // namespace
}  // namespace contactlab::cli
