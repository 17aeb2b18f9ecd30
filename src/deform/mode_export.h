// Export of reduced mode shapes for inspection (Barbič & James 2008, sec. 4.1): the coarse
// tet mesh as a VTK legacy unstructured grid with one displacement vector field per basis
// vector, viewable in ParaView ("Warp By Vector").
#pragma once

#include <filesystem>

#include "deform/reduced_model.h"

namespace contactlab {

// Writes MODEL's mesh and basis columns (each scaled by SCALE, metres per unit q) to PATH
// atomically, each number as the shortest text that reads back exactly. Throws Error naming PATH
// when it cannot be written or a value is not finite (nothing is written then).
void ExportModesVtk(const ReducedModel& model, const std::filesystem::path& path, double scale = 1.0);

}  // namespace contactlab
