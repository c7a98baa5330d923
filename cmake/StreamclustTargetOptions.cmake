# SPDX-License-Identifier: MIT
#
# Flags for the project's own targets (tests, examples, benchmarks, header
# checks). Never applied to the INTERFACE library `streamclust`: a consumer's
# flags are the consumer's business.
include_guard(GLOBAL)

# Warnings as errors. Dependencies (Eigen, Boost, range-v3, doctest, benchmark)
# arrive through imported targets or the compiler's own search path, so their
# headers are system headers and these flags do not fire on them; the
# streamclust headers themselves are NOT system in the build tree, so every
# warning in them does fire here.
function(streamclust_set_warnings target)
  if(MSVC)
    target_compile_options(${target} PRIVATE /W4 /WX /permissive-)
  else()
    target_compile_options(${target} PRIVATE
      -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Werror)
  endif()
endfunction()

# -DSTREAMCLUST_SANITIZE=ON: AddressSanitizer + UndefinedBehaviorSanitizer,
# aborting on the first report. A Debug build is optimised at -O1 (asserts
# stay on): at -O0 every Eigen expression-template node is a function call,
# and the simulation-heavy tests ran ten times slower than at -O1
# (tests/test_sim_mounts.cpp: 171 s against 18 s). Its debug information is
# line tables only: a report's stack keeps its files and lines, and the
# tool's heaviest translation unit compiles in 10 % less time with half the
# object size.
function(streamclust_set_sanitizers target)
  if(STREAMCLUST_SANITIZE AND NOT MSVC)
    set(_flags -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
    if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
      set(_lines -gline-tables-only)
    else()
      set(_lines -g1)
    endif()
    target_compile_options(${target} PRIVATE ${_flags} $<$<CONFIG:Debug>:-O1> $<$<CONFIG:Debug>:${_lines}>)
    get_target_property(_type ${target} TYPE)
    if(NOT _type STREQUAL "OBJECT_LIBRARY")
      target_link_options(${target} PRIVATE ${_flags})
    endif()
  endif()
endfunction()

# Everything a project target gets: warnings, sanitizers, no compiler extensions.
function(streamclust_project_target target)
  streamclust_set_warnings(${target})
  streamclust_set_sanitizers(${target})
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
endfunction()

# Environment for tests of a sanitized build: any report fails the test, with a
# stack trace.
set(STREAMCLUST_SANITIZER_TEST_ENV
    "ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
    "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
