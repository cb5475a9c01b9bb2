# Runs clothsim on a scene that cannot be solved (Newton allowed one iteration, no step halving)
# and checks that the run stops with exit code 2 and a message, and that what was written before
# the failure is intact: parameters, the first frame in solution.pvd, the t = 0 rows of the CSVs.
# -DMESSAGE_REGEX=...: what the message must say about the failure (default: where Newton
# failed).
# Usage: cmake -DCLOTHSIM=... -DOUTPUT_DIR=... -DARGS="a;b" -P expect_simulation_failure.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
execute_process(COMMAND "${CLOTHSIM}" ${ARGS} --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit code ${result}; stderr: ${err}")
if(NOT result EQUAL 2)
  message(FATAL_ERROR "expected exit code 2, got ${result}")
endif()
if(NOT MESSAGE_REGEX)
  set(MESSAGE_REGEX "Newton failed at t = .*")
endif()
if(NOT err MATCHES "simulation failed: ${MESSAGE_REGEX} output up to t = 0(\\.0+)? is kept")
  message(FATAL_ERROR "expected a message saying why the run failed (${MESSAGE_REGEX}) and what is kept")
endif()
foreach(f original.prm parameters.prm solution.pvd solution-00000.vtu probes.csv statistics.csv)
  if(NOT EXISTS "${OUTPUT_DIR}/${f}")
    message(FATAL_ERROR "${f} is missing after the failed run")
  endif()
endforeach()
file(READ "${OUTPUT_DIR}/solution.pvd" pvd)
if(NOT pvd MATCHES "solution-00000.vtu" OR NOT pvd MATCHES "</VTKFile>")
  message(FATAL_ERROR "solution.pvd does not list the first frame as a complete file")
endif()
file(STRINGS "${OUTPUT_DIR}/probes.csv" probe_lines)
list(LENGTH probe_lines n_probe_lines)
if(NOT n_probe_lines EQUAL 4)
  message(FATAL_ERROR "probes.csv should hold the header and the 3 probes at t = 0, has ${n_probe_lines} lines")
endif()
