// A body filled with non-overlapping inner spheres (Weller & Zachmann, "Inner Sphere Trees for
// Proximity and Penetration Queries", RSS 2009): greedy largest empty spheres on the grid of its
// signed distance field (every grid point up to about two million of them, else every k-th per
// axis). Each candidate point inside the body has a free radius, the largest sphere
// centred there that stays inside the body (-phi) and outside every sphere placed; the point
// with the largest free radius takes the next sphere. Free radii only shrink, so a lazy
// priority queue places them in order, re-measuring a point only against the spheres placed
// since it was last measured.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sdf/distance_field.h"

namespace contactlab {

// Bumped when the packing built from the same field and parameters changes (cache key).
inline constexpr int kSpherePackingVersion = 1;

struct SpherePackingOptions {
  int max_spheres = 2000;    // stop after this many
  double coverage = 0;       // stop once the spheres fill this fraction of VOLUME (0: no target)
  double min_radius_cells = 0.5;  // stop when the largest free radius is below this (cells)
};

struct SpherePacking {
  std::vector<Eigen::Vector3d> centers;  // body frame, metres
  std::vector<double> radii;
  double body_volume = 0;  // the volume the coverage is measured against, m^3
  // Fraction of the body's volume the spheres fill.
  double Coverage() const;
  double SphereVolume() const;
};

// Packs the inside (phi < 0) of FIELD, whose body has volume BODY_VOLUME (m^3, > 0). Throws
// Error naming WHERE when the field has no inside or the options are out of range.
SpherePacking BuildSpherePacking(const DistanceField& field, double body_volume, const SpherePackingOptions& options,
                                 const std::string& where);

void SaveSpherePacking(const SpherePacking& packing, const std::filesystem::path& path);
// Throws Error naming PATH when the file is not a sphere packing or is damaged.
SpherePacking LoadSpherePacking(const std::filesystem::path& path);

}  // namespace contactlab
