# `cmake --install` (or `make install`): the contactlab command, the data it reads and the
# figure script, laid out so that PREFIX/bin/contactlab finds PREFIX/share/contactlab/data on
# its own (src/util/data_path.h):
#   PREFIX/bin/contactlab
#   PREFIX/share/contactlab/data/{meshes,scenes,trajectories}
#   PREFIX/share/contactlab/experiments/*.yaml
#   PREFIX/share/contactlab/scripts/make_figures.py and its figures/ package
#   PREFIX/share/doc/contactlab/{README.md,LICENSE}
#   PREFIX/lib/libcontactlab_*.a, PREFIX/include/contactlab/ (the headers of src/ and
#   baselines/ as they are included: "contact/contact_model.h", "contact/register_contact_models.h")
#   and PREFIX/lib/cmake/ContactLab/: the CMake package, find_package(ContactLab) ->
#   ContactLab::contactlab (examples/cpp uses it)
#   PREFIX/lib/python3/dist-packages/contactlab/ (the Python module, when built: Debian's folder
#   for the prefix /usr, python/install_dir.py) and PREFIX/share/doc/contactlab/examples/python
# `cpack -G DEB` in the build folder makes a .deb of the same files.
install(TARGETS contactlab-cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/data)
file(GLOB _contactlab_configs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/experiments/*.yaml)
install(FILES ${_contactlab_configs} DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/experiments)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/make_figures.py DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/scripts)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scripts/figures DESTINATION ${CONTACTLAB_INSTALL_SHAREDIR}/scripts
        FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
if(TARGET contactlab_python)
  # The package folder depends on the prefix installed to, which cpack changes (/usr for the
  # .deb): asked of the interpreter at install time unless CONTACTLAB_INSTALL_PYTHONDIR names it.
  file(GLOB _contactlab_python_files CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/python/contactlab/*.py)
  list(APPEND _contactlab_python_files ${PROJECT_BINARY_DIR}/python/contactlab/_build.py)  # python/CMakeLists.txt
  install(CODE "
    set(_pythondir [[${CONTACTLAB_INSTALL_PYTHONDIR}]])
    if(_pythondir STREQUAL \"\")
      execute_process(COMMAND [[${Python_EXECUTABLE}]] [[${PROJECT_SOURCE_DIR}/python/install_dir.py]]
                              \"\${CMAKE_INSTALL_PREFIX}\"
                      OUTPUT_VARIABLE _pythondir RESULT_VARIABLE _result)
      if(NOT _result EQUAL 0 OR _pythondir STREQUAL \"\")
        message(FATAL_ERROR \"cannot ask ${Python_EXECUTABLE} for its package folder; set CONTACTLAB_INSTALL_PYTHONDIR\")
      endif()
    endif()
    if(NOT IS_ABSOLUTE \"\${_pythondir}\")
      set(_pythondir \"\${CMAKE_INSTALL_PREFIX}/\${_pythondir}\")
    endif()
    file(INSTALL DESTINATION \"\${_pythondir}/contactlab\" TYPE MODULE FILES [[$<TARGET_FILE:contactlab_python>]])
    file(INSTALL DESTINATION \"\${_pythondir}/contactlab\" TYPE FILE FILES ${_contactlab_python_files})
  ")
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/python/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples/python
          FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
endif()

# --- The library and its CMake package. Exported: the umbrella `contactlab` and every
# contactlab_* library it links, found by walking its link interface (static libraries' private
# links included: their consumers link them too), so a library added to the umbrella is
# exported with it.
set(_contactlab_exported "")
set(_contactlab_queue contactlab)
while(_contactlab_queue)
  list(POP_FRONT _contactlab_queue _t)
  if(_t IN_LIST _contactlab_exported)
    continue()
  endif()
  list(APPEND _contactlab_exported ${_t})
  get_target_property(_links ${_t} INTERFACE_LINK_LIBRARIES)
  get_target_property(_type ${_t} TYPE)
  if(NOT _type STREQUAL "INTERFACE_LIBRARY")
    get_target_property(_private ${_t} LINK_LIBRARIES)
    list(APPEND _links ${_private})
  endif()
  foreach(_l IN LISTS _links)
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" _l "${_l}")
    if(_l MATCHES "^contactlab_" AND TARGET ${_l})
      list(APPEND _contactlab_queue ${_l})
    endif()
  endforeach()
endwhile()
set(CONTACTLAB_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/ContactLab)
install(TARGETS ${_contactlab_exported} EXPORT ContactLabTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/contactlab)
install(EXPORT ContactLabTargets NAMESPACE ContactLab:: DESTINATION ${CONTACTLAB_INSTALL_CMAKEDIR})
# The headers, in the layout they are included by: src/X/... as X/..., baselines/... as
# baselines/... (the command line and the viewer, which are not in the library, left out).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/contactlab
        FILES_MATCHING PATTERN "*.h" PATTERN "cli" EXCLUDE PATTERN "view" EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/baselines/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/contactlab/baselines
        FILES_MATCHING PATTERN "*.h")
include(CMakePackageConfigHelpers)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/ContactLabConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/ContactLabConfig.cmake
                              INSTALL_DESTINATION ${CONTACTLAB_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/ContactLabConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/ContactLabConfig.cmake ${PROJECT_BINARY_DIR}/ContactLabConfigVersion.cmake
        DESTINATION ${CONTACTLAB_INSTALL_CMAKEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/cpp DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples)

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
# find_package(ContactLab) (the static libraries' CMake package) needs the development packages
# of what they link.
set(_contactlab_cgal_dev "")
if(CONTACTLAB_WITH_CGAL)
  set(_contactlab_cgal_dev ", libcgal-dev, libgmp-dev, libmpfr-dev, libboost-dev")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "libeigen3-dev, libtbb-dev, libyaml-cpp-dev, nlohmann-json3-dev, zlib1g-dev, libnanoflann-dev, libhwy-dev, libspectra-dev, liboctomap-dev, libfcl-dev, libccd-dev, libbullet-dev, libbullet-extras-dev, libspnav-dev, pkg-config${_contactlab_cgal_dev}")
if(TARGET contactlab_python)
  # The module is built for Debian's python3 and returns NumPy arrays; load_results reads pandas.
  math(EXPR _python_next_minor "${Python_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS
      "python3 (>= ${Python_VERSION_MAJOR}.${Python_VERSION_MINOR}), python3 (<< ${Python_VERSION_MAJOR}.${_python_next_minor}), python3-numpy")
  string(APPEND CPACK_DEBIAN_PACKAGE_RECOMMENDS ", python3-pandas")
endif()
if(CONTACTLAB_WITH_CGAL)
  set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "${CPACK_PACKAGE_DESCRIPTION_SUMMARY}\n Built with CGAL: the binary is covered by the GPL-3.0-or-later.")
endif()
set(CPACK_GENERATOR DEB)
include(CPack)
