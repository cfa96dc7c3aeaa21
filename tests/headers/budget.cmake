# Header cost budget: preprocesses every public header under ${ROOT}/shade alone (a
# translation unit holding only `#include <shade/...>`) and counts the lines of the
# preprocessor's output, the measure of what a header costs every file that includes it.
# Budgets (lines, with g++ 12 and libstdc++, -std=c++20): 60000 for the headers of core/,
# brdf/, bsdf/, geometry/, light/, shading/ and color/ (their detail/ folders included), 95000 for
# the umbrella shade/shade.hpp, 85000 for any other (the property kit in check/, which
# needs containers and streams), and 75000 for shade/brdf/any_brdf.hpp, which owns its
# model through std::unique_ptr and so pays for <memory> (about 22000 lines). New headers
# are found by globbing at test time.
#
#   cmake -DCXX=<compiler> -DROOT=<include dir> [-DEXTRA_FLAGS=<list>] -P budget.cmake
cmake_minimum_required(VERSION 3.20)

foreach(var CXX ROOT)
    if(NOT DEFINED ${var})
        message(FATAL_ERROR "budget.cmake: -D${var}=... is required")
    endif()
endforeach()

set(lean_folders core brdf bsdf geometry light shading color)

file(GLOB_RECURSE headers RELATIVE ${ROOT} ${ROOT}/shade/*.hpp)
list(SORT headers)
if(NOT headers)
    message(FATAL_ERROR "budget.cmake: no headers under ${ROOT}/shade")
endif()

set(work ${CMAKE_CURRENT_BINARY_DIR}/header_budget)
file(MAKE_DIRECTORY ${work})
set(over "")
set(report "")
foreach(header IN LISTS headers)
    string(REGEX REPLACE "^shade/([^/]+)/.*" "\\1" folder "${header}")
    if(header STREQUAL "shade/shade.hpp")
        set(budget 95000)
    elseif(header STREQUAL "shade/brdf/any_brdf.hpp")
        set(budget 75000)
    elseif(folder IN_LIST lean_folders)
        set(budget 60000)
    else()
        set(budget 85000)
    endif()
    string(MAKE_C_IDENTIFIER "${header}" id)
    set(tu ${work}/${id}.cpp)
    file(WRITE ${tu} "#include <${header}>\n")
    execute_process(
        COMMAND ${CXX} -std=c++20 ${EXTRA_FLAGS} -I${ROOT} -E ${tu}
        COMMAND wc -l
        OUTPUT_VARIABLE lines
        ERROR_VARIABLE errors
        RESULT_VARIABLE status)
    string(STRIP "${lines}" lines)
    if(NOT status EQUAL 0 OR NOT lines MATCHES "^[0-9]+$")
        message(FATAL_ERROR "budget.cmake: preprocessing ${header} failed:\n${errors}")
    endif()
    if(lines GREATER budget)
        set(verdict "OVER")
        list(APPEND over "${header} (${lines} > ${budget})")
    else()
        set(verdict "ok")
    endif()
    string(APPEND report "${lines}\t${budget}\t${verdict}\t${header}\n")
endforeach()

message("preprocessed lines\tbudget\t\theader\n${report}")
if(over)
    list(JOIN over "\n  " over_text)
    message(FATAL_ERROR "headers over their preprocessed-line budget:\n  ${over_text}")
endif()
