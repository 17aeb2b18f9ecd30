// The deformed distance field (Barbič & James 2008, sec. 4.2) answering many points at once:
// for a group of points (one per vector lane) the k nearest deformed proxies of a domain are
// kept sorted in registers while the domain's proxies stream past (compare and blend, no
// branches), the eq. (3) weights are formed lane-wise, the k pull-backs gather their proxy's
// affine map, and the k pulled-back points of a whole batch go to the domain's rest field as one
// vectorised lookup (sdf/batch_distance.h). Google Highway, run-time dispatch.
#pragma once

#include <cstdint>

#include "deform/deformed_distance_field.h"

namespace contactlab {

// D[k] = FIELD.Distance(STATE, (X, Y, Z)[k]) for k < N (field body frame) and, when NEAREST is
// not null, NEAREST[k] the slot that call reports. Equal to the one-point Distance to float
// rounding (fused multiply-adds, another summation order); the same proxies are chosen, ties
// broken alike. With several domains, a domain whose lower bound
// (DeformedFieldDomainBounds) exceeds the distance another domain already gave a
// point is not queried for it: it cannot hold the minimum. Returns the (point, domain) queries
// answered, N per domain without that culling. Allocates nothing, throws nothing.
std::int64_t DeformedFieldDistances(const DeformedDistanceField& field, const DeformedFieldState& state,
                                    const float* x, const float* y, const float* z, int n, float* d,
                                    std::int32_t* nearest);

// OUT[k] = a lower bound on domain DOM's distance at (X, Y, Z)[k], k < N, for STATE, without a
// proxy scan or a lookup: every pulled-back point lies within rho = spread + slope |x - O| of
// the domain's mean map c + A x (DeformedFieldState::DomainBound); where that ball lies outside
// the box of one of the domain's levels, each pulled-back distance, and so their weighted mean,
// exceeds the level; where it lies outside the field's grid, each is at least its conservative
// bound. -infinity where neither holds (x near or inside the domain, or not finite). Less a
// margin for rounding (1e-4 of a cell and 1e-5 relative: pull-backs, lookups and weights are
// float). Allocates nothing, throws nothing.
void DeformedFieldDomainBounds(const DeformedDistanceField& field, const DeformedFieldState& state, int dom,
                               const float* x, const float* y, const float* z, int n, float* out);

}  // namespace contactlab
