# Checks that a column of a CSV file a run wrote (e.g. statistics.csv) rose during the run:
# its value in the first row is at most ABOVE, in the last row above it.
# Usage: cmake -DFILE=... -DCOLUMN=name -DABOVE=number -P expect_column_rises.cmake
file(STRINGS "${FILE}" rows)
list(LENGTH rows n_rows)
if(n_rows LESS 3)
  message(FATAL_ERROR "${FILE}: fewer than two rows")
endif()
list(GET rows 0 header)
string(REPLACE "," ";" header "${header}")
list(FIND header "${COLUMN}" column)
if(column LESS 0)
  message(FATAL_ERROR "${FILE} has no column ${COLUMN}")
endif()
foreach(which 1 -1)
  list(GET rows ${which} row)
  string(REPLACE "," ";" row "${row}")
  list(GET row ${column} value_${which})
endforeach()
message("${COLUMN}: ${value_1} in the first row, ${value_-1} in the last (expected at most "
        "${ABOVE}, then above it)")
if(value_1 GREATER ABOVE OR NOT value_-1 GREATER ABOVE)
  message(FATAL_ERROR "${COLUMN} did not rise above ${ABOVE}")
endif()
