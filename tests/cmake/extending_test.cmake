# SPDX-License-Identifier: MIT
#
# cmake -DBUILD_DIR=<streamclust build> -DEXAMPLE_DIR=<examples/extending> -DWORK_DIR=<scratch dir>
#       -DCXX_COMPILER=<c++> [-DCXX_COMPILER_LAUNCHER=<ccache>] [-DGENERATOR=<gen>] -P extending_test.cmake
#
# The out-of-tree example as its user builds it, against an installed package
# and nothing else:
# 1. cmake --install BUILD_DIR --prefix WORK_DIR/prefix --component streamclust_development
# 2. configure EXAMPLE_DIR with CMAKE_PREFIX_PATH=WORK_DIR/prefix alone (no
#    package registry) and check that streamclust was found there; build it
#    unoptimised (its tool compiles the whole command-line tool)
# 3. run its own CTest: the kit's laws and exactness, the benchmark's smoke run
# 4. run its tool (extending_tool.cmake)

cmake_minimum_required(VERSION 3.20)

include("${CMAKE_CURRENT_LIST_DIR}/script_steps.cmake")
require_defined(extending_test.cmake BUILD_DIR EXAMPLE_DIR WORK_DIR CXX_COMPILER)

set(_prefix "${WORK_DIR}/prefix")
set(_build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${_prefix}" "${_build}")
file(MAKE_DIRECTORY "${WORK_DIR}")

run_step("install into ${_prefix}"
         "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${_prefix}" --component streamclust_development)

set(_options "-DCMAKE_PREFIX_PATH=${_prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF "-DCMAKE_BUILD_TYPE="
             "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}")
if(CXX_COMPILER_LAUNCHER)
  list(APPEND _options "-DCMAKE_CXX_COMPILER_LAUNCHER=${CXX_COMPILER_LAUNCHER}")
endif()
if(GENERATOR)
  list(APPEND _options -G "${GENERATOR}")
endif()
run_step("configure ${EXAMPLE_DIR}" "${CMAKE_COMMAND}" -S "${EXAMPLE_DIR}" -B "${_build}" ${_options})
file(STRINGS "${_build}/CMakeCache.txt" _found REGEX "^streamclust_DIR:")
string(REGEX REPLACE "^[^=]*=" "" _found "${_found}")
file(REAL_PATH "${_prefix}" _real_prefix)
file(REAL_PATH "${_found}" _real_found)
string(FIND "${_real_found}" "${_real_prefix}/" _at)
if(NOT _at EQUAL 0)
  message(FATAL_ERROR "FAILED: the example found streamclust in '${_found}', not under ${_prefix}")
endif()

# Its tool is a dozen heavy translation units: as many jobs as cores.
cmake_host_system_information(RESULT _cores QUERY NUMBER_OF_LOGICAL_CORES)
run_step("build" "${CMAKE_COMMAND}" --build "${_build}" --parallel ${_cores})
run_step("the example's tests" "${CMAKE_CTEST_COMMAND}" --test-dir "${_build}" --output-on-failure)
foreach(_test test_upright bench_upright)
  string(REGEX MATCH "[0-9]+/[0-9]+ Test +#[0-9]+: ${_test} [.]+ +Passed" _passed "${out}")
  if(NOT _passed)
    message(FATAL_ERROR "FAILED: the example's ctest did not pass ${_test}:\n${out}")
  endif()
endforeach()

set(TOOL "${_build}/upright_streamclust")
set(WORK "${WORK_DIR}")
include("${CMAKE_CURRENT_LIST_DIR}/extending_tool.cmake")
message(STATUS "ok: the tool's checks")
