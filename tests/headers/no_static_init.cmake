# Fails when PROGRAM's symbols include a static initialiser: a _GLOBAL__sub_I_ function,
# which g++ and clang++ emit for a translation unit whose namespace-scope variables are
# initialised at run time (and which then runs before main in every program).
#
#   cmake -DNM=<nm> -DPROGRAM=<executable> -P no_static_init.cmake
cmake_minimum_required(VERSION 3.20)
execute_process(COMMAND ${NM} ${PROGRAM} OUTPUT_VARIABLE symbols RESULT_VARIABLE status)
if(NOT status EQUAL 0)
    message(FATAL_ERROR "nm ${PROGRAM} failed")
endif()
string(REGEX MATCHALL "_GLOBAL__sub_I_[A-Za-z0-9_.]*" found "${symbols}")
if(found)
    list(JOIN found ", " text)
    message(FATAL_ERROR "static initialiser found: ${text}")
endif()
message("no static initialiser in ${PROGRAM}")
