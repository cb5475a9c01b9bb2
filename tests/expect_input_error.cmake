# Runs clothsim on bad input and checks what a user must see:
#   exit code 1, exactly one line on stderr naming the file (FILE_REGEX) and matching
#   MESSAGE_REGEX, and no output directory created; with -DABSENT_FILE=..., that file
#   (e.g. a .msh generated from a bad .geo) does not exist afterwards either.
# Usage: cmake -DCLOTHSIM=... -DOUTPUT_DIR=... -DFILE_REGEX=... -DMESSAGE_REGEX=...
#              -DARGS="a;b;c" [-DABSENT_FILE=...] -P expect_input_error.cmake
file(REMOVE_RECURSE "${OUTPUT_DIR}")
if(ABSENT_FILE)
  file(REMOVE "${ABSENT_FILE}")
endif()
execute_process(COMMAND "${CLOTHSIM}" ${ARGS} --output-dir "${OUTPUT_DIR}"
                RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
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
if(ABSENT_FILE AND EXISTS "${ABSENT_FILE}")
  message(FATAL_ERROR "a file was left behind: ${ABSENT_FILE}")
endif()
