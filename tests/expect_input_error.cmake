# Runs clothsim on bad input and checks what a user must see:
#   exit code 1, exactly one line on stderr naming the file (FILE_REGEX) and matching
#   MESSAGE_REGEX, and no output directory created.
# Options: -DMPIEXEC=... -DRANKS=N runs it on N ranks (mpirun's own report of the exit
# code is removed from stderr first; the error must come once, from rank 0; a hang is
# caught by the test's TIMEOUT); -DABSENT=path: a path that must not exist afterwards
# (e.g. a parent directory, or a .msh generated from a bad .geo, that the run must not
# leave behind).
# Usage: cmake -DCLOTHSIM=... -DOUTPUT_DIR=... -DFILE_REGEX=... -DMESSAGE_REGEX=...
#              -DARGS="a;b;c" [-DABSENT=...] -P expect_input_error.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
if(ABSENT)
  file(REMOVE_RECURSE "${ABSENT}")
endif()
set(launcher)
if(RANKS)
  set(launcher ${MPIEXEC} --oversubscribe -np ${RANKS})
endif()
execute_process(COMMAND ${launcher} "${CLOTHSIM}" ${ARGS} --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(RANKS)
  # mpirun's report: a block between lines of dashes.
  string(REGEX REPLACE "-----+\n([^\n]*\n)*-----+\n?" "" err "${err}")
  string(REGEX REPLACE "-----+\n([^\n]*\n)*-----+\n?" "" err "${err}")
endif()
string(STRIP "${err}" err)
message("exit code ${result}; stderr: ${err}")
if(NOT result EQUAL 1)
  message(FATAL_ERROR "expected exit code 1, got ${result}")
endif()
string(FIND "${err}" "\n" newline)
if(NOT newline EQUAL -1)
  message(FATAL_ERROR "expected a one-line error message")
endif()
if(NOT err MATCHES "^clothsim: error: ")
  message(FATAL_ERROR "expected 'clothsim: error: ...'")
endif()
if(NOT err MATCHES "${FILE_REGEX}")
  message(FATAL_ERROR "the message does not name the file (${FILE_REGEX})")
endif()
if(NOT err MATCHES "${MESSAGE_REGEX}")
  message(FATAL_ERROR "the message does not match ${MESSAGE_REGEX}")
endif()
if(EXISTS "${OUTPUT_DIR}")
  message(FATAL_ERROR "an output directory was created: ${OUTPUT_DIR}")
endif()
if(ABSENT AND EXISTS "${ABSENT}")
  message(FATAL_ERROR "${ABSENT} was left behind")
endif()
