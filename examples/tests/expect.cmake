# Runs one command and checks its exit status and output, for the example programs' tests.
#
#   cmake -DPROGRAM=<exe> -DARGS=<arg|arg|...> -DEXPECT_EXIT=<n> [-DEXPECT_OUTPUT=<regex>]
#         [-DREJECT_OUTPUT=<regex>] [-DEXPECT_ABSENT=<file|file...>] [-DKEEP=<file>]
#         -P expect.cmake
#
# ARGS separates arguments with '|' (a CMake list would be split by add_test); @EMPTY@
# stands for an empty argument. The test fails unless the exit status is EXPECT_EXIT,
# stdout+stderr match EXPECT_OUTPUT and do not match REJECT_OUTPUT.
# EXPECT_ABSENT: files removed before the run that must not exist after it, nor any
# "<file>.partial-*" temporary file next to them.
# KEEP: a file written with known bytes before the run that must hold them after it (an
# existing output file kept when the run fails).
if(NOT DEFINED PROGRAM OR NOT DEFINED EXPECT_EXIT)
    message(FATAL_ERROR "expect.cmake needs PROGRAM and EXPECT_EXIT")
endif()
string(REPLACE "|" ";" absent "${EXPECT_ABSENT}")
foreach(file IN LISTS absent)
    file(REMOVE "${file}")
endforeach()
set(kept_bytes "kept by a failed run\n")
if(DEFINED KEEP)
    file(WRITE "${KEEP}" "${kept_bytes}")
endif()

# The command is built as code so that an empty argument survives (a list drops it).
string(REPLACE "|" ";" arguments "${ARGS}")
set(command "execute_process(COMMAND \"${PROGRAM}\"")
foreach(argument IN LISTS arguments)
    if(argument STREQUAL "@EMPTY@")
        set(argument "")
    endif()
    string(REPLACE "\\" "\\\\" argument "${argument}")
    string(REPLACE "\"" "\\\"" argument "${argument}")
    string(REPLACE "$" "\\$" argument "${argument}")
    string(APPEND command " \"${argument}\"")
endforeach()
string(APPEND command " RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)")
cmake_language(EVAL CODE "${command}")

message("${out}${err}")
if(NOT status STREQUAL EXPECT_EXIT)
    message(FATAL_ERROR "exit status ${status}, expected ${EXPECT_EXIT}")
endif()
if(DEFINED EXPECT_OUTPUT AND NOT "${out}${err}" MATCHES "${EXPECT_OUTPUT}")
    message(FATAL_ERROR "output does not match '${EXPECT_OUTPUT}'")
endif()
if(DEFINED REJECT_OUTPUT AND "${out}${err}" MATCHES "${REJECT_OUTPUT}")
    message(FATAL_ERROR "output matches '${REJECT_OUTPUT}', which it must not")
endif()
foreach(file IN LISTS absent)
    if(EXISTS "${file}")
        message(FATAL_ERROR "'${file}' exists after the run")
    endif()
    file(GLOB partial "${file}.partial-*")
    if(partial)
        message(FATAL_ERROR "temporary files left after the run: ${partial}")
    endif()
endforeach()
if(DEFINED KEEP)
    file(READ "${KEEP}" now)
    if(NOT now STREQUAL kept_bytes)
        message(FATAL_ERROR "'${KEEP}' was changed by the run")
    endif()
endif()
