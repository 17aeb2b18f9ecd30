// The per-point work of a deformable pointshell (Barbič & James 2008, sec. 4.1) many points at
// a time: deformed positions x = X + U q, corrected normals, and the reduced force and stiffness of the points in
// contact, sum_k d_k U_k^T N_k and sum_k (U_k^T N_k)(U_k^T N_k)^T. Each point's three rows of
// U are read as whole vectors from EmbeddedPoints' padded rows, and the dot products of a
// group of points are reduced together (one vector of results per group), so the loops run
// at vector width whether the points are contiguous (linear traversal) or a tree level's list
// (whose next rows are prefetched). Google Highway, the instruction set chosen at run time as
// for sdf/batch_distance.h.
#pragma once

#include <cstdint>

#include "deform/embedded_points.h"

namespace contactlab {

// Largest EmbeddedPoints::basis_stride().
inline constexpr int kMaxBasisStride =
    (kMaxReducedModes + EmbeddedPoints::kBasisLanes - 1) / EmbeddedPoints::kBasisLanes * EmbeddedPoints::kBasisLanes;

// (X, Y, Z)[k] = rest position + U_i q of point i = INDEX[k] (BEGIN + k when INDEX is null) of
// P, k < N; the rest positions are REST_X/Y/Z[i]. Q holds P.basis_stride() floats, zero past
// r. Equal to EmbeddedPoints::Position to float rounding (another summation order). Allocates nothing,
// throws nothing.
void DeformedPositions(const EmbeddedPoints& P, const float* rest_x, const float* rest_y, const float* rest_z,
                       const float* q, const std::int32_t* index, int begin, int n, float* x, float* y, float* z);

// (NX, NY, NZ)[k] = normalize(rest normal + N_i q), the corrected unit normal of point
// i = INDEX[k], k < N, the rest normals REST_NX/NY/NZ[i] (zero where the sum is zero). Equal to
// EmbeddedPoints::CorrectedNormal to float rounding.
void CorrectedNormals(const EmbeddedPoints& P, const float* rest_nx, const float* rest_ny, const float* rest_nz,
                      const float* q, const std::int32_t* index, int n, float* nx, float* ny, float* nz);

// The reduced sums of N points in contact: point i = INDEX[k] at depth D[k] with unit normal
// (NX, NY, NZ)[i] acts through w_k = U_i^T N_i. Adds sum_k d_k w_k to G_SUM (stride floats)
// and, when STIFFNESS is non-null, sum_k w_k w_k^T to it: row b < r at STIFFNESS + b stride,
// stride floats each (entries past r stay zero). Float sums; allocates nothing.
void AddReducedPointSums(const EmbeddedPoints& P, const float* nx, const float* ny, const float* nz,
                         const std::int32_t* index, const float* d, int n, float* g_sum, float* stiffness);

// The memory bound of DeformedPositions over points [0, N): reads their rows of U and rest
// positions with vector loads and nothing else, returning their sum (benchmarks time it).
float StreamPointRows(const EmbeddedPoints& P, const float* rest_x, const float* rest_y, const float* rest_z, int n);

// The instruction set they run with on this CPU ("AVX2", "SSE4", ...).
const char* ReducedPointBatchTarget();

}  // namespace contactlab
