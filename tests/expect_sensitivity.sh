#!/usr/bin/env bash
# scripts/sensitivity.sh on the swinging sheet (params/benchmarks/swing.prm, N = 21, first
# 0.3 s, before it goes slack): the perturbed run starts exactly the default perturbation
# away (1e-8 x y m: 1e-8 m at the free corner, x = y = 1), the two runs stay within 2e-8 m
# of each other (measured: at most 1.0e-8 m; the amplification starts at about 0.5 s), and
# the script finds no distance beyond 1 mm.
# Usage: expect_sensitivity.sh SCRIPT BUILD_DIR
set -euo pipefail
script=$1
build=$2
table=$("$script" --build "$build" --set "Mesh/Mesh file=../../meshes/swing-21.msh" \
  --set "Time/End time=0.3" --set "Output/Progress=off" 2>&1)
echo "$table"
echo "$table" | awk '
  $1 ~ /^[0-9.]+$/ && NF == 4 {
    rows++
    if ($1 + 0 == 0) start = $2 + 0
    if ($2 + 0 > largest) largest = $2 + 0
  }
  /^first beyond 1 mm: never$/ { never = 1 }
  END {
    ok = rows >= 9 && start > 0.99e-8 && start < 1.01e-8 && largest < 2e-8 && never
    printf "rows %d, distance at t = 0: %g m, largest: %g m, none beyond 1 mm: %d\n",
           rows, start, largest, never
    if (!ok) { print "FAIL"; exit 1 }
    print "PASSED"
  }'
