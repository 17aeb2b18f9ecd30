// VTK export of reduced mode shapes (Barbič & James 2008, sec. 4.1).
#include "deform/mode_export.h"

#include <iomanip>
#include <ostream>

#include "util/atomic_file.h"

namespace contactlab {

void ExportModesVtk(const ReducedModel& model, const std::filesystem::path& path, double scale) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    const TetMesh& mesh = model.mesh;
    out << std::setprecision(9);
    out << "# vtk DataFile Version 3.0\n"
        << "contactlab reduced model " << model.source << ", r = " << model.r() << "\n"
        << "ASCII\nDATASET UNSTRUCTURED_GRID\n"
        << "POINTS " << mesh.num_vertices() << " double\n";
    for (const auto& p : mesh.vertices) out << p.x() << " " << p.y() << " " << p.z() << "\n";
    out << "CELLS " << mesh.num_tets() << " " << 5 * mesh.num_tets() << "\n";
    for (const auto& t : mesh.tets) out << "4 " << t[0] << " " << t[1] << " " << t[2] << " " << t[3] << "\n";
    out << "CELL_TYPES " << mesh.num_tets() << "\n";
    for (int t = 0; t < mesh.num_tets(); ++t) out << "10\n";
    out << "POINT_DATA " << mesh.num_vertices() << "\n";
    out << "SCALARS fixed int 1\nLOOKUP_TABLE default\n";
    for (auto f : model.fixed) out << int(f) << "\n";
    for (int j = 0; j < model.r(); ++j) {
      out << "VECTORS mode_" << j << " double\n";
      for (int v = 0; v < mesh.num_vertices(); ++v) {
        out << scale * model.basis(3 * v, j) << " " << scale * model.basis(3 * v + 1, j) << " "
            << scale * model.basis(3 * v + 2, j) << "\n";
      }
    }
  });
}

}  // namespace contactlab
