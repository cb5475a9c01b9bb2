#!/usr/bin/env bash
# Cost of obstacle contact (issue 16): params/contact/sheet-on-sphere.prm as shipped against
# the same scene with its obstacle removed ("Obstacle 1/Shape=none": the sheet falls freely),
# on N x N-vertex sheets (meshes/swing-N.msh), all measured in this one invocation (compare
# the ratios, not the absolute times of different machines). Runs one simulation at a time.
#
# Prints two tables (progress on stderr, tables on stdout). Per run:
#   steps, halvings   time steps taken and step halvings ("done:" line of the run)
#   wall_s            the run's wall time (its timer's total)
#   ms/step           wall_s / steps
#   newton/step       Newton iterations per step, failed attempts included
#   lin/step          linear iterations per step (1 per Newton iteration with "direct")
#   lin/newton        linear iterations per Newton iteration (CG's count with "cg")
#   ms/newton         wall_s / Newton iterations
#   contact%          the contact and friction terms' share of the assembly time per term
#   x_prev            ms/step and newton/step over the same method's and obstacle's at the
#                     previous size (N to about 2N: h halved)
# and per method and N the ratios contact / no contact of the wall time (same simulated
# time), ms/step, newton/step, lin/step and ms/newton. Those runs follow different motions
# (the free sheet never deforms: one Newton iteration per step).
# The issue's target, "the sheet-on-sphere step against the same step without the
# obstacle: contact adds less than 2x", is the third table: from each time T of --from, the
# next --window steps of the sphere run against the same steps taken from the same state
# with the sphere gone ('Obstacle 1/Removed at = T + dt/2': from the step after T on, no
# barrier, cap or friction of it, and nothing carried along with it). The script checks that
# both runs are the same up to T (Newton iterations and kinetic energy, every step) and
# prints, per T and summed over the T's: Newton iterations and wall time (statistics.csv's
# wall_seconds) over the window, with and without the sphere, and their ratios.
# A failed run is marked FAILED (its figures from its statistics.csv, accepted steps only),
# the others still run, the output directory is kept and the exit code is 1.
#
# Usage: scripts/benchmark-contact.sh [options]
#   --sizes "N ..."     vertices per side (default "21 41 81"; meshes/swing-N.geo must exist)
#   --methods "M ..."   'Linear solver/Method' values (default "direct", as the scene; "cg"
#                       for CG with AMG: slow with contact, see Time below)
#   --end-time T        simulated time, s (default 1.5, as the scene: the sheet lands at
#                       about 0.1 s, so it is on the sphere for 93 % of the run)
#   --from "T ..."      times (s) from which the same steps are run without the sphere
#                       (default "0.3 0.6 0.9 1.2"; "" skips that table); each at
#                       least window + 3 steps before --end-time
#   --window K          steps after each T (default 6: 0.1 s)
#   --instructions      also count the instructions of each window (callgrind, valgrind
#                       needed): both runs to T write a checkpoint, and each window is its
#                       restart counted in TimeStepper::run() alone (start-up, mesh and
#                       checkpoint reading excluded): a fourth table, free of the machine's
#                       timing noise. Slow: callgrind runs about 50 times slower (N = 21:
#                       seconds per window, N = 41: about a minute, N = 81: minutes).
#                       With 'Contact/Self contact = creases' but not 'true' (it has
#                       no checkpoints yet: the runs to T stop with that message, and
#                       the windows are FAILED)
#   --set "S/N=V"       passed to every run (repeatable)
#   --output DIR        where the runs write (DIR/<method>-N<N>-<sphere|none|from-T>/,
#                       run.log);
#                       default a temporary directory, removed at the end unless --keep
#   --keep              keep the temporary output directory
#   --reuse             with --output: do not run again what a run there finished (its
#                       run.log has the "done:" line), e.g. to print the tables again
#   CLOTHSIM=path       the executable (default build/clothsim of the source tree)
# Example: CLOTHSIM=/tmp/clothsim scripts/benchmark-contact.sh --sizes "21 41" --methods direct
# Time (one core): N = 21, 41, 81 with direct about 5 s, 25 s, 3 min with contact, seconds
# without; the runs from the --from times 2.3 times the contact run's again (about 10 min
# in all). cg with contact: 15 s at N = 21, 14 min at N = 41 (step halvings), far longer.
set -euo pipefail

repository=$(cd "$(dirname "$0")/.." && pwd)
clothsim=${CLOTHSIM:-$repository/build/clothsim}
sizes="21 41 81"
methods="direct"
end_time=1.5
from_times="0.3 0.6 0.9 1.2"
window=6
output=""
keep=false
reuse=false
instructions=false
overrides=()

die() {
  echo "benchmark-contact: error: $*" >&2
  exit 1
}
while [ $# -gt 0 ]; do
  case "$1" in
    --sizes | --methods | --end-time | --from | --window | --set | --output)
      [ $# -ge 2 ] || die "$1 expects a value"
      case "$1" in
        --sizes) sizes=$2 ;;
        --methods) methods=$2 ;;
        --end-time) end_time=$2 ;;
        --from) from_times=$2 ;;
        --window) window=$2 ;;
        --set) overrides+=(--set "$2") ;;
        --output) output=$2 ;;
      esac
      shift 2
      ;;
    --keep) keep=true && shift ;;
    --instructions) instructions=true && shift ;;
    --reuse) reuse=true && shift ;;
    -h | --help) sed -n '/^# Usage:/,/^# Example:/p' "$0" | sed 's/^# \{0,1\}//' && exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done
[ -x "$clothsim" ] || die "no executable '$clothsim' (build first, or set CLOTHSIM)"
[ "$instructions" = false ] || [ -n "$from_times" ] || die "--instructions needs --from times"
[ "$instructions" = false ] || command -v valgrind >/dev/null ||
  die "--instructions needs valgrind (Debian package valgrind)"
[[ "$window" =~ ^[1-9][0-9]*$ ]] || die "--window: a positive number of steps, not '$window'"
# The scene's step (s), from its parameter file.
dt=$(sed -n 's/^ *set Time step *= *\([0-9.e+-]*\).*/\1/p' \
  "$repository/params/contact/sheet-on-sphere.prm" | head -n 1)
for t in $from_times; do
  awk -v t="$t" -v e="$end_time" -v w="$window" -v d="$dt" \
    'BEGIN { exit !(t ~ /^[0-9.]+([eE][-+]?[0-9]+)?$/ && t > 0 && t + (w + 3) * d <= e) }' ||
    die "--from: '$t' is not a time in (0, end time - (window + 3) steps] (end time $end_time s, window $window steps of $dt s)"
done
for n in $sizes; do
  [[ "$n" =~ ^[0-9]+$ ]] && [ -f "$repository/meshes/swing-$n.geo" ] ||
    die "--sizes: no mesh meshes/swing-$n.geo"
done
if [ -z "$output" ]; then
  output=$(mktemp -d "${TMPDIR:-/tmp}/benchmark-contact.XXXXXX")
  temporary=true
else
  mkdir -p "$output" && output=$(cd "$output" && pwd)
  temporary=false
fi

# measure DIR: "vertices steps halvings wall newton linear contact% status" of the run.
measure() {
  local log="$1/run.log" done_line
  done_line=$(grep '^done: ' "$log" | tail -n 1 || true)
  sed -n 's/^  mesh .*: \([0-9]*\) vertices,.*/\1/p' "$log" | head -n 1 | tr '\n' ' '
  if [ -n "$done_line" ]; then
    sed 's/^done: \([0-9]*\) steps in \([0-9.e+-]*\) s; Newton iterations \([0-9]*\) .*linear iterations \([0-9]*\) .*step halvings \([0-9]*\).*/\1 \5 \2 \3 \4/' \
      <<<"$done_line" | tr '\n' ' '
  else
    awk -F, 'NR == 1 { for (c = 1; c <= NF; ++c) k[$c] = c; next }
      { s = $k["step"]; w = $k["wall_seconds"]; h += $k["retries"]
        n += $k["newton_iterations"]; l += $k["linear_iterations"] }
      END { printf "%d %d %s %d %d ", s, h, w + 0, n, l }' "$1/statistics.csv" 2>/dev/null ||
      printf '0 0 0 0 0 '
  fi
  # "assembly time per term ...: membrane 1.2 s, ..., contact 0.5 s, friction 0.1 s"
  sed -n 's/^assembly time per term[^:]*: //p' "$log" | tr ',' '\n' | awk '
    $2 ~ /^[0-9.e+-]+$/ { all += $2; if ($1 == "contact" || $1 == "friction") c += $2 }
    END { if (all > 0) printf "%.1f ", 100 * c / all; else printf "- " }'
  [ -n "$done_line" ] && echo ok || echo FAILED
}

# run_scene DIRECTORY N END_TIME METHOD [--set S/N=V]...: the scene into DIRECTORY, its log
# in DIRECTORY/run.log; skipped with --reuse where a run there finished.
run_scene() {
  local directory=$1 n=$2 end=$3 method=$4
  shift 4
  mkdir -p "$directory"
  if [ "$reuse" = true ] && grep -q '^done: ' "$directory/run.log" 2>/dev/null; then
    printf '(reused) ' >&2
    return 0
  fi
  "$clothsim" "$repository/params/contact/sheet-on-sphere.prm" \
    --set "Mesh/Mesh file=$repository/meshes/swing-$n.msh" --set "Time/End time=$end" \
    --set "Output/Write VTK=false" --set "Output/Progress=off" \
    --set "Linear solver/Method=$method" ${overrides[@]+"${overrides[@]}"} "$@" \
    --output-dir "$directory" >"$directory/run.log" 2>&1
}

rows=()
failed=false
echo "benchmark-contact: $clothsim, end time $end_time s, sizes $sizes, methods $methods" >&2
for method in $methods; do
  for n in $sizes; do
    for obstacle in sphere none; do
      directory="$output/$method-N$n-$obstacle"
      printf '%s, N = %s, obstacle %s ... ' "$method" "$n" "$obstacle" >&2
      shape=()
      [ "$obstacle" = none ] && shape=(--set "Obstacle 1/Shape=none")
      run_scene "$directory" "$n" "$end_time" "$method" ${shape[@]+"${shape[@]}"} ||
        failed=true
      row="$method $n $obstacle $(measure "$directory")"
      [ "${row##* }" = ok ] || failed=true
      rows+=("$row")
      echo "$(cut -d' ' -f11 <<<"$row"), $(cut -d' ' -f7 <<<"$row") s" >&2
    done
  done
done

printf '%s\n' "${rows[@]}" | awk '
  function r(a, b) { return b > 0 ? sprintf("%.2f", a / b) : "-" }
  { m = $1; n = $2; o = $3; steps = $5; newton = $8
    ms[m, n, o] = steps ? 1000 * $7 / steps : 0; nps[m, n, o] = steps ? newton / steps : 0
    lps[m, n, o] = steps ? $9 / steps : 0; msn[m, n, o] = newton ? 1000 * $7 / newton : 0
    wall[m, n, o] = $7; line[NR] = $0; key[NR] = m SUBSEP n SUBSEP o
    if (!((m, o) in last)) prev[NR] = ""; else prev[NR] = last[m, o]
    last[m, o] = key[NR]
    if (!((m, n) in seen)) { seen[m, n] = 1; pairs[++np] = m SUBSEP n } }
  END {
    f = "%-7s %4s %-6s %8s %5s %4s %8s %8s %7s %7s %7s %8s %8s %8s %8s  %s\n"
    printf f, "method", "N", "obst.", "vertices", "steps", "halv", "wall_s", "ms/step",
      "newton/", "lin/", "lin/", "ms/", "contact%", "ms/step", "newton/", "status"
    printf f, "", "", "", "", "", "", "", "", "step", "step", "newton", "newton", "", "x_prev",
      "x_prev", ""
    for (i = 1; i <= NR; ++i) {
      split(line[i], v, " "); k = key[i]; p = prev[i]
      printf f, v[1], v[2], v[3], v[4], v[5], v[6], sprintf("%.2f", v[7]),
        sprintf("%.1f", ms[k]), sprintf("%.2f", nps[k]), sprintf("%.2f", lps[k]),
        v[8] ? sprintf("%.2f", v[9] / v[8]) : "-", sprintf("%.2f", msn[k]), v[10],
        p == "" ? "-" : r(ms[k], ms[p]), p == "" ? "-" : r(nps[k], nps[p]), v[11]
    }
    printf "\ncontact / no contact (same method, N and duration)\n"
    g = "%-7s %4s %6s %8s %12s %9s %10s\n"
    printf g, "method", "N", "wall", "ms/step", "newton/step", "lin/step", "ms/newton"
    for (i = 1; i <= np; ++i) {
      split(pairs[i], q, SUBSEP); c = pairs[i] SUBSEP "sphere"; z = pairs[i] SUBSEP "none"
      printf g, q[1], q[2], r(wall[c], wall[z]), r(ms[c], ms[z]), r(nps[c], nps[z]), r(lps[c], lps[z]),
        r(msn[c], msn[z])
    }
  }'

# same_steps WITH WITHOUT T: "newton_with newton_without wall_with wall_without
# halvings_with halvings_without status" over the steps that end in (T, T + window dt] of
# the two runs' statistics.csv, status "ok" if every step up to T is the same in both
# (Newton iterations and kinetic energy as written).
same_steps() {
  awk -F, -v t="$3" -v end="$(awk -v t="$3" -v w="$window" -v d="$dt" 'BEGIN { printf "%.17g", t + w * d + 1e-9 }')" '
    FNR == 1 { run++; for (c = 1; c <= NF; ++c) k[c] = $c; for (c = 1; c <= NF; ++c) col[$c] = c
               previous = 0; next }
    { time = $col["time"] + 0; wall = $col["wall_seconds"] + 0; step = wall - previous
      previous = wall
      if (time <= t + 1e-9) {
        key = sprintf("%.9f", time); state = $col["newton_iterations"] " " $col["kinetic_energy"]
        if (run == 1) before[key] = state
        else if (!(key in before) || before[key] != state) diverged = 1
        else matched++
      } else if (time <= end) {
        newton[run] += $col["newton_iterations"]; seconds[run] += step
        halvings[run] += $col["retries"]; last[run] = time
      }
    }
    END { status = diverged || matched == 0 ? "DIVERGED" : "ok"
          if (newton[1] == 0 || newton[2] == 0 || last[1] < end - 1e-6 || last[2] < end - 1e-6)
            status = "FAILED"
          printf "%d %d %.3f %.3f %d %d %s\n", newton[1], newton[2], seconds[1], seconds[2],
            halvings[1], halvings[2], status }' \
    "$1" "$2" 2>/dev/null || echo "0 0 0 0 0 0 FAILED"
}

# The same steps from the same states without the sphere (the third table).
if [ -n "$from_times" ]; then
  same_rows=()
  for method in $methods; do
    for n in $sizes; do
      with="$output/$method-N$n-sphere"
      for t in $from_times; do
        directory="$output/$method-N$n-from-$t"
        printf '%s, N = %s, the sphere gone after t = %s s ... ' "$method" "$n" "$t" >&2
        removal=$(awk -v t="$t" -v d="$dt" 'BEGIN { printf "%.17g", t + d / 2 }')
        # Three steps past the window: the run's last two steps may be split evenly to
        # end on the end time (a BDF2 step of 0.75 dt), which must not fall in the window.
        finish=$(awk -v t="$t" -v d="$dt" -v w="$window" 'BEGIN { printf "%.17g", t + (w + 3) * d }')
        # Its Newton may fail after the window (checked below), not a failure here.
        run_scene "$directory" "$n" "$finish" "$method" \
          --set "Obstacle 1/Removed at=$removal" || true
        row="$method $n $t $(same_steps "$with/statistics.csv" "$directory/statistics.csv" "$t")"
        # The window complete, a run that stopped after it is marked, not failed.
        [ "${row##* }" = ok ] && ! grep -q '^done: ' "$directory/run.log" 2>/dev/null &&
          row="${row% *} ok,stopped-after"
        [ "${row##* }" = FAILED ] || [ "${row##* }" = DIVERGED ] && failed=true
        same_rows+=("$row")
        echo "${row##* }" >&2
      done
    done
  done
  echo
  echo "the same $window steps from the same state, with the sphere / without it (gone after T;"
  echo "'ok,stopped-after': that run's Newton failed after the window, see its run.log)"
  printf '%s\n' "${same_rows[@]}" | awk '
    function r(a, b) { return b > 0 ? sprintf("%.2f", a / b) : "-" }
    BEGIN { f = "%-7s %4s %6s %8s %8s %7s %8s %8s %7s %6s %6s  %s\n"
            printf f, "method", "N", "T", "newton", "newton", "ratio", "wall_s", "wall_s", "ratio",
              "halv", "halv", "status"
            printf f, "", "", "", "sphere", "none", "", "sphere", "none", "", "sphere", "none", "" }
    { printf f, $1, $2, $3, $4, $5, r($4, $5), $6, $7, r($6, $7), $8, $9, $10
      k = $1 SUBSEP $2; if (!(k in n1)) order[++m] = k
      n1[k] += $4; n2[k] += $5; w1[k] += $6; w2[k] += $7; h1[k] += $8; h2[k] += $9 }
    END { for (i = 1; i <= m; ++i) { split(order[i], q, SUBSEP); k = order[i]
            printf f, q[1], q[2], "all", n1[k], n2[k], r(n1[k], n2[k]), sprintf("%.3f", w1[k]),
              sprintf("%.3f", w2[k]), r(w1[k], w2[k]), h1[k], h2[k], "" } }'
fi

# The instructions of each window (the fourth table): the runs to T with a checkpoint at
# T, with the sphere and with it removed after T, each restarted to T + window dt under
# callgrind, which counts TimeStepper::run() only.
if [ "$instructions" = true ]; then
  count_rows=()
  for method in $methods; do
    for n in $sizes; do
      for t in $from_times; do
        removal=$(awk -v t="$t" -v d="$dt" 'BEGIN { printf "%.17g", t + d / 2 }')
        finish=$(awk -v t="$t" -v d="$dt" -v w="$window" 'BEGIN { printf "%.17g", t + w * d }')
        row="$method $n $t"
        for obstacle in sphere none; do
          directory="$output/$method-N$n-count-$obstacle-$t"
          printf '%s, N = %s, instructions from t = %s s, %s ... ' "$method" "$n" "$t" "$obstacle" >&2
          removed=()
          [ "$obstacle" = none ] && removed=(--set "Obstacle 1/Removed at=$removal")
          rm -rf "$directory"
          run_scene "$directory" "$n" "$t" "$method" --set "Output/Checkpoint interval=$t" \
            ${removed[@]+"${removed[@]}"} || true
          valgrind --tool=callgrind --callgrind-out-file="$directory/callgrind.out" \
            --log-file="$directory/callgrind.log" --collect-atstart=no \
            --toggle-collect='clothsim::TimeStepper::run()' \
            "$clothsim" --restart "$directory" --set "Time/End time=$finish" \
            >>"$directory/run.log" 2>&1 || true
          # One "Collected : N" line per thread and process: their sum.
          counted=$(awk '/Collected :/ { n += $NF; found = 1 } END { if (found) printf "%.0f\n", n }' \
            "$directory/callgrind.log" 2>/dev/null || true)
          newton=$(awk -F, -v t="$t" 'NR == 1 { for (c = 1; c <= NF; ++c) col[$c] = c; next }
            $col["time"] > t + 1e-9 { n += $col["newton_iterations"] } END { print n + 0 }' \
            "$directory/statistics.csv" 2>/dev/null || echo 0)
          if grep -q '^done: ' "$directory/run.log" && [ -n "$counted" ]; then
            echo "ok, $counted instructions" >&2
          else
            echo FAILED >&2
            counted=0 && failed=true
          fi
          row="$row $newton $counted"
        done
        count_rows+=("$row")
      done
    done
  done
  echo
  echo "the same $window steps from the same state, instructions (callgrind, TimeStepper::run()):"
  printf '%s\n' "${count_rows[@]}" | awk '
    function r(a, b) { return b > 0 ? sprintf("%.2f", a / b) : "-" }
    BEGIN { f = "%-7s %4s %6s %8s %8s %7s %12s %12s %7s %10s\n"
            printf f, "method", "N", "T", "newton", "newton", "ratio", "instr.", "instr.", "ratio",
              "per newton"
            printf f, "", "", "", "sphere", "none", "", "sphere", "none", "", "ratio" }
    { printf f, $1, $2, $3, $4, $6, r($4, $6), $5, $7, r($5, $7),
        ($4 > 0 && $6 > 0 ? r($5 / $4, $7 / $6) : "-")
      k = $1 SUBSEP $2; if (!(k in n1)) order[++m] = k
      n1[k] += $4; i1[k] += $5; n2[k] += $6; i2[k] += $7 }
    END { for (i = 1; i <= m; ++i) { split(order[i], q, SUBSEP); k = order[i]
            printf f, q[1], q[2], "all", n1[k], n2[k], r(n1[k], n2[k]), sprintf("%.0f", i1[k]),
              sprintf("%.0f", i2[k]),
              r(i1[k], i2[k]), (n1[k] > 0 && n2[k] > 0 ? r(i1[k] / n1[k], i2[k] / n2[k]) : "-") } }'
fi

if [ "$failed" = true ]; then
  echo "benchmark-contact: a run failed; runs kept in $output" >&2
  exit 1
elif [ "$temporary" = true ] && [ "$keep" = false ]; then
  rm -rf "$output"
else
  echo "runs kept in $output" >&2
fi
