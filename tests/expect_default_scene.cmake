# Runs clothsim without a parameter file (the default scene, params/default.prm: a sheet
# falls 5 cm onto a ball of radius 0.25 m and drapes over it) and checks what a user must
# see at t = 2 s, from probes.csv:
#   - the centre rests on top of the ball, inside the contact thickness (5 mm) and never in
#     the ball: its fall uz in (-0.050, -0.045) m, and it stays over the top (|ux|, |uy| < 1 cm);
#   - the sheet drapes: the corner has fallen more than 0.4 m (the ball's top is 0.05 m down);
#   - the log names params/default.prm as the scene it ran.
# Usage: cmake -DCLOTHSIM=... -DOUTPUT_DIR=... -P expect_default_scene.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
execute_process(COMMAND "${CLOTHSIM}" --set "Output/Write VTK=false" --set "Output/Progress=off"
                        --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "exit code ${result}: ${err}")
endif()
if(NOT out MATCHES "params/default\\.prm")
  message(FATAL_ERROR "the log does not name params/default.prm")
endif()
file(STRINGS "${OUTPUT_DIR}/probes.csv" rows)
set(final_time)
foreach(row IN LISTS rows)
  string(REPLACE "," ";" fields "${row}")
  list(GET fields 1 time)
  list(GET fields 2 probe)
  if(probe STREQUAL "center" OR probe STREQUAL "corner")
    list(SUBLIST fields 6 3 u)
    set(${probe}_u ${u})
    set(final_time ${time})
  endif()
endforeach()
if(NOT final_time EQUAL 2)
  message(FATAL_ERROR "the last probe row is at t = ${final_time} s, not 2 s")
endif()
list(GET center_u 0 ux)
list(GET center_u 1 uy)
list(GET center_u 2 uz)
list(GET corner_u 2 corner_uz)
message("centre u = (${ux}, ${uy}, ${uz}) m, corner uz = ${corner_uz} m at t = 2 s")
# CMake compares numbers as doubles (if LESS/GREATER).
if(NOT (uz LESS -0.045 AND uz GREATER -0.050))
  message(FATAL_ERROR "the centre is not resting on the ball: uz = ${uz} m, expected "
                      "-0.050 < uz < -0.045 (ball top 5 cm down, contact thickness 5 mm)")
endif()
foreach(c ux uy)
  if(${c} GREATER 0.01 OR ${c} LESS -0.01)
    message(FATAL_ERROR "the centre slid off the top of the ball: ${c} = ${${c}} m")
  endif()
endforeach()
if(NOT corner_uz LESS -0.4)
  message(FATAL_ERROR "the sheet does not drape: the corner fell only ${corner_uz} m")
endif()
