# A run without a launcher keeps OpenMPI's session directory to itself (src/app/mpi_session.h).
# OpenMPI's shared place for it, ${TMPDIR}/ompi.<host>.<uid>, is made unusable (a plain file
# there): a run that used it would fail in MPI_Init, as one did in CI when another run
# removed it halfway. The run must succeed and leave TMPDIR as it found it.
# Usage: cmake -DCLOTHSIM=... -DSCRATCH=dir -P expect_private_session_dir.cmake
file(REMOVE_RECURSE "${SCRATCH}")
file(MAKE_DIRECTORY "${SCRATCH}")
cmake_host_system_information(RESULT host QUERY HOSTNAME)
string(REGEX REPLACE "\\..*" "" host "${host}") # OpenMPI drops the domain
execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
set(shared "${SCRATCH}/ompi.${host}.${uid}")
file(WRITE "${shared}" "")
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=OMPI_MCA_orte_tmpdir_base
                        "TMPDIR=${SCRATCH}" "${CLOTHSIM}" --version
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("exit code ${result}; stderr: ${err}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "clothsim --version failed with ${shared} in the way")
endif()
file(GLOB left RELATIVE "${SCRATCH}" "${SCRATCH}/*")
if(NOT left STREQUAL "ompi.${host}.${uid}")
  message(FATAL_ERROR "TMPDIR holds '${left}' after the run, expected only the file put there")
endif()
