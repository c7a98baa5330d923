# SPDX-License-Identifier: MIT
# The add_tool test's checks, run as `cmake -DTOOL=<tool> -DWORK=<dir> -P run.cmake`:
# the help lists the researcher's linkage and its option, the option parses,
# a bad value is the usual usage error (exit 2), `cluster --verify` runs the
# linkage on a simulated stream (continuous partition = batch partition), and
# `evaluate` and `evaluate --objects` run with it.
function(run expected_code)
  execute_process(COMMAND "${TOOL}" ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "${TOOL} ${ARGN}: exit ${code}, expected ${expected_code}\n${out}\n${err}")
  endif()
  set(out "${out}${err}" PARENT_SCOPE)
endfunction()

run(0 cluster --help)
foreach(expected "--linkage angular|euclidean|range-adaptive|intensity-gated" "--intensity-gap I (default 20)"
                 "intensity-gated: largest intensity difference of a link")
  string(FIND "${out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "cluster --help lacks '${expected}':\n${out}")
  endif()
endforeach()
run(2 cluster x.csv --linkage intensity-gated --intensity-gap -3)
string(FIND "${out}" "--intensity-gap: expected a positive number, got '-3'" at)
if(at EQUAL -1)
  message(FATAL_ERROR "unexpected message: ${out}")
endif()
run(0 simulate --sensor mid360 --scene office --seconds 0.3 --out "${WORK}/office.csv")
run(0 cluster "${WORK}/office.csv" --linkage intensity-gated --intensity-gap 5 --distance 0.4 --verify --quiet
    --report "${WORK}/report.json")
run(0 evaluate --duration 0.4 --linkage intensity-gated --intensity-gap 5 --method carc --quiet --json "${WORK}/e.json")
file(READ "${WORK}/e.json" json)
string(FIND "${json}" "\"intensity_gap\": 5" at)
if(at EQUAL -1)
  message(FATAL_ERROR "evaluate --json lacks the linkage's option:\n${json}")
endif()
# `evaluate --objects` with the researcher's linkage in the objects preset's
# linkage slot: its option parsed, the partition verified against the batch,
# the JSON naming the linkage and its values.
run(0 evaluate --objects --linkage intensity-gated --intensity-gap 7 --duration 0.75 --window-time 0.25
    --method objects --verify --quiet --json "${WORK}/objects.json")
file(READ "${WORK}/objects.json" json)
foreach(expected "\"linkage\": \"intensity-gated\"" "\"intensity_gap\": 7")
  string(FIND "${json}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "evaluate --objects --json lacks '${expected}':\n${json}")
  endif()
endforeach()
run(2 evaluate --objects --linkage intensity-gated --intensity-gap 0)
string(FIND "${out}" "--intensity-gap: expected a positive number, got '0'" at)
if(at EQUAL -1)
  message(FATAL_ERROR "unexpected message: ${out}")
endif()
