# Runs one command and checks its exit status and output, for the compare tool's tests.
#
#   cmake -DPROGRAM=<exe> -DARGS=<arg|arg|...> -DEXPECT_EXIT=<n> [-DEXPECT_OUTPUT=<regex>]
#         -P expect.cmake
#
# ARGS separates arguments with '|' (a CMake list would be split by add_test). The test
# fails unless the exit status is EXPECT_EXIT and stdout+stderr match EXPECT_OUTPUT.
if(NOT DEFINED PROGRAM OR NOT DEFINED EXPECT_EXIT)
    message(FATAL_ERROR "expect.cmake needs PROGRAM and EXPECT_EXIT")
endif()
string(REPLACE "|" ";" arguments "${ARGS}")
execute_process(COMMAND ${PROGRAM} ${arguments}
    RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT status STREQUAL EXPECT_EXIT)
    message(FATAL_ERROR "exit status ${status}, expected ${EXPECT_EXIT}")
endif()
if(DEFINED EXPECT_OUTPUT AND NOT "${out}${err}" MATCHES "${EXPECT_OUTPUT}")
    message(FATAL_ERROR "output does not match '${EXPECT_OUTPUT}'")
endif()
