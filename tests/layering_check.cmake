# Layering (docs/architecture.md "Layers"), checked on the sources: nothing in src/contact or baselines
# includes a header of the experiment harness or the command line, nor of deform/ other than
# where deformed points are (the kinematics: embedded points and their vector batches, the
# deformable pointshell, the deformed distance field, the tet mesh they live in);
# baselines/CMakeLists.txt checks the same of what they link when the build is configured. Run by ctest as
#   cmake -DROOT=<source dir> -P tests/layering_check.cmake
file(GLOB_RECURSE sources ${ROOT}/src/contact/*.h ${ROOT}/src/contact/*.cc ${ROOT}/baselines/*.h ${ROOT}/baselines/*.cc)
list(LENGTH sources count)
if(count LESS 10)
  message(FATAL_ERROR "layering: found only ${count} sources under ${ROOT}; wrong ROOT?")
endif()
set(violations "")
foreach(f IN LISTS sources)
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"(experiment|cli|haptics)/")
  foreach(l IN LISTS lines)
    string(APPEND violations "\n  ${f}: ${l}")
  endforeach()
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"deform/")
  foreach(l IN LISTS lines)
    if(NOT l MATCHES "\"deform/(embedded_points|reduced_point_batch|deformable_pointshell|deformed_distance_field|deformed_field_batch|tet_mesh)\\.h\"")
      string(APPEND violations "\n  ${f}: ${l}")
    endif()
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "layering: contact/ and baselines/ must not include experiment/, cli/, haptics/ or the finite-element part of deform/:${violations}")
endif()
message(STATUS "layering: ${count} files of src/contact and baselines include nothing of experiment/, cli/, haptics/ or deform/'s finite elements")
