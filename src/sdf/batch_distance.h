// Many field lookups at once: the signed distance of points P_i = R p_i + t in a field, N points
// per instruction (Google Highway, the widest instruction set of the running CPU chosen at run
// time: AVX-512, AVX2, SSE4 or scalar). The per-point loops of the paper's contact model
// (Barbič & James 2008, sec. 3) call it on a chunk of points, then add the few in contact.
#pragma once

#include <cstdint>

#include "sdf/distance_field.h"

namespace contactlab {

// A rigid map p -> R p + t in float (R row-major), the pointshell body's pose in the field's frame.
struct BatchTransform {
  float r[9];
  float t[3];
};

// The identity: points looked up as they are, already in the field's frame (R p + t is p bit for
// bit, each coordinate a fused 1 * p + 0).
inline constexpr BatchTransform kIdentityTransform{{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0}};

// D[k] = FIELD.Distance(R p + t) for p = (X[i], Y[i], Z[i]), i = INDEX[k] (or i = k when INDEX
// is null), k in [0, N). Equal to the scalar Distance to float rounding (the vector path uses
// fused multiply-adds). Never allocates, never throws; the field must hold fewer than 2^31
// samples (DistanceField's constructor checks).
void BatchDistances(const DistanceField& field, const BatchTransform& X, const float* x, const float* y,
                    const float* z, const std::int32_t* index, int n, float* d);

// The instruction set BatchDistances runs with on this CPU ("AVX3", "AVX2", "SSE4", ...).
const char* BatchDistanceTarget();

}  // namespace contactlab
