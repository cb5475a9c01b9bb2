# Writes OUTPUT, a C++ header defining CLOTHSIM_GIT_REVISION, the git revision of SOURCE_DIR
# ("unknown" outside a git checkout). Run at every build by the clothsim_revision target
# (CMakeLists.txt); the header is rewritten only when the revision changes, so that only
# src/io/provenance.cc is compiled again.
execute_process(COMMAND git -C "${SOURCE_DIR}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET RESULT_VARIABLE status)
if(NOT status EQUAL 0 OR revision STREQUAL "")
  set(revision "unknown")
endif()
set(text "#define CLOTHSIM_GIT_REVISION \"${revision}\"\n")
set(old "")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUTPUT}" "${text}")
endif()
