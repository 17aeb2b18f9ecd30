# Finds OpenVDB's core library (Debian: libopenvdb-dev) and defines OpenVDB::openvdb.
#
# Debian's own FindOpenVDB.cmake (/usr/lib/<arch>/cmake/OpenVDB) requires the Boost.Iostreams
# development package, which libopenvdb-dev does not depend on and which only OpenVDB's
# delayed file loading needs; building grids in memory needs the library, its headers, Imath
# (half floats in the headers) and TBB. Sets OpenVDB_FOUND and OpenVDB_VERSION.
find_path(OpenVDB_INCLUDE_DIR openvdb/openvdb.h)
find_library(OpenVDB_LIBRARY openvdb)
if(OpenVDB_INCLUDE_DIR AND EXISTS ${OpenVDB_INCLUDE_DIR}/openvdb/version.h)
  file(STRINGS ${OpenVDB_INCLUDE_DIR}/openvdb/version.h _vdb_version
       REGEX "^#define OPENVDB_LIBRARY_VERSION_STRING ")
  string(REGEX REPLACE ".*\"([0-9.]+)\".*" "\\1" OpenVDB_VERSION "${_vdb_version}")
endif()
# Imath directly: its CMake config warns about a Python module Debian does not ship.
find_path(OpenVDB_Imath_INCLUDE_DIR Imath/half.h)
find_library(OpenVDB_Imath_LIBRARY NAMES Imath-3_1 Imath)
find_package(TBB QUIET)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenVDB
  REQUIRED_VARS OpenVDB_LIBRARY OpenVDB_INCLUDE_DIR OpenVDB_Imath_LIBRARY OpenVDB_Imath_INCLUDE_DIR TBB_FOUND
  VERSION_VAR OpenVDB_VERSION)

if(OpenVDB_FOUND AND NOT TARGET OpenVDB::openvdb)
  add_library(OpenVDB::openvdb UNKNOWN IMPORTED)
  set_target_properties(OpenVDB::openvdb PROPERTIES
    IMPORTED_LOCATION ${OpenVDB_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES "${OpenVDB_INCLUDE_DIR};${OpenVDB_Imath_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${OpenVDB_Imath_LIBRARY};TBB::tbb")
endif()
mark_as_advanced(OpenVDB_INCLUDE_DIR OpenVDB_LIBRARY OpenVDB_Imath_INCLUDE_DIR OpenVDB_Imath_LIBRARY)
