// Reduced coordinates q of a deformable body given on a command line (paper sec. 4: u = U q):
// "q1,q2,...,qr" or "@FILE", FILE holding the r numbers separated by commas, spaces or line
// breaks ('#' starts a comment to the end of the line).
#pragma once

#include <string>

#include "reduced/reduced_state.h"

namespace contactlab {

class BodyAssets;

// Parses TEXT for BODY, which must be deformable with r reduced coordinates. Throws Error
// naming OPTION (e.g. "--q-a") for a rigid body, a wrong count of values, a value that is not
// a finite number, coordinates whose deformation U q is not finite (they overflow) or moves a
// node of the simulation mesh beyond kMaxCoordinate (geometry/triangle_mesh.h: what the mesh
// readers accept), or an unreadable file.
ReducedState ParseReducedCoordinates(const std::string& text, BodyAssets& body, const std::string& option);

}  // namespace contactlab
