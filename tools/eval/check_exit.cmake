# Runs TOOL --gt GT --est EST [EXTRA_OPT EXTRA_VAL] and checks that it exits with EXPECT_RC and that stderr contains
# EXPECT_ERR. Usage: cmake -DTOOL=... -DGT=... -DEST=... -DEXPECT_RC=2 -DEXPECT_ERR=... -P this
execute_process(COMMAND ${TOOL} --gt ${GT} --est ${EST} ${EXTRA_OPT} ${EXTRA_VAL}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "${EXPECT_RC}")
  message(FATAL_ERROR "expected exit code ${EXPECT_RC}, got '${rc}'\nstdout: ${out}\nstderr: ${err}")
endif()
string(FIND "${err}" "${EXPECT_ERR}" pos)
if(pos EQUAL -1)
  message(FATAL_ERROR "stderr does not contain '${EXPECT_ERR}':\n${err}")
endif()
message(STATUS "exit code ${rc}, stderr: ${err}")
