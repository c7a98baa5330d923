# SPDX-License-Identifier: MIT
# Helpers of the package test scripts run with `cmake -P`
# (consumer_test.cmake, extending_test.cmake).

# require_defined(<script> <variable>...): stops, naming the first -D<variable>=... not given.
function(require_defined script)
  foreach(_var IN LISTS ARGN)
    if(NOT DEFINED ${_var})
      message(FATAL_ERROR "${script}: -D${_var}=... is required")
    endif()
  endforeach()
endfunction()

# run_step(<what> <command>...): runs the command; a non-zero exit stops with
# the step, the command line and its output; else prints "ok: <what>" and
# leaves the output (stdout and stderr) in `out`.
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
  if(NOT _rc EQUAL 0)
    list(JOIN ARGN " " _cmd)
    message(FATAL_ERROR "FAILED: ${what} (exit ${_rc})\ncommand: ${_cmd}\n${_out}")
  endif()
  message(STATUS "ok: ${what}")
  set(out "${_out}" PARENT_SCOPE)
endfunction()
