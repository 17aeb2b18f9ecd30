// Exporting one tree level of a pointshell for viewing and plotting (Barbič & James 2008, sec.
// 2.4, Fig. 7): ASCII PLY with normals, or CSV.
#pragma once

#include <filesystem>

#include "pointshell/pointshell.h"

namespace contactlab {

// Writes the points of tree level LEVEL (the prefix [0, level_point_end[LEVEL])) to PATH,
// atomically; format by extension (case-insensitive):
//  .ply: ASCII PLY, vertex properties x y z nx ny nz (float; normals inward, as stored);
//  .csv: header x,y,z,nx,ny,nz,level,parent,radius, one row per point: level = the
//        repulsion level that introduced the point, parent = the point index of the parent
//        of its first instance (-1 on level 0), radius = the bounding radius of its node on
//        tree level LEVEL (metres; 0 on the deepest level).
// Throws Error naming PATH for an unknown extension or a write failure, and for LEVEL outside
// [0, num_levels).
void ExportPointshell(const Pointshell& shell, int level, const std::filesystem::path& path);

}  // namespace contactlab
