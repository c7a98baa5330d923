# SPDX-License-Identifier: MIT
# streamclust_add_benchmark(<name> SOURCES <file>... [LIBRARIES <target>...])
#
# A Google Benchmark program built with the benchmark kit
# (<streamclust/benchmarking/...>, docs/performance.md): the executable
# <name> from SOURCES, linked to streamclust::benchmarking and LIBRARIES, and
# a CTest smoke run of it (`<name> --benchmark_min_time=0.01`, label bench;
# with STREAMCLUST_BENCHMARK_MAIN() that simulates short streams). Loaded by
# find_package(streamclust COMPONENTS benchmarking).
function(streamclust_add_benchmark name)
  cmake_parse_arguments(PARSE_ARGV 1 _arg "" "" "SOURCES;LIBRARIES")
  if(NOT _arg_SOURCES)
    message(FATAL_ERROR "streamclust_add_benchmark(${name}): SOURCES is required")
  endif()
  if(_arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "streamclust_add_benchmark(${name}): unknown arguments ${_arg_UNPARSED_ARGUMENTS}")
  endif()
  add_executable(${name} ${_arg_SOURCES})
  target_link_libraries(${name} PRIVATE streamclust::benchmarking ${_arg_LIBRARIES})
  add_test(NAME ${name} COMMAND ${name} --benchmark_min_time=0.01)
  set_tests_properties(${name} PROPERTIES LABELS bench TIMEOUT 300)
endfunction()
