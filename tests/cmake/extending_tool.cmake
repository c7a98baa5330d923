# SPDX-License-Identifier: MIT
# The checks of examples/extending's tool (`upright_streamclust`, built by
# streamclust_add_tool with UprightLinkage), included by extending_test.cmake
# with TOOL (the executable) and WORK (a scratch directory) set: the help lists
# the linkage and its options, a bad value is the usual usage error (exit 2),
# `cluster --verify` runs the linkage on a simulated stream (continuous
# partition = batch partition), `evaluate` selects it by name and reports its
# options, `evaluate --objects` swaps it into the objects preset.
function(run expected_code)
  execute_process(COMMAND "${TOOL}" ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT code EQUAL expected_code)
    message(FATAL_ERROR "${TOOL} ${ARGN}: exit ${code}, expected ${expected_code}\n${out}\n${err}")
  endif()
  set(out "${out}${err}" PARENT_SCOPE)
endfunction()

function(expect_in text what)
  foreach(expected IN LISTS ARGN)
    string(FIND "${text}" "${expected}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${what} lacks '${expected}':\n${text}")
    endif()
  endforeach()
endfunction()

run(0 cluster --help)
expect_in("${out}" "cluster --help" "--linkage angular|euclidean|range-adaptive|scan-adaptive|upright" "--stretch S (default 2)"
          "upright: vertical reach over horizontal, in [1, 10]")
run(2 cluster x.csv --linkage upright --stretch -3)
expect_in("${out}" "the message" "--stretch: expected a positive number, got '-3'")
run(0 simulate --sensor mid360 --scene office --seconds 0.3 --out "${WORK}/office.csv")
run(2 cluster "${WORK}/office.csv" --linkage upright --stretch 0.5 --quiet)
expect_in("${out}" "the message" "UprightLinkage: stretch = 0.500000 is invalid" "allowed: [1, 10]")
run(0 cluster "${WORK}/office.csv" --linkage upright --stretch 3 --min-distance 0.25 --verify --quiet
    --report "${WORK}/report.json")
run(0 evaluate --duration 0.4 --linkage upright --stretch 3 --method carc --quiet --json "${WORK}/e.json")
file(READ "${WORK}/e.json" json)
expect_in("${json}" "evaluate --json" "\"stretch\": 3")
# The objects preset with the linkage swapped in: its parameters reach it (a
# bad one is its usage error), --verify exits 3 unless every objects
# partition equals the batch partition of its object points, and the JSON
# names the linkage and its values.
run(2 evaluate --objects --linkage upright --stretch 0.5 --duration 0.4 --window-time 0.2 --method objects --quiet)
expect_in("${out}" "evaluate --objects's message" "UprightLinkage: stretch = 0.500000 is invalid" "allowed: [1, 10]")
run(0 evaluate --objects --linkage upright --stretch 3 --duration 0.4 --window-time 0.2 --method objects --verify
    --quiet --json "${WORK}/objects.json")
file(READ "${WORK}/objects.json" json)
expect_in("${json}" "evaluate --objects --json" "\"mismatches\": []" "\"linkage\": \"upright\"" "\"stretch\": 3")
