// Procedural closed meshes for tests and demos. Every mesh is closed, manifold and oriented
// outward, centred at the origin unless said otherwise. Sizes in metres.
#pragma once

#include "geometry/triangle_mesh.h"

namespace contactlab {

// Icosphere: 20 * 4^SUBDIVISIONS triangles, vertices exactly on the sphere of RADIUS.
TriangleMesh MakeSphere(double radius, int subdivisions = 4);

// Axis-aligned box with half extents HALF: 12 N^2 triangles with N cuts per edge (12 with one).
TriangleMesh MakeBox(const Eigen::Vector3d& half, int cuts_per_edge = 1);

// Torus around the z axis: MAJOR radius of the tube centre line, MINOR tube radius.
TriangleMesh MakeTorus(double major, double minor, int major_segments = 64, int minor_segments = 32);

// Capsule along z: a cylinder of RADIUS and length 2*HALF_LENGTH capped by hemispheres.
TriangleMesh MakeCapsule(double radius, double half_length, int segments = 32, int rings = 8);

// Open-ended tube along z (a thick-walled cylinder, genus 1): OUTER and INNER radii, length
// 2*HALF_LENGTH, flat annular ends. Vertices lie exactly on both circles; SEGMENTS around.
TriangleMesh MakeTube(double outer, double inner, double half_length, int segments = 64);

// A closed slab of size SIZE x SIZE (x, y) and THICKNESS (z from -THICKNESS to 0) whose top
// face z = 0 carries BUMPS x BUMPS smooth cosine bumps of HEIGHT, sampled by RESOLUTION
// quads per side. For "scan across bumps" experiments.
TriangleMesh MakeBumpyPlate(double size, double thickness, int bumps, double height,
                            int resolution = 128);

}  // namespace contactlab
