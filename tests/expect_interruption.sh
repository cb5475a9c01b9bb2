#!/usr/bin/env bash
# A run stopped by SIGINT or SIGTERM finishes its step, writes the state it reached as the
# last frame, closes its files whole, prints one line on stderr and exits with 128 + the
# signal's number. Under MPI the signal goes to one rank only (the last one): all ranks
# must stop together after the same step.
# Usage: expect_interruption.sh CLOTHSIM CHECK_OUTPUTS PARAMETER_FILE OUTPUT_DIR SIGNAL
#                               [RANKS MPIEXEC]
set -u
clothsim=$1 check_outputs=$2 prm=$3 directory=$4 signal=$5 ranks=${6:-1} mpiexec=${7:-}
rm -rf "$directory"
command=("$clothsim" "$prm" --set "Time/End time=1000" --output-dir "$directory")
if [ "$ranks" -gt 1 ]; then
  command=("$mpiexec" --oversubscribe -np "$ranks" "${command[@]}")
fi
"${command[@]}" >"$directory.out" 2>"$directory.err" &
launched=$!

# Wait until the run has written a few frames (3 probe rows each), at most 120 s.
for _ in $(seq 1200); do
  rows=$(cat "$directory/probes.csv" 2>/dev/null | wc -l)
  [ "$rows" -ge 10 ] && break
  sleep 0.1
done
target=$launched
if [ "$ranks" -gt 1 ]; then
  # mpirun's children are the ranks (/proc: no procps needed).
  target=$(cat /proc/"$launched"/task/*/children | tr ' ' '\n' | grep . | tail -n 1)
fi
echo "sending SIG$signal to process $target after $rows rows of probes.csv"
kill -s "$signal" "$target"
wait "$launched"
status=$?
cat "$directory.err"

fail() { echo "FAIL: $*"; exit 1; }
expected=$((128 + $(kill -l "$signal")))
[ "$status" -eq "$expected" ] || fail "exit code $status, expected $expected"
grep -v -e '^-----' -e '^Primary job' -e '^a non-zero exit' -e '^$' -e '^mpirun' \
  -e '^the job' -e '^  Process name' -e '^  Exit code' -e '^The first process' \
  "$directory.err" >"$directory.ours"
[ "$(wc -l <"$directory.ours")" -eq 1 ] || fail "expected one line from clothsim on stderr"
grep -q "^clothsim: interrupted by SIG$signal after step [0-9]* (t = [0-9.e+-]*)" \
  "$directory.ours" || fail "the line does not say which signal stopped the run and where"
time=$(sed -n 's/.*(t = \([0-9.e+-]*\)).*/\1/p' "$directory.ours")
"$check_outputs" "$directory" --last-time "$time" || fail "the outputs are not whole"
echo "interrupted cleanly at t = $time"
