# SPDX-License-Identifier: MIT
# streamclust_add_python_module: the Python package `streamclust`
# (docs/python.md) built with a researcher's own policies beside the stock
# ones: each is selectable by its registered name and its options are
# keywords (docs/python.md, "Your own policies in Python"):
#
#   find_package(streamclust REQUIRED COMPONENTS io live)
#   streamclust_add_python_module(my_streamclust_python
#     POLICIES ${CMAKE_CURRENT_SOURCE_DIR}/intensity_gated.hpp   # as streamclust_add_tool
#     LINKAGES my::IntensityGatedLinkage)
#   # PYTHONPATH=<build>/my_streamclust_python python3 -c 'import streamclust;
#   #   streamclust.Clusterer("carc-mid360", linkage="intensity-gated", intensity_gap=20)'
#
# Arguments:
#   POLICIES, LINKAGES, INDEXES, CONNECTIVITIES, PROJECTIONS   as streamclust_add_tool
#   OUTPUT_DIRECTORY   where the package directory `streamclust` is assembled
#                      (default <current binary dir>/<target>): put it on PYTHONPATH
#
# Needs the Python 3 interpreter and development files and pybind11 >= 2.6
# (CONFIG); the function stops with a message naming what is missing and
# its Debian package. The module is compiled in the calling project from the
# installed sources (<datadir>/streamclust/python, and the tool's in
# <datadir>/streamclust/tool: the module parses keywords with the tool's
# parser): the extension `_streamclust` (target <target>) with one generated
# translation unit per linkage (every projection's engines of it), and the
# package's Python files copied beside it. The stock module is this function
# with no policies of its own (python/CMakeLists.txt). Each added linkage
# costs one such unit, as in the tool.

include("${CMAKE_CURRENT_LIST_DIR}/StreamclustAddTool.cmake")  # the shared policies header

if(NOT DEFINED STREAMCLUST_PYTHON_SOURCE_DIR)
  # Installed: <prefix>/<datadir>/cmake/streamclust/ -> <prefix>/<datadir>/streamclust/python
  get_filename_component(STREAMCLUST_PYTHON_SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/../../streamclust/python" ABSOLUTE)
endif()

function(streamclust_add_python_module target)
  cmake_parse_arguments(ARG "" "OUTPUT_DIRECTORY" "POLICIES;LINKAGES;INDEXES;CONNECTIVITIES;PROJECTIONS" ${ARGN})
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "streamclust_add_python_module(${target}): unknown arguments ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TARGET streamclust::io OR NOT TARGET streamclust::live)
    message(FATAL_ERROR "streamclust_add_python_module(${target}): the module reads recordings and live "
                        "sensors; find the package with find_package(streamclust REQUIRED COMPONENTS io live)")
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
  find_package(pybind11 2.6 CONFIG QUIET)
  set(_missing "")
  if(NOT Python3_Interpreter_FOUND)
    list(APPEND _missing "the Python 3 interpreter (Debian package python3)")
  endif()
  if(NOT Python3_Development.Module_FOUND)
    list(APPEND _missing "the Python 3 development files (Debian package python3-dev)")
  endif()
  if(NOT pybind11_FOUND)
    list(APPEND _missing "pybind11 >= 2.6 with its CMake package (Debian package pybind11-dev)")
  endif()
  if(_missing)
    list(JOIN _missing ", " _missing)
    message(FATAL_ERROR "streamclust_add_python_module(${target}): needs ${_missing}: not found")
  endif()
  find_package(nlohmann_json 3 REQUIRED)  # the tool's JSON helpers, included by the module
  if(NOT ARG_OUTPUT_DIRECTORY)
    set(ARG_OUTPUT_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}/${target}")
  endif()
  set(_dir "${CMAKE_CURRENT_BINARY_DIR}/${target}_generated")
  set(_src "${STREAMCLUST_PYTHON_SOURCE_DIR}")

  _streamclust_policies_header("streamclust_add_python_module(${target})" "${_dir}/tool_policies.hpp"
    POLICIES ${ARG_POLICIES} PROJECTIONS ${ARG_PROJECTIONS} INDEXES ${ARG_INDEXES} LINKAGES ${ARG_LINKAGES}
    CONNECTIVITIES ${ARG_CONNECTIVITIES})

  # One translation unit per linkage, for every projection (every index,
  # window, mode and connectivity of the registry: python/src/engine_clusterer.hpp).
  set(_engines "#include \"engine_clusterer.hpp\"\nSTREAMCLUST_INSTANTIATE_PYTHON_ENGINE(@P@, @L@);\n")
  _streamclust_units("streamclust_add_python_module(${target})" "${_dir}" engines _units
    PROJECTIONS ${ARG_PROJECTIONS} LINKAGES ${ARG_LINKAGES} BODY _engines)

  set(_package "${ARG_OUTPUT_DIRECTORY}/streamclust")
  # NO_EXTRAS: without pybind11's link-time optimisation, whose serial link
  # of every unit cost about a minute; the engine's hot loops live inside
  # single units, where LTO has nothing to inline across. Stripped as
  # pybind11 would (optimised builds).
  pybind11_add_module(${target} MODULE NO_EXTRAS "${_src}/src/module.cpp" "${_src}/src/erased_clusterer.cpp" ${_units})
  string(TOUPPER "${CMAKE_BUILD_TYPE}" _build_type)
  if(NOT MSVC AND NOT _build_type MATCHES "DEBUG|RELWITHDEBINFO")
    pybind11_strip(${target})
  endif()
  target_include_directories(${target} PRIVATE "${_src}/src" "${STREAMCLUST_TOOL_SOURCE_DIR}")
  if(_STREAMCLUST_OWN_POLICIES)  # without policies of its own, the stock registry (cli/tool_policies.hpp)
    target_compile_definitions(${target} PRIVATE "STREAMCLUST_TOOL_POLICIES_HEADER=\"${_dir}/tool_policies.hpp\"")
  endif()
  target_link_libraries(${target} PRIVATE streamclust::streamclust streamclust::io streamclust::live
                        nlohmann_json::nlohmann_json)
  target_compile_features(${target} PRIVATE cxx_std_17)
  set_target_properties(${target} PROPERTIES OUTPUT_NAME _streamclust LIBRARY_OUTPUT_DIRECTORY "${_package}")

  # The pure-Python files, copied beside the extension (re-copied when they change).
  file(GLOB _py_files CONFIGURE_DEPENDS "${_src}/streamclust/*.py")
  foreach(_f IN LISTS _py_files)
    get_filename_component(_name "${_f}" NAME)
    configure_file("${_f}" "${_package}/${_name}" COPYONLY)
  endforeach()
endfunction()
