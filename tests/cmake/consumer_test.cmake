# SPDX-License-Identifier: MIT
#
# cmake -DBUILD_DIR=<streamclust build> -DCONSUMER_SOURCE_DIR=<tests/consumer>
#       -DWORK_DIR=<scratch dir> -DCXX_COMPILER=<c++> [-DGENERATOR=<gen>]
#       [-DBUILD_TYPE=<cfg>] [-DEXPECTED_VERSION=<x.y.z>] -P consumer_test.cmake
#
# 1. cmake --install BUILD_DIR --prefix WORK_DIR/prefix --component streamclust_development
#    (the library alone: the command-line tool need not be built)
# 2. check the installed tree (merged headers, package files, one targets
#    file per package component)
# 3. configure tests/consumer with CMAKE_PREFIX_PATH=WORK_DIR/prefix and the
#    components io, sim, eval, testing (benchmarking if found), build, run it
# 4. a machine without the codecs: every codec package disabled
#    (CMAKE_DISABLE_FIND_PACKAGE_<pkg>=ON): the engine alone configures,
#    builds and runs; asking for io fails, naming each missing Debian package
# 5. the build tree as a package: the consumer configures against BUILD_DIR

cmake_minimum_required(VERSION 3.18)

include("${CMAKE_CURRENT_LIST_DIR}/script_steps.cmake")
require_defined(consumer_test.cmake BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR CXX_COMPILER)
if(NOT BUILD_TYPE)
  set(BUILD_TYPE Release)
endif()

set(_prefix "${WORK_DIR}/prefix")
set(_build "${WORK_DIR}/build")
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

run_step("install into ${_prefix}"
         "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${_prefix}" --config "${BUILD_TYPE}"
         --component streamclust_development)

# The installed tree: both source include roots merged under include/streamclust,
# package config + version + targets files, the four targets exported.
file(GLOB _config "${_prefix}/*/cmake/streamclust/streamclustConfig.cmake"
                  "${_prefix}/*/*/cmake/streamclust/streamclustConfig.cmake")
if(NOT _config)
  message(FATAL_ERROR "FAILED: no streamclustConfig.cmake under ${_prefix}")
endif()
foreach(_f streamclustConfigVersion.cmake streamclustTargets.cmake Findlz4.cmake StreamclustBenchmark.cmake)
  get_filename_component(_dir "${_config}" DIRECTORY)
  if(NOT EXISTS "${_dir}/${_f}")
    message(FATAL_ERROR "FAILED: ${_f} missing next to ${_config}")
  endif()
endforeach()
get_filename_component(_src_root "${CONSUMER_SOURCE_DIR}/../.." ABSOLUTE)
file(GLOB_RECURSE _src_headers RELATIVE "${_src_root}/include" "${_src_root}/include/streamclust/*.hpp")
file(GLOB_RECURSE _pol_headers RELATIVE "${_src_root}/policies" "${_src_root}/policies/streamclust/*.hpp")
foreach(_h IN LISTS _src_headers _pol_headers)
  if(NOT EXISTS "${_prefix}/include/${_h}")
    message(FATAL_ERROR "FAILED: header <${_h}> was not installed to ${_prefix}/include")
  endif()
endforeach()
# The engine in streamclustTargets.cmake, each component in its own file.
foreach(_t streamclust io eval sim testing benchmarking)
  set(_file "${_dir}/streamclust_${_t}Targets.cmake")
  if(_t STREQUAL "streamclust")
    set(_file "${_dir}/streamclustTargets.cmake")
  endif()
  if(NOT EXISTS "${_file}")
    message(FATAL_ERROR "FAILED: ${_file} missing")
  endif()
  file(READ "${_file}" _targets_file)
  string(FIND "${_targets_file}" "add_library(streamclust::${_t} INTERFACE IMPORTED)" _pos)
  if(_pos EQUAL -1)
    message(FATAL_ERROR "FAILED: streamclust::${_t} is not exported in ${_file}")
  endif()
endforeach()
# The umbrella header and the presets are framework headers: a policy never
# includes an engine.
foreach(_h streamclust/streamclust.hpp streamclust/presets.hpp)
  if(NOT EXISTS "${_src_root}/include/${_h}")
    message(FATAL_ERROR "FAILED: <${_h}> is not under include/")
  endif()
endforeach()
list(LENGTH _src_headers _n_src)
list(LENGTH _pol_headers _n_pol)
message(STATUS "ok: installed ${_n_src} framework + ${_n_pol} policy headers under ${_prefix}/include/streamclust")

set(_gen_args)
if(GENERATOR)
  set(_gen_args -G "${GENERATOR}")
endif()
set(_version_args)
if(EXPECTED_VERSION)
  set(_version_args "-DSTREAMCLUST_EXPECTED_VERSION=${EXPECTED_VERSION}")
endif()
set(_consumer_args ${_gen_args}
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
    "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}"
    "-DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF"
    ${_version_args})

# run_consumer(<what> <build dir> [configure arguments]): configures, builds
# and runs tests/consumer against the prefix.
function(run_consumer what build)
  run_step("configure the consumer (${what})"
           "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${build}" ${_consumer_args}
           "-DCMAKE_PREFIX_PATH=${_prefix}" "-DSTREAMCLUST_EXPECTED_PREFIX=${_prefix}" ${ARGN})
  run_step("build the consumer (${what})" "${CMAKE_COMMAND}" --build "${build}" --config "${BUILD_TYPE}")
  set(_exe "${build}/consumer")
  if(NOT EXISTS "${_exe}")
    file(GLOB_RECURSE _exe "${build}/consumer" "${build}/consumer.exe")
  endif()
  run_step("run the consumer (${what})" "${_exe}")
endfunction()

run_consumer("components io sim eval testing" "${_build}")

# A machine without the codec packages. Findlz4.cmake is the package's own
# module: disabling lz4 must reach it like the others.
set(_codecs lz4 zstd BZip2 SQLite3 ZLIB)
set(_debian liblz4-dev libzstd-dev libbz2-dev libsqlite3-dev zlib1g-dev)
set(_no_codecs)
foreach(_pkg IN LISTS _codecs)
  list(APPEND _no_codecs "-DCMAKE_DISABLE_FIND_PACKAGE_${_pkg}=ON")
endforeach()
run_consumer("engine alone, no codec package" "${_build}-engine" -DCONSUMER_ENGINE_ONLY=ON ${_no_codecs})

execute_process(COMMAND "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${_build}-io" ${_consumer_args}
                        "-DCMAKE_PREFIX_PATH=${_prefix}" -DCONSUMER_ENGINE_ONLY=ON -DCONSUMER_ASK_IO=ON ${_no_codecs}
                RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
if(_rc EQUAL 0)
  message(FATAL_ERROR "FAILED: COMPONENTS io configured without any codec package\n${_out}")
endif()
string(REGEX REPLACE "[ \t\r\n]+" " " _flat "${_out}")  # CMake wraps long messages
foreach(_pkg _deb IN ZIP_LISTS _codecs _debian)
  string(FIND "${_flat}" "${_pkg} (Debian package ${_deb})" _pos)
  if(_pos EQUAL -1)
    message(FATAL_ERROR "FAILED: the error of COMPONENTS io without codecs does not name ${_pkg} (${_deb}):\n${_out}")
  endif()
endforeach()
message(STATUS "ok: COMPONENTS io without codecs fails naming the five Debian packages")

# The build tree is a package too (its export files): configure only.
run_step("configure the consumer against the build tree"
         "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE_DIR}" -B "${_build}-tree" ${_consumer_args}
         "-DCMAKE_PREFIX_PATH=${BUILD_DIR}")
