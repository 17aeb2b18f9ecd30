# `cmake --install` (or `make install`): the contactlab command, the data it reads and the
# figure script, laid out so that PREFIX/bin/contactlab finds PREFIX/share/contactlab/data on
# its own (src/util/data_path.h):
#   PREFIX/bin/contactlab
#   PREFIX/share/contactlab/data/{meshes,scenes,trajectories}
#   PREFIX/share/contactlab/experiments/*.yaml
#   PREFIX/share/contactlab/scripts/make_figures.py and its figures/ package
#   PREFIX/share/doc/contactlab/{README.md,LICENSE}
# `cpack -G DEB` in the build folder makes a .deb of the same files.
install(TARGETS contactlab-cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/data)
file(GLOB _contactlab_configs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/experiments/*.yaml)
install(FILES ${_contactlab_configs} DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/experiments)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/make_figures.py DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/scripts)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scripts/figures DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/scripts
        FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(CPACK_PACKAGE_NAME contactlab)
set(CPACK_PACKAGE_VENDOR "ContactLab")
set(CPACK_PACKAGE_CONTACT "ContactLab maintainers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Testbed for six-degree-of-freedom haptic contact (Barbic & James 2008)")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# libjs-three: `contactlab view` and `session --view` inline three.js from its files.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-matplotlib, python3-numpy, python3-yaml, libjs-three")
if(CONTACTLAB_WITH_CGAL)
  set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "${CPACK_PACKAGE_DESCRIPTION_SUMMARY}\n Built with CGAL: the binary is covered by the GPL-3.0-or-later.")
endif()
set(CPACK_GENERATOR DEB)
include(CPack)
