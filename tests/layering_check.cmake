# The layering rule (docs/architecture.md, "Layers"), checked on the sources: src/contact is the
# interface alone, so it includes no model (src/pointshell_contact, baselines/) and nothing of
# deform/; no model (the paper's in src/pointshell_contact, or a baseline) includes a header of
# the experiment harness, the haptic loop or the command line, nor of deform/ other than where
# deformed points are (the kinematics: embedded points and their vector batches, the deformable
# pointshell, the deformed distance field, the tet mesh they live in). The scene layer
# (src/scene) sits below the harness, the viewer, the command and Python: it includes nothing of
# experiment/, view/ or cli/, and no model (it asks the registry for what it needs of one).
# cmake/contact_models.cmake checks the same of what they link when the build is configured. Run
# by ctest as
#   cmake -DROOT=<source dir> -P tests/layering_check.cmake
file(GLOB_RECURSE interface ${ROOT}/src/contact/*.h ${ROOT}/src/contact/*.cc)
file(GLOB_RECURSE models ${ROOT}/src/pointshell_contact/*.h ${ROOT}/src/pointshell_contact/*.cc ${ROOT}/baselines/*.h
     ${ROOT}/baselines/*.cc)
file(GLOB_RECURSE scene_layer ${ROOT}/src/scene/*.h ${ROOT}/src/scene/*.cc)
list(LENGTH interface interface_count)
list(LENGTH scene_layer scene_count)
list(LENGTH models model_count)
if(interface_count LESS 5 OR model_count LESS 10 OR scene_count LESS 6)
  message(FATAL_ERROR "layering: found only ${interface_count} + ${model_count} + ${scene_count} sources under ${ROOT}; wrong ROOT?")
endif()
set(violations "")
foreach(f IN LISTS interface models)
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"(experiment|cli|haptics|view)/")
  foreach(l IN LISTS lines)
    string(APPEND violations "\n  ${f}: ${l}")
  endforeach()
endforeach()
foreach(f IN LISTS interface)
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"(deform|pointshell_contact|baselines)/")
  foreach(l IN LISTS lines)
    string(APPEND violations "\n  ${f}: ${l} (contact/ is the interface alone)")
  endforeach()
endforeach()
foreach(f IN LISTS models)
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"deform/")
  foreach(l IN LISTS lines)
    if(NOT l MATCHES "\"deform/(embedded_points|reduced_point_batch|deformable_pointshell|deformed_distance_field|deformed_field_batch|tet_mesh)\\.h\"")
      string(APPEND violations "\n  ${f}: ${l}")
    endif()
  endforeach()
endforeach()
foreach(f IN LISTS scene_layer)
  file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*\"(experiment|cli|view|pointshell_contact|baselines)/")
  foreach(l IN LISTS lines)
    string(APPEND violations "\n  ${f}: ${l} (scene/ is below the harness, the viewer and the command, and names no model)")
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "layering: scene/ must include nothing of experiment/, cli/, view/ or any model; contact/ must include no model and nothing of deform/; no model may include experiment/, cli/, haptics/, view/ or deform/'s finite elements:${violations}")
endif()
message(STATUS "layering: ${scene_count} files of src/scene include nothing of experiment/, cli/, view/ or any model; ${interface_count} files of src/contact include no model and nothing of deform/; ${model_count} files of src/pointshell_contact and baselines include nothing of experiment/, cli/, haptics/, view/ or deform/'s finite elements")
