// The paper's contact model with a deformable body (Barbič & James 2008, sec. 4): the instances of
// PointshellFieldModel whose shell side (sec. 4.1), field side (sec. 4.2) or both deform.
#pragma once

#include "pointshell_contact/deformable_sides.h"
#include "pointshell_contact/pointshell_field_model.h"
#include "pointshell_contact/rigid_sides.h"

namespace contactlab {

// A deformable pointshell against a rigid field.
using DeformablePointshellContactModel = PointshellFieldModel<DeformableShell, GridField>;
// A rigid pointshell against a deformed field.
using RigidShellDeformedFieldModel = PointshellFieldModel<RigidShell, DeformedField>;
// Both bodies deformable.
using DeformableShellDeformedFieldModel = PointshellFieldModel<DeformableShell, DeformedField>;

extern template class PointshellFieldModel<DeformableShell, GridField>;
extern template class PointshellFieldModel<RigidShell, DeformedField>;
extern template class PointshellFieldModel<DeformableShell, DeformedField>;

}  // namespace contactlab
