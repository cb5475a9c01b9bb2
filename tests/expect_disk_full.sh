#!/usr/bin/env bash
# A write that fails (a full disk, a file-size limit) stops the run with exit code 2 and
# one line naming the file and the reason, and leaves every file whole (check_outputs).
#   ulimit: a file-size limit of LIMIT KiB (ulimit -f), the run without VTK frames: the
#           growing statistics.csv or probes.csv hits it mid-run ("File too large").
#   tmpfs:  a LIMIT KiB tmpfs as the output directory, with VTK frames: a frame hits it
#           ("No space left on device"). Needs root and permission to mount; where that is
#           not given the test prints SKIPPED.
# Usage: expect_disk_full.sh CLOTHSIM CHECK_OUTPUTS PARAMETER_FILE WORK_DIR MODE LIMIT
#                            [clothsim arguments...]
set -u
clothsim=$1 check_outputs=$2 prm=$3 work=$4 mode=$5 limit=$6
shift 6
rm -rf "$work"
mkdir -p "$work/disk"
directory=$work/disk/run
fail() { echo "FAIL: $*"; exit 1; }

if [ "$mode" = tmpfs ]; then
  if ! mount -t tmpfs -o "size=${limit}k" clothsim-test "$work/disk" 2>/dev/null; then
    echo "SKIPPED: cannot mount a tmpfs here (not root, or no permission in this container)"
    exit 0
  fi
  trap 'umount "$work/disk"' EXIT
  "$clothsim" "$prm" "$@" --output-dir "$directory" >"$work/out" 2>"$work/err"
  status=$?
  reason="No space left on device"
else
  # PMIx keeps its shared-memory store in a file, which the limit would stop at MPI_Init.
  (export PMIX_MCA_gds=hash; ulimit -f "$limit"; exec "$clothsim" "$prm" "$@" --output-dir "$directory") \
    >"$work/out" 2>"$work/err"
  status=$?
  reason="File too large"
fi
cat "$work/err"
[ "$status" -eq 2 ] || fail "exit code $status, expected 2"
[ "$(wc -l <"$work/err")" -eq 1 ] || fail "expected one line on stderr"
grep -q "^clothsim: output failed: cannot write $directory/[a-z0-9.-]*: $reason" "$work/err" ||
  fail "the line does not name the file and the reason ($reason)"
"$check_outputs" "$directory" || fail "the outputs are not whole"
[ "$(wc -l <"$directory/probes.csv")" -gt 4 ] || fail "the run should have failed mid-run"
echo "the write failure stopped the run cleanly"
