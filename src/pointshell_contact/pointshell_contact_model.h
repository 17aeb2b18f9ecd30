// The paper's contact model with both bodies rigid: a pointshell against a grid distance field
// (Barbič & James 2008, sec. 2.1, 3, 5), the rigid x grid instance of PointshellFieldModel.
#pragma once

#include "pointshell_contact/pointshell_field_model.h"
#include "pointshell_contact/rigid_sides.h"

namespace contactlab {

using PointshellContactModel = PointshellFieldModel<RigidShell, GridField>;
extern template class PointshellFieldModel<RigidShell, GridField>;

}  // namespace contactlab
