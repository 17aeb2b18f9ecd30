# Runs PROGRAM with ARGS (a ;-list) and fails unless it exits with status EXPECTED and, when
# OUTPUT_HAS is given, prints it (stdout or stderr). A crash is not an exit status and fails.
execute_process(COMMAND ${PROGRAM} ${ARGS} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status STREQUAL "${EXPECTED}")
  message(FATAL_ERROR "${PROGRAM} exited with '${status}', expected ${EXPECTED}\n${out}\n${err}")
endif()
if(DEFINED OUTPUT_HAS AND NOT "${out}${err}" MATCHES "${OUTPUT_HAS}")
  message(FATAL_ERROR "${PROGRAM} did not print '${OUTPUT_HAS}'\n${out}\n${err}")
endif()
