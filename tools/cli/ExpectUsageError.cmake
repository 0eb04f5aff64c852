# Runs PROGRAM with the list ARGS and passes when it exits with 2 and its standard error contains
# EXPECT (cmake -DPROGRAM=... -DARGS=a;b -DEXPECT=... -P ExpectUsageError.cmake).
execute_process(COMMAND "${PROGRAM}" ${ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
    message(FATAL_ERROR "expected exit code 2, got '${rc}'\nstderr:\n${err}")
endif()
string(FIND "${err}" "${EXPECT}" at)
if(at EQUAL -1)
    message(FATAL_ERROR "expected '${EXPECT}' on stderr, got:\n${err}")
endif()
message(STATUS "refused as expected: ${EXPECT}")
