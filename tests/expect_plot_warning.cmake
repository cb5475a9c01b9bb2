# Runs a clothsim study with no gnuplot on PATH and checks that the study still succeeds:
# exit code 0, the CSV (CSV, relative to OUTPUT_DIR) written, the plot (PLOT) not drawn
# but its data and script beside it, and a warning on stderr that names the plot and the
# Debian package.
# Usage: cmake -DCLOTHSIM=... -DOUTPUT_DIR=... -DCSV=pareto.csv -DPLOT=pareto
#              -DARGS="a;b;c" -P expect_plot_warning.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
# A PATH without gnuplot: a directory with Open MPI's orted and ssh only (a singleton MPI
# process starts orted, and Open MPI wants an ssh agent on PATH).
set(bin "${OUTPUT_DIR}-bin")
file(REMOVE_RECURSE "${bin}")
file(MAKE_DIRECTORY "${bin}")
foreach(name orted ssh)
  find_program(program_${name} ${name} REQUIRED)
  file(CREATE_LINK "${program_${name}}" "${bin}/${name}" SYMBOLIC)
endforeach()
set(ENV{PATH} "${bin}")
execute_process(COMMAND "${CLOTHSIM}" ${ARGS} --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
string(STRIP "${err}" err)
message("exit code ${result}; stderr: ${err}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "expected exit code 0, got ${result}")
endif()
if(NOT EXISTS "${OUTPUT_DIR}/${CSV}")
  message(FATAL_ERROR "${CSV} not written")
endif()
foreach(file ${PLOT}.dat ${PLOT}.gp)
  if(NOT EXISTS "${OUTPUT_DIR}/${file}")
    message(FATAL_ERROR "${file} not written")
  endif()
endforeach()
if(EXISTS "${OUTPUT_DIR}/${PLOT}.png" OR EXISTS "${OUTPUT_DIR}/${PLOT}.png.partial"
   OR EXISTS "${OUTPUT_DIR}/${PLOT}.gnuplot.log")
  message(FATAL_ERROR "${PLOT}.png, its temporary file or a gnuplot log left without gnuplot")
endif()
if(NOT err MATCHES "warning: [^\n]*${PLOT}\\.png not drawn: gnuplot not found on PATH \\(Debian package gnuplot-nox\\)")
  message(FATAL_ERROR "no warning naming ${PLOT}.png and gnuplot-nox on stderr")
endif()
message("PASSED")
