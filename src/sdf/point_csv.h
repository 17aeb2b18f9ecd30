// Query points in and distances out as CSV, for `contactlab sdf-eval` (Barbič & James 2008,
// sec. 2.3: trilinear distance queries).
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace contactlab {

// Reads rows "x,y,z" (metres; spaces around fields allowed; blank lines skipped; an optional
// first header line whose first field is not a number). Throws Error naming PATH and the line
// for a row without exactly three finite numbers, and for a missing or unreadable file.
std::vector<Eigen::Vector3d> ReadPointsCsv(const std::filesystem::path& path);

// Writes "x,y,z,d" with a header line, each number as the shortest text that reads back exactly
// (util/number_text.h), atomically (util/atomic_file.h). Throws Error naming PATH, writing
// nothing, for a non-finite point or distance.
// POINTS and DISTANCES have the same length.
void WritePointDistancesCsv(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
                            const std::vector<double>& distances);

}  // namespace contactlab
