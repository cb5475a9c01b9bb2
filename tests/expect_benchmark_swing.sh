#!/usr/bin/env bash
# scripts/benchmark-swing.sh with --repeat (N = 21, 0.05 s, both models, two runs each):
# a row per model, each run, no step halving, fem/ms given; every run's wall time listed
# after the table, two per model, and each row's cost (us/vtx-step, which shows more
# digits than wall_s) that of the fastest of its two. A
# --repeat that is not a positive number is refused.
# --cpu: through a clothsim that logs its own CPU affinity, every run of the table is
# pinned to the first CPU it may run on by default (0 here), to the CPU given (the
# last one), and to none with --cpu any; a CPU the machine does not have is refused.
# Usage: expect_benchmark_swing.sh SCRIPT BUILD_DIR
set -euo pipefail
script=$1
build=$2

fake=$(mktemp -d "${TMPDIR:-/tmp}/benchmark-swing-test.XXXXXX")
trap 'rm -rf "$fake"' EXIT
{
  echo '#!/bin/sh'
  echo "case \"\$*\" in *--output-dir*) taskset -cp \$\$ | sed 's/.*: //' >>'$fake/affinity' ;; esac"
  echo "exec '$(cd "$build" && pwd)/clothsim' \"\$@\""
} >"$fake/clothsim"
chmod +x "$fake/clothsim"
n_cpus=$(nproc --all)
all_cpus=$(taskset -cp $$ | sed 's/.*: //')
for cpu in default "$((n_cpus - 1))" any; do
  rm -f "$fake/affinity"
  option=()
  [ "$cpu" = default ] || option=(--cpu "$cpu")
  footer=$("$script" --build "$fake" --sizes 21 --end-time 0.05 --models fem "${option[@]}" \
    2>/dev/null | grep '^one-rank runs' || true)
  expected=$cpu
  [ "$cpu" = default ] && expected=${all_cpus%%[-,]*}
  [ "$cpu" = any ] && expected=$all_cpus
  got=$(sort -u "$fake/affinity" | tr '\n' ' ')
  echo "--cpu $cpu: the run's affinity ${got}($footer)"
  [ "$got" = "$expected " ] || { echo "FAIL: expected the affinity $expected"; exit 1; }
done
if message=$("$script" --build "$build" --cpu "$n_cpus" 2>&1); then
  echo "FAIL: --cpu $n_cpus was accepted on $n_cpus CPUs"
  exit 1
fi
grep -q -- "--cpu: '$n_cpus' is not a CPU this process may run on" <<<"$message" ||
  { echo "FAIL: --cpu $n_cpus refused with: $message"; exit 1; }

if message=$("$script" --build "$build" --repeat 0 2>&1); then
  echo "FAIL: --repeat 0 was accepted"
  exit 1
fi
grep -q -- "--repeat: '0' is not a positive number of runs" <<<"$message" ||
  { echo "FAIL: --repeat 0 refused with: $message"; exit 1; }
table=$("$script" --build "$build" --sizes 21 --end-time 0.05 --repeat 2 2>/dev/null)
echo "$table"
echo "$table" | awk '
  $1 == 21 && ($2 == "fem" || $2 == "mass-spring") && $NF == "ok" {
    rows++
    cost[$2] = $8; vertex_steps[$2] = $4 * $5
    if ($5 != 3 || $6 != 0 || !($9 > 0)) bad = bad " " $2 ": steps " $5 ", halvings " $6
    if ($2 == "fem" && !($11 > 0)) bad = bad " fem/ms " $11
  }
  /^  N = 21, (fem|mass-spring), 1 rank\(s\): / {
    model = $4; sub(/,$/, "", model)
    k = 0; fastest = 0
    for (i = 7; i < NF; ++i) { ++k; if (fastest == 0 || $i < fastest) fastest = $i }
    runs[model] = k; fastest_wall[model] = fastest
  }
  END {
    for (m in cost) {
      best = sprintf("%.1f", 1e6 * fastest_wall[m] / vertex_steps[m])
      if (runs[m] != 2 || best != cost[m])
        bad = bad " " m ": " runs[m] " runs listed, the fastest " best " us/vtx-step, the row " cost[m]
    }
    printf "rows %d%s\n", rows, bad == "" ? "" : ";" bad
    if (rows != 2 || bad != "") { print "FAIL"; exit 1 }
    print "PASSED"
  }'
