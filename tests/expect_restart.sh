#!/usr/bin/env bash
# Checkpoint and restart (README "Checkpoint and restart"): a run to T and a run to T/2
# restarted to T end with byte-identical probes.csv, frames and solution.pvd (but for the
# date in its comment), and statistics.csv rows equal but for their wall times; so does a
# run stopped by SIGTERM and restarted. Then the refusals: a changed material entry (by
# --set and by editing parameters.prm), an end time not after the checkpoint, another
# number of ranks, a corrupt, truncated or missing checkpoint: exit code 1, one line
# "clothsim: error: <file>: <entry>: ...", nothing in the directory changed.
# Usage: expect_restart.sh CLOTHSIM COMPARE_PROBES PARAMETER_FILE OUTPUT_DIR T RANKS
#                          MPIEXEC MODE [--set ...]...
#   MODE exact: the run to T writes no checkpoint, and the run stopped by SIGTERM and
#   restarted gives the same bytes as well (the solver keeps nothing from step to step
#   that a checkpoint does not store: Newton with the direct solver). MODE renewed: the
#   solver keeps state that a checkpoint renews (AMG aggregates, modified Newton's
#   tangent): the run to T writes a checkpoint at T/2 too, and the restart after SIGTERM
#   (renewed where it stopped) agrees with it to 1e-6 of the probes' displacements.
set -u
clothsim=$1 compare_probes=$2 prm=$3 out=$4 end=$5 ranks=$6 mpiexec=$7 mode=$8
shift 8
sets=("$@")
half=$(awk "BEGIN { printf \"%.17g\", $end / 2 }")
run=("$clothsim")
[ "$ranks" -gt 1 ] && run=("$mpiexec" --oversubscribe -np "$ranks" "$clothsim")
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$out" && mkdir -p "$out"

# Byte-identical frames, records and probes; statistics.csv without its timing columns
# (wall_seconds, assembly_seconds, linear_solve_seconds: 12, 15, 16).
same_outputs() {
  local a=$1 b=$2
  cmp -s "$a/probes.csv" "$b/probes.csv" || fail "$b/probes.csv differs from $a's"
  [ -s "$a/probes.csv" ] || fail "$a/probes.csv is empty"
  local frames_a frames_b
  frames_a=$(cd "$a" && ls solution* | sort) frames_b=$(cd "$b" && ls solution* | sort)
  [ "$frames_a" = "$frames_b" ] || fail "$b has other frame files than $a"
  for file in $frames_a; do
    # (solution.pvd names the time it was written in a comment)
    cmp -s <(grep -v '^#This file was generated' "$a/$file") \
      <(grep -v '^#This file was generated' "$b/$file") || fail "$b/$file differs from $a's"
  done
  cut -d, -f1-11,13-14,17- "$a/statistics.csv" >"$a.stats"
  cut -d, -f1-11,13-14,17- "$b/statistics.csv" >"$b.stats"
  cmp -s "$a.stats" "$b.stats" || fail "$b/statistics.csv differs from $a's"
  echo "$b: $(echo "$frames_a" | wc -w) frame files, $(wc -l <"$a/probes.csv") probe rows: identical to $a"
}

# One input error: exit 1, the message, and the directory's files unchanged.
expect_refusal() {
  local what=$1 pattern=$2 directory=$3
  shift 3
  local before after
  before=$(cd "$directory" && cat probes.csv statistics.csv solution.pvd checkpoint.bin 2>/dev/null | md5sum)
  "$@" >"$out/refusal.out" 2>"$out/refusal.err"
  local status=$?
  grep -v -e '^-----' -e '^Primary job' -e '^a non-zero exit' -e '^$' -e '^mpirun' \
    -e '^the job' -e '^  Process name' -e '^  Exit code' -e '^The first process' \
    "$out/refusal.err" >"$out/refusal.ours"
  [ "$status" -eq 1 ] || { cat "$out/refusal.err"; fail "$what: exit code $status, expected 1"; }
  [ "$(wc -l <"$out/refusal.ours")" -eq 1 ] || { cat "$out/refusal.err"; fail "$what: expected one line on stderr"; }
  grep -q -E "^clothsim: error: $pattern" "$out/refusal.ours" ||
    fail "$what: message '$(cat "$out/refusal.ours")' does not match '$pattern'"
  after=$(cd "$directory" && cat probes.csv statistics.csv solution.pvd checkpoint.bin 2>/dev/null | md5sum)
  [ "$before" = "$after" ] || fail "$what: the output directory changed"
  echo "refused ($what): $(cat "$out/refusal.ours")"
}

# The run to T (with a checkpoint at T/2 if asked).
full=("${run[@]}" "$prm" "${sets[@]}" --set "Time/End time=$end" --output-dir "$out/full")
[ "$mode" = renewed ] && full+=(--set "Output/Checkpoint interval=$half")
"${full[@]}" >"$out/full.log" 2>&1 || { cat "$out/full.log"; fail "the run to T failed"; }

# The run to T/2 with a checkpoint at its end, restarted to T.
"${run[@]}" "$prm" "${sets[@]}" --set "Time/End time=$half" \
  --set "Output/Checkpoint interval=$half" --output-dir "$out/halves" \
  >"$out/halves.log" 2>&1 || { cat "$out/halves.log"; fail "the run to T/2 failed"; }
[ -s "$out/halves/checkpoint.bin" ] || fail "the run to T/2 left no checkpoint"
echo "checkpoint: $(stat -c %s "$out/halves/checkpoint.bin") bytes"
cp -r "$out/halves" "$out/pristine"
"${run[@]}" --restart "$out/halves" --set "Time/End time=$end" >>"$out/halves.log" 2>&1 ||
  { cat "$out/halves.log"; fail "the restart failed"; }
grep -q "restart from the checkpoint" "$out/halves.log" || fail "the restart does not say so"
same_outputs "$out/full" "$out/halves"

# Stopped by SIGTERM after a few frames, then restarted: the same answer.
"${run[@]}" "$prm" "${sets[@]}" --set "Time/End time=$end" --output-dir "$out/stopped" \
  >"$out/stopped.log" 2>&1 &
launched=$!
probes=$(awk -F, 'NR > 1 { print $3 }' "$out/full/probes.csv" | sort -u | wc -l)
for _ in $(seq 1200); do
  rows=$(cat "$out/stopped/probes.csv" 2>/dev/null | wc -l)
  [ "$rows" -ge $((1 + 2 * probes)) ] && break
  sleep 0.05
done
target=$launched
if [ "$ranks" -gt 1 ]; then
  target=$(cat /proc/"$launched"/task/*/children | tr ' ' '\n' | grep . | tail -n 1)
fi
kill -s TERM "$target"
wait "$launched"
status=$?
[ "$status" -ne 0 ] || fail "the run ended before SIGTERM arrived (choose a longer T)"
[ "$ranks" -gt 1 ] || [ "$status" -eq 143 ] || { cat "$out/stopped.log"; fail "exit code $status after SIGTERM"; }
grep -q "continue it with clothsim --restart" "$out/stopped.log" ||
  { cat "$out/stopped.log"; fail "the interrupted run does not say how to continue"; }
[ -s "$out/stopped/checkpoint.bin" ] || fail "the interrupted run left no checkpoint"
grep -o 'interrupted by SIGTERM after step [0-9]* (t = [^)]*)' "$out/stopped.log"
"${run[@]}" --restart "$out/stopped" >>"$out/stopped.log" 2>&1 ||
  { cat "$out/stopped.log"; fail "the restart after SIGTERM failed"; }
if [ "$mode" = exact ]; then
  same_outputs "$out/full" "$out/stopped"
else
  "$compare_probes" "$out/full/probes.csv" "$out/stopped/probes.csv" 1e-6 1e-9 ||
    fail "the restart after SIGTERM does not agree with the run to T"
  [ "$(cd "$out/full" && ls solution* | sort)" = "$(cd "$out/stopped" && ls solution* | sort)" ] ||
    fail "the restart after SIGTERM has other frame files than the run to T"
fi

# Refusals, on the directory of the run to T/2 (as it was before its restart).
pristine=$out/pristine
expect_refusal "changed material by --set" "--set: Material/Poisson ratio: .*only" \
  "$pristine" "${run[@]}" --restart "$pristine" --set "Material/Poisson ratio=0.3"
cp "$pristine/parameters.prm" "$out/parameters.prm.saved"
sed -i 's/^\(  set Areal density *= *\).*/\10.2/' "$pristine/parameters.prm"
expect_refusal "changed material in parameters.prm" \
  ".*parameters.prm: Material/Areal density: differs from the checkpoint's run" \
  "$pristine" "${run[@]}" --restart "$pristine" --set "Time/End time=$end"
cp "$out/parameters.prm.saved" "$pristine/parameters.prm"
expect_refusal "end time not later" ".*Time/End time: the checkpoint is at t = " \
  "$pristine" "${run[@]}" --restart "$pristine"
other=$((ranks == 1 ? 2 : 1))
other_run=("$clothsim")
[ "$other" -gt 1 ] && other_run=("$mpiexec" --oversubscribe -np "$other" "$clothsim")
expect_refusal "$other rank(s)" ".*checkpoint.bin: the checkpoint was written by $ranks MPI rank" \
  "$pristine" "${other_run[@]}" --restart "$pristine" --set "Time/End time=$end"
cp "$pristine/checkpoint.bin" "$out/checkpoint.saved"
size=$(stat -c %s "$out/checkpoint.saved")
printf '\x55' | dd of="$pristine/checkpoint.bin" bs=1 seek=$((size - 9)) conv=notrunc status=none
expect_refusal "corrupt checkpoint" ".*checkpoint.bin: the checkpoint is corrupt" \
  "$pristine" "${run[@]}" --restart "$pristine" --set "Time/End time=$end"
head -c $((size / 2)) "$out/checkpoint.saved" >"$pristine/checkpoint.bin"
expect_refusal "truncated checkpoint" ".*checkpoint.bin: the checkpoint is truncated" \
  "$pristine" "${run[@]}" --restart "$pristine" --set "Time/End time=$end"
rm "$pristine/checkpoint.bin"
expect_refusal "missing checkpoint" ".*checkpoint.bin: no checkpoint to restart from" \
  "$pristine" "${run[@]}" --restart "$pristine" --set "Time/End time=$end"
echo "restart checks passed"
