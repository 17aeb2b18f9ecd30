// VTK export of reduced mode shapes (Barbič & James 2008, sec. 4.1).
#include "deform/mode_export.h"

#include <ostream>
#include <string>

#include "util/atomic_file.h"
#include "util/number_text.h"

namespace contactlab {

void ExportModesVtk(const ReducedModel& model, const std::filesystem::path& path, double scale) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    const TetMesh& mesh = model.mesh;
    // Every number as the shortest text that reads back exactly (util/number_text.h).
    std::string text;
    auto vector = [&](double x, double y, double z, const std::string& what) {
      AppendNumber(x, &text, what);
      text += ' ';
      AppendNumber(y, &text, what);
      text += ' ';
      AppendNumber(z, &text, what);
      text += '\n';
    };
    out << "# vtk DataFile Version 3.0\n"
        << "contactlab reduced model " << model.source << ", r = " << model.r() << "\n"
        << "ASCII\nDATASET UNSTRUCTURED_GRID\n"
        << "POINTS " << mesh.num_vertices() << " double\n";
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      const auto& p = mesh.vertices[v];
      vector(p.x(), p.y(), p.z(), "vertex " + std::to_string(v));
    }
    out << text;
    text.clear();
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
        vector(scale * model.basis(3 * v, j), scale * model.basis(3 * v + 1, j), scale * model.basis(3 * v + 2, j),
               "mode " + std::to_string(j) + " at vertex " + std::to_string(v));
      }
      out << text;
      text.clear();
    }
  });
}

}  // namespace contactlab
