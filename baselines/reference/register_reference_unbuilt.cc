// In a build without CGAL (-DCONTACTLAB_WITH_CGAL=OFF): the names register_reference.cc
// registers, recorded as not built (contact/unbuilt_models.h), so that a config naming one is
// told to build with CGAL rather than that the model is unknown.
#include "contact/unbuilt_models.h"

namespace contactlab {

void RegisterReferenceContactModels() {
  for (const char* name : {"reference", "volume", "eq2-halfspace"}) {
    RegisterUnbuiltContactModel(name, "it needs CGAL (configure with -DCONTACTLAB_WITH_CGAL=ON)");
  }
}

}  // namespace contactlab
