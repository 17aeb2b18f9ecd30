// A body filled with non-overlapping inner spheres (Weller & Zachmann, "Inner Sphere Trees for
// Proximity and Penetration Queries", RSS 2009): greedy largest empty spheres, the next sphere
// always where the free radius (the largest sphere centred there that stays inside the body,
// -phi, and outside every sphere placed) is largest among the candidate centres.
//
// Why grid points alone stop at 72-80 %: a sphere's centre can only be a candidate, and the
// packing ends when no candidate is left with a free radius above the floor. Once every grid
// point lies inside a placed sphere or within the floor of one, that is the end, although the
// voids between spheres (the gaps between three or four spheres, and the wedges between the
// spheres and a flat face, whose deepest points fall between the grid points) still hold
// spheres: their centres are no grid point. Lowering the floor does not help: on a box of
// 60 x 27 x 25 cells the grid-only packing stops at 72.0 % with a floor of half a cell and at
// 74.1 % with a tenth of a cell (every grid point's free radius then below 0.1 cell), while
// its voids still take spheres of 0.65 cell centred off the grid (sphere_packing_test.cc).
//
// So the candidates are not limited to grid points. As in Weller & Zachmann's Protosphere
// packing (Weller & Zachmann, "ProtoSphere: A GPU-Assisted Prototype Guided Sphere Packing
// Algorithm for Arbitrary Objects", SIGGRAPH Asia 2010 sketch), each winning candidate is a
// prototype that moves away from its nearest obstacles (the body's surface and the placed
// spheres) while its free radius grows, which takes it to the centre of its void (a vertex of
// the obstacles' Voronoi diagram); and every placed sphere seeds new prototypes just outside
// its surface, so every void next to a sphere gets a candidate whether or not it holds a grid
// point. Free radii only shrink as spheres are placed, so a lazy priority queue takes the
// candidates in order, re-measuring one only when spheres were placed since it was measured
// (against the newest spheres directly, or through a grid of cells binning the placed spheres).
//
// What is left is the slow tail of any packing of spheres: each void takes ever smaller ones.
// 90 % of that box at 120 x 53 x 50 cells takes about 280,000 spheres; the meshes of the bench
// scenes (fields of 128 cells) stop at 84-90 % when the smallest sphere, a tenth of a cell, is
// reached (docs/models.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sdf/distance_field.h"

namespace contactlab {

// Bumped when the packing built from the same field and parameters changes (cache key).
inline constexpr int kSpherePackingVersion = 2;

struct SpherePackingOptions {
  int max_spheres = 2000;    // stop after this many
  double coverage = 0;       // stop once the spheres fill this fraction of VOLUME (0: no target)
  double min_radius_cells = 0.1;  // stop when the largest free radius is below this (cells)
  // Protosphere prototypes (moves and seeds, above); false: candidates on the grid points only
  // (the packing of version 1, kept to measure what the grid alone reaches).
  bool protosphere = true;
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
