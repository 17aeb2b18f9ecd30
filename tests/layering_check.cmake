# The layering rule of DESIGN.md, checked on the sources: nothing in src/contact or baselines
# includes a header of the experiment harness or the command line. Run by ctest as
#   cmake -DROOT=<source dir> -P tests/layering_check.cmake
file(GLOB_RECURSE sources ${ROOT}/src/contact/*.h ${ROOT}/src/contact/*.cc ${ROOT}/baselines/*.h ${ROOT}/baselines/*.cc)
list(LENGTH sources count)
if(count LESS 10)
  message(FATAL_ERROR "layering: found only ${count} sources under ${ROOT}; wrong ROOT?")
endif()
set(violations "")
foreach(f IN LISTS sources)
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"(experiment|cli)/")
  foreach(l IN LISTS lines)
    string(APPEND violations "\n  ${f}: ${l}")
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "layering: contact/ and baselines/ must not include experiment/ or cli/:${violations}")
endif()
message(STATUS "layering: ${count} files of src/contact and baselines include nothing of experiment/ or cli/")
