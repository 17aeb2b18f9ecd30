// The FCL baseline's own keys in a scene's model section (register_fcl.cc): the bounding
// volume of its mesh hierarchies, FCL's contact cap, and whether each body is a triangle mesh
// or the convex hull of its vertices.
//
// Not offered: FCL's own GJK/EPA solver for convex pairs (GST_INDEP). In FCL 0.7 it reports a
// Convex pair's depth negated and its normal in object 1's frame (FCL PR #334), and even
// corrected its depth is wrong: a 642-vertex ball hull pressed 0.5, 2 and 5 mm into a box gives
// 0.38, 1.2 and 1.4 mm, with EPA's stores enlarged 32-fold alike. libccd's MPR (FCL's default)
// gives the closed form within the tessellation (fcl_contact_model_test.cc).
#pragma once

#include <cstddef>

#include "util/param_table.h"

namespace contactlab {

// The bounding volume of FCL's BVHModel (fcl/math/bv/). All give the same contacts: the
// triangle pairs tested are the same, the BV only changes what is culled and at what cost.
// Offered: the types FCL 0.7 traverses with the bodies' transforms applied on the fly. Not
// offered: RSS, AABB and the k-DOPs. FCL collides those by copying both BVHModels into the world
// frame on every query (BVHCollideImpl), and BVHModel's copy constructor allocates its nodes with
// malloc while its destructor frees them with delete[] (AddressSanitizer: alloc-dealloc mismatch
// inside libfcl, undefined behaviour). Measured before they were withdrawn: forces identical to
// OBBRSS's, 4-540x slower (docs/results-models.md).
enum class FclBv { kObbrss, kObb, kKios };

// What FCL collides: each body's triangle mesh (BVHModel, triangle-pair contacts with a depth
// local to the pair), or fcl::Convex of its vertices (one contact with the depth of the two
// convex hulls' overlap by libccd's MPR; sensible for convex bodies only).
enum class FclShape { kMesh, kConvex };

struct FclOwnParams {
  FclBv bv = FclBv::kObbrss;         // bounding volume of the mesh hierarchies (fcl_shape: mesh)
  long long max_contacts = 100000;   // FCL's num_max_contacts
  FclShape shape = FclShape::kMesh;  // triangle meshes, or the convex hulls of their vertices
};

// The rows' names of the choices, for messages.
const char* FclBvName(FclBv bv);

const ParamTable<FclOwnParams>& FclOwnParamTable();

}  // namespace contactlab
