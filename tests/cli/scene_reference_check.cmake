# docs/scene-reference.md is what `contactlab params` prints: regenerate it with
#   build/bin/contactlab params --out docs/scene-reference.md
# whenever a parameter table changes. Arguments: ROOT (source tree), CLI, OUT (a scratch file).
execute_process(COMMAND ${CLI} params --out ${OUT} RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "contactlab params failed (${rc}): ${err}")
endif()
file(READ ${OUT} generated)
file(READ ${ROOT}/docs/scene-reference.md committed)
if(NOT generated STREQUAL committed)
  message(FATAL_ERROR "docs/scene-reference.md differs from `contactlab params`: regenerate it with "
                      "`build/bin/contactlab params --out docs/scene-reference.md`")
endif()
