# Runs clothsim on a short scene with its standard output going to a pipe (as to a log
# file) and checks what the log must hold (README, "Running"):
#   - the provenance header: version and git revision, library versions (the BLAS with
#     its kernels: never OpenBLAS' SSE3 'Prescott' fallback on a CPU with AVX2 and FMA,
#     solvers/blas_kernels.h), ranks, command;
#   - progress as plain lines every 5 % of the run (20 of them), never a carriage return;
#   - the closing summary: each probe's final displacement, the energy budget, the path of
#     solution.pvd;
#   - parameters.prm starting with the same provenance as comments.
# Usage: cmake -DCLOTHSIM=... -DOUTPUT_DIR=... -DARGS="a;b" [-DMPIEXEC=... -DRANKS=N]
#              -P expect_run_log.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
set(launcher)
if(RANKS)
  set(launcher ${MPIEXEC} --oversubscribe -np ${RANKS})
endif()
execute_process(COMMAND ${launcher} "${CLOTHSIM}" ${ARGS} --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "exit code ${result}: ${err}")
endif()
function(expect regex what)
  if(NOT out MATCHES "${regex}")
    message(FATAL_ERROR "the log lacks ${what} (${regex})")
  endif()
endfunction()
set(n_ranks 1)
if(RANKS)
  set(n_ranks ${RANKS})
endif()
expect("^clothsim [0-9]+\\.[0-9]+\\.[0-9]+ \\(git [^)]+\\)\n" "the version line first")
expect("\ndeal\\.II 9\\.[0-9.]+, Trilinos [0-9.]+, MUMPS [0-9.]+, gmsh [0-9.]+, [^\n]*MPI"
       "the libraries' versions")
expect("\ndeal\\.II [^\n]*, (OpenBLAS [0-9.]+ \\([A-Za-z0-9]+ kernels[^\n]*\\)|BLAS: not OpenBLAS)\n"
       "the BLAS and its kernels")
file(READ /proc/cpuinfo cpu_info)
if(cpu_info MATCHES "\nflags[^\n]* avx2 [^\n]*" AND CMAKE_MATCH_0 MATCHES " fma ")
  if(out MATCHES "OpenBLAS [0-9.]+ \\(Prescott kernels")
    message(FATAL_ERROR "OpenBLAS runs its SSE3 'Prescott' kernels on a CPU with AVX2 and FMA")
  endif()
endif()
expect("\nrun started 20[0-9][0-9]-[0-9][0-9]-[0-9][0-9] [0-9:]+ UTC on ${n_ranks} MPI rank"
       "the date and rank count")
expect("\ncommand: [^\n]*clothsim [^\n]*--output-dir" "the command line")
string(FIND "${out}" "\r" carriage_return)
if(NOT carriage_return EQUAL -1)
  message(FATAL_ERROR "a carriage return in a log")
endif()
string(REGEX MATCHALL "\n *[0-9]+\\.[0-9]%  step [0-9]+  t = [^\n]* elapsed [^\n]* ETA"
       progress_lines "${out}")
list(LENGTH progress_lines n_lines)
if(NOT n_lines EQUAL 20)
  message(FATAL_ERROR "expected 20 progress lines (every 5 %), found ${n_lines}")
endif()
expect("\n100\\.0%  step" "the progress line at the end")
expect("\n  probes at t = [^\n]* s, displacement \\(m\\): [a-z_]+ \\([^)]+\\), \\|u\\| "
       "the probes' final displacements")
expect("\n  energy \\(J\\) from t = 0 to [^\n]*total [^\n]* -> [^\n]*total \\+ dissipated changed by "
       "the energy budget")
expect("\n  open in ParaView: /[^\n]*/solution\\.pvd\n" "the path of solution.pvd")
file(STRINGS "${OUTPUT_DIR}/parameters.prm" head LIMIT_COUNT 4)
list(GET head 0 first)
list(GET head 3 fourth)
if(NOT first MATCHES "^# clothsim [0-9.]+ \\(git " OR NOT fourth MATCHES "^# command: ")
  message(FATAL_ERROR "parameters.prm does not start with the provenance: ${head}")
endif()
