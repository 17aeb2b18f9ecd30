// Barbič & James 2008, sec. 4: the deformable instances of the paper's contact model.
#include "pointshell_contact/deformable_contact_models.h"

namespace contactlab {

template class PointshellFieldModel<DeformableShell, GridField>;
template class PointshellFieldModel<RigidShell, DeformedField>;
template class PointshellFieldModel<DeformableShell, DeformedField>;

}  // namespace contactlab
