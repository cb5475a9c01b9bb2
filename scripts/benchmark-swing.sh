#!/usr/bin/env bash
# Cost of the swinging sheet (params/benchmarks/swing.prm) against the mesh size, for the
# finite elements and the mass-spring model on the same mesh, all measured in this one
# invocation (compare the ratios, not the absolute times of different machines).
#
# For each N of --sizes it runs clothsim on meshes/swing-N.msh (N x N vertices, generated
# from its .geo on first use) once with "Model=fem" and once with "Model=mass-spring",
# then prints one table, a row per N, model and number of MPI ranks (--ranks):
#   vertices        of the mesh, as the run reports it
#   steps           time steps taken (last row of statistics.csv)
#   halvings        step halvings after a failed Newton solve ("step halvings" of the run)
#   wall_s          wall time of the time loop (the last wall_seconds of statistics.csv:
#                   it counts from the first frame, so it is not summed)
#   us/vtx-step     wall_s / (vertices x steps), in microseconds
#   newton/step     Newton iterations per step, failed attempts included
#   lin/newton      linear iterations per Newton iteration
#   ranks           MPI ranks of the run (mpirun -np, for more than one)
#   steady_us       us/vtx-step over the steps after the first, whose wall time holds the
#                   one-time work (the direct solver's analysis: about 3 s at N = 321)
#   steady_vs_N0    steady_us over the same model's at the smallest N (same ranks)
#   fem/ms          (fem rows) the fem cost per vertex-step over the mass-spring one
#                   (same N and ranks)
#   vs_N0           the cost per vertex-step over the same model's at the smallest N (same
#                   ranks)
#   speedup         (runs on several ranks) the wall time on one rank over this one, same N
#                   and model (needs 1 in --ranks)
#   it_speedup      (runs on several ranks) the same per Newton iteration of the steps
#                   after the first, which holds one-time work (the direct solver's
#                   analysis: about 3 s at N = 321) that a long run amortises
#   status          ok, or FAILED with the time the run reached
# After the table, a line names the libraries and the BLAS' kernels (clothsim --version).
# With more than one rank, a line after the table says how fast the CPUs the ranks run on
# are: the same one-rank run (N = 161, fem, 0.1 s) pinned to each of CPUs 0 .. R-1 (R the
# most ranks; mpirun binds rank r to core r), before and after the runs, and the speedup
# that R ranks splitting the work evenly could reach on them at best, R t_fastest /
# t_slowest. Virtual machines' CPUs need not be equal (measured here: one 1.4 times
# slower than the other for tens of minutes), and then no even split reaches R.
# A run that fails ends the benchmark: the rows measured so far (the failed run's from
# what it wrote, its iteration counts from its accepted steps only, marked *) are
# printed, then one line on stderr with clothsim's message, and the exit code is 1. The
# output directory is then kept for its logs. Progress lines go to stderr, the table to
# stdout.
#
# Usage: scripts/benchmark-swing.sh [options]
#   --sizes "N ..."   vertices per side (default "21 41 81 161 321"; a meshes/swing-N.geo
#                     must exist)
#   --end-time T      simulated time, s (default 2, as the scene)
#   --models "M ..."  models to run (default "fem mass-spring"; fem/ms needs both)
#   --ranks "R ..."   MPI ranks per run (default "1"); e.g. "1 2" runs everything on one
#                     rank and under mpirun -np 2, and prints the speedup
#   --params FILE     parameter file (default params/benchmarks/swing.prm; e.g.
#                     params/benchmarks/swing-membrane.prm)
#   --set "S/N=V"     passed to every run (repeatable), e.g. --set "Time/Integrator=bdf2"
#                     --set "Linear solver/Method=cg"; the model is set after them
#   --build DIR       build directory holding clothsim (default build/ of the source tree)
#   --output DIR      where the runs write (DIR/N-<N>/<model>/, with run.log); default a
#                     temporary directory, removed at the end unless --keep is given
#   --keep            keep the temporary output directory (its path is printed)
#   --repeat K        run every N, model and number of ranks K times (default 1), in
#                     passes that alternate them (N by N), and keep each one's fastest
#                     run: a virtual machine's speed drifts by 10 to 30 % over minutes,
#                     which a ratio of two runs taken minutes apart (the speedup) takes
#                     in whole. A line after the table lists every run's wall time.
#   --cpu C           the CPU every one-rank run is pinned to (taskset; default the
#                     first this process may run on: 0, where mpirun puts rank 0, on an
#                     unrestricted machine), or "any" to leave them to the scheduler. A
#                     virtual machine's CPUs can differ in speed (measured here: one 1.45
#                     times slower than the other for an hour), and a one-rank run left
#                     to the scheduler lands on either, so that ratios between sizes or
#                     models (vs_N0, fem/ms) would compare different CPUs.
# Example: scripts/benchmark-swing.sh --sizes "21 41" --end-time 0.2
# Time: at the solver's speed when this was written, N = 81 alone takes about 40 s per
# 0.5 s of simulated time (fem and mass-spring), and the cost per vertex-step grows with N: the defaults
# take long.
set -uo pipefail

repository=$(cd "$(dirname "$0")/.." && pwd)
sizes="21 41 81 161 321"
ranks_list="1"
models="fem mass-spring"
end_time=2
params="$repository/params/benchmarks/swing.prm"
build="$repository/build"
output=""
keep=false
repeat=1
cpu="" # the first CPU this process may run on
overrides=()

usage() {
  sed -n '/^# Usage:/,/^# Time:/p' "$0" | sed 's/^# \{0,1\}//' | sed '$d'
}
die() {
  echo "benchmark-swing: error: $*" >&2
  exit 1
}

while [ $# -gt 0 ]; do
  case "$1" in
    --sizes | --end-time | --ranks | --models | --params | --set | --build | --output | --repeat | --cpu)
      [ $# -ge 2 ] || die "$1 expects a value"
      case "$1" in
        --sizes) sizes=$2 ;;
        --end-time) end_time=$2 ;;
        --ranks) ranks_list=$2 ;;
        --models) models=$2 ;;
        --params) params=$2 ;;
        --set) overrides+=(--set "$2") ;;
        --build) build=$2 ;;
        --output) output=$2 ;;
        --repeat) repeat=$2 ;;
        --cpu) cpu=$2 ;;
      esac
      shift 2
      ;;
    --keep)
      keep=true
      shift
      ;;
    -h | --help)
      usage
      exit 0
      ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done

clothsim="$build/clothsim"
[ -x "$clothsim" ] || die "no clothsim executable in '$build' (build first, or --build DIR)"
[ -f "$params" ] || die "no parameter file '$params'"
params=$(cd "$(dirname "$params")" && pwd)/$(basename "$params")
awk -v t="$end_time" 'BEGIN { exit !(t ~ /^[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?$/ && t > 0) }' ||
  die "--end-time: '$end_time' is not a positive number"
[[ "$repeat" =~ ^[1-9][0-9]*$ ]] || die "--repeat: '$repeat' is not a positive number of runs"
pin=()
if [ "$cpu" != any ]; then
  command -v taskset >/dev/null ||
    die "--cpu: no taskset on the PATH (util-linux) to pin the runs; --cpu any runs them unpinned"
  allowed=$(taskset -cp $$ | sed 's/.*: //')
  [ -n "$cpu" ] || cpu=${allowed%%[-,]*}
  [[ "$cpu" =~ ^[0-9]+$ ]] && taskset -c "$cpu" true 2>/dev/null ||
    die "--cpu: '$cpu' is not a CPU this process may run on ($allowed), or any"
  pin=(taskset -c "$cpu")
fi
for model in $models; do
  [ "$model" = fem ] || [ "$model" = mass-spring ] ||
    die "--models: unknown model '$model' (fem or mass-spring)"
done
[ -n "${models// /}" ] || die "--models: no model given"
sizes=$(tr -s ' \t' '\n' <<<"$sizes" | grep . | sort -n -u | tr '\n' ' ')
sizes=${sizes% }
[ -n "$sizes" ] || die "--sizes: no size given"
for n in $sizes; do
  [[ "$n" =~ ^[0-9]+$ ]] || die "--sizes: '$n' is not a number of vertices"
  [ -f "$repository/meshes/swing-$n.geo" ] ||
    die "--sizes: no mesh meshes/swing-$n.geo (there are:" \
      "$(find "$repository/meshes" -name 'swing-*.geo' | sed 's/.*swing-\([0-9]*\)\.geo/\1/' |
        sort -n | tr '\n' ' '))"
done

ranks_list=$(tr -s ' \t' '\n' <<<"$ranks_list" | grep . | sort -n -u | tr '\n' ' ')
ranks_list=${ranks_list% }
[ -n "$ranks_list" ] || die "--ranks: no number of ranks given"
for r in $ranks_list; do
  [[ "$r" =~ ^[1-9][0-9]*$ ]] || die "--ranks: '$r' is not a positive number of ranks"
done
mpirun=()
if [ "$ranks_list" != "1" ]; then
  command -v mpirun >/dev/null || die "--ranks: no mpirun on the PATH"
  mpirun=(mpirun --oversubscribe)
  [ "$(id -u)" -eq 0 ] && mpirun+=(--allow-run-as-root)
fi

if [ -z "$output" ]; then
  output=$(mktemp -d "${TMPDIR:-/tmp}/benchmark-swing.XXXXXX") || die "cannot create a temporary directory"
  temporary=true
else
  mkdir -p "$output" || die "cannot create the output directory '$output'"
  temporary=false
fi
output=$(cd "$output" && pwd)

# One row per N, model and ranks (the fastest of its --repeat runs), tab-separated: n
# model ranks vertices steps halvings wall newton linear later_wall later_newton status,
# where newton and linear are totals and later_* the wall time and Newton iterations of
# the accepted steps after the first (which holds one-time work: the direct solver's
# analysis). keys: "n model ranks" in the table's order; each one's row and run times.
rows=()
keys=()
declare -A best_row best_wall all_walls

# measure DIR: the row's fields from DIR/run.log and DIR/statistics.csv.
measure() {
  local directory=$1 log="$1/run.log" statistics="$1/statistics.csv"
  local vertices steps wall newton linear halvings done_line later_wall later_newton
  vertices=$(sed -n 's/^  mesh .*: \([0-9]*\) vertices,.*/\1/p' "$log" | head -n 1)
  done_line=$(grep '^done: ' "$log" | tail -n 1)
  if [ -f "$statistics" ]; then
    # steps and wall time from the last row; iterations summed over the accepted steps.
    read -r steps wall newton linear later_wall later_newton < <(awk -F, '
      NR == 1 { for (c = 1; c <= NF; ++c) column[$c] = c; next }
      { steps = $column["step"]; wall = $column["wall_seconds"]
        newton += $column["newton_iterations"]; linear += $column["linear_iterations"]
        if (steps == 1) { first_wall = wall; first_newton = newton } }
      END { print steps + 0, wall + 0, newton + 0, linear + 0, wall - first_wall,
                  newton - first_newton }' "$statistics")
  else
    steps=0 wall=0 newton=0 linear=0 later_wall=0 later_newton=0
  fi
  if [ -n "$done_line" ]; then
    # The run's totals include the iterations of attempts that failed and were halved.
    newton=$(sed -n 's/.*Newton iterations \([0-9]*\) .*/\1/p' <<<"$done_line")
    linear=$(sed -n 's/.*linear iterations \([0-9]*\) .*/\1/p' <<<"$done_line")
    halvings=$(sed -n 's/.*step halvings \([0-9]*\).*/\1/p' <<<"$done_line")
  else
    halvings=$(grep -c 'retrying with dt' "$log")
  fi
  printf '%s\t%s\t%s\t%s\t%s' "${vertices:-0}" "$steps" "$halvings" "$wall" "$newton"
  printf '\t%s\t%s\t%s\n' "$linear" "$later_wall" "$later_newton"
}

print_table() {
  rows=()
  for key in "${keys[@]}"; do
    [ -n "${best_row[$key]:-}" ] && rows+=("${best_row[$key]}")
  done
  [ ${#rows[@]} -gt 0 ] || return 0
  printf '%s\n' "${rows[@]}" | awk -F'\t' -v smallest="${sizes%% *}" '
    # value with the given printf format, or "-" where it is not defined.
    function show(defined, format, value) { return defined ? sprintf(format, value) : "-" }
    { n[NR] = $1; model[NR] = $2; ranks[NR] = $3; vertices[NR] = $4; steps[NR] = $5
      halvings[NR] = $6; wall[NR] = $7; newton[NR] = $8; linear[NR] = $9; status[NR] = $12
      cost[NR] = ($4 > 0 && $5 > 0) ? 1e6 * $7 / ($4 * $5) : 0
      steady[NR] = ($4 > 0 && $5 > 1) ? 1e6 * $10 / ($4 * ($5 - 1)) : 0
      if (steady[NR] > 0 && !(($2, $3) in steady_first)) steady_first[$2, $3] = steady[NR]
      iteration[NR] = $11 > 0 ? $10 / $11 : 0
      if (iteration[NR] > 0) per_iteration[$1, $2, $3] = iteration[NR]
      if (cost[NR] > 0) {
        of[$1, $2, $3] = cost[NR]
        if (!(($2, $3) in first)) first[$2, $3] = cost[NR]
      } }
    END {
      format = "%5s  %-11s %5s %8s %6s %8s %9s %11s %11s %10s %6s %6s %9s %12s %7s %9s  %s\n"
      printf format, "N", "model", "ranks", "vertices", "steps", "halvings", "wall_s",
        "us/vtx-step", "newton/step", "lin/newton", "fem/ms", "vs_N0", "steady_us",
        "steady_vs_N0", "speedup", "it_speedup", "status"
      for (r = 1; r <= NR; ++r) {
        mark = status[r] == "ok" ? "" : "*"
        ms = of[n[r], "mass-spring", ranks[r]]
        one = of[n[r], model[r], 1]
        printf format, n[r], model[r], ranks[r], show(vertices[r] > 0, "%d", vertices[r]),
          steps[r], halvings[r],
          sprintf("%.2f", wall[r]), show(cost[r] > 0, "%.1f", cost[r]),
          show(steps[r] > 0, "%.2f" mark, newton[r] / (steps[r] ? steps[r] : 1)),
          show(newton[r] > 0, "%.2f" mark, linear[r] / (newton[r] ? newton[r] : 1)),
          show(model[r] == "fem" && cost[r] > 0 && ms > 0, "%.2f", cost[r] / (ms ? ms : 1)),
          show(cost[r] > 0, "%.2f",
               cost[r] / (first[model[r], ranks[r]] ? first[model[r], ranks[r]] : 1)),
          show(steady[r] > 0, "%.1f", steady[r]),
          show(steady[r] > 0 && steady_first[model[r], ranks[r]] > 0, "%.2f",
               steady[r] / (steady_first[model[r], ranks[r]] ? steady_first[model[r], ranks[r]] : 1)),
          show(ranks[r] > 1 && cost[r] > 0 && one > 0, "%.2f", one / (cost[r] ? cost[r] : 1)),
          show(ranks[r] > 1 && iteration[r] > 0 && per_iteration[n[r], model[r], 1] > 0,
               "%.2f", per_iteration[n[r], model[r], 1] / (iteration[r] ? iteration[r] : 1)),
          status[r]
      }
      printf "(us/vtx-step: wall time of the time loop per vertex and step; fem/ms: the fem\n"
      printf "cost per vertex-step over the mass-spring one on the same mesh and ranks; vs_N0:\n"
      printf "over the same model'"'"'s at N = %s; steady_*: the same over the steps after the\n", smallest
      printf "first, whose wall time holds one-time work; speedup: one rank'"'"'s wall time over this\n"
      printf "one'"'"'s; it_speedup: the same per Newton iteration after the first step, which\n"
      printf "holds the direct solver'"'"'s analysis; *: a failed run'"'"'s accepted steps only)\n"
    }'
}

finish() {
  if [ "$temporary" = true ] && [ "$keep" = false ] && [ "$1" -eq 0 ]; then
    rm -rf "$output"
  elif [ "$1" -eq 0 ]; then
    echo "runs kept in $output" >&2
  fi
}
trap 'finish 1; echo "benchmark-swing: interrupted; runs kept in $output" >&2; exit 130' INT TERM

# cpu_times: the time loop's wall time of the check run pinned to each CPU (one line).
cpu_times() {
  local cpu times=""
  for ((cpu = 0; cpu < max_ranks; ++cpu)); do
    directory="$output/cpu-check/cpu$cpu"
    mkdir -p "$directory" || die "cannot create '$directory'"
    taskset -c "$cpu" "$clothsim" "$params" --set "Mesh/Mesh file=$repository/meshes/swing-161.msh" \
      --set "Time/End time=0.1" --set "Output/Progress=off" "${overrides[@]}" \
      --set "Model=fem" --output-dir "$directory" >"$directory/run.log" 2>&1 ||
      { echo "the CPU check on CPU $cpu failed; log: $directory/run.log" >&2; return 1; }
    times+="$(awk -F, 'NR == 1 { for (c = 1; c <= NF; ++c) if ($c == "wall_seconds") w = c }
                       NR > 1 { t = $w } END { print t + 0 }' "$directory/statistics.csv") "
  done
  echo "${times% }"
}
max_ranks=$(tr ' ' '\n' <<<"$ranks_list" | sort -n | tail -n 1)
cpu_before=""
if [ "$max_ranks" -gt 1 ]; then
  command -v taskset >/dev/null || die "--ranks: no taskset on the PATH (util-linux)"
  [ "$(nproc --all)" -ge "$max_ranks" ] || die "--ranks: $max_ranks ranks but $(nproc --all) CPUs"
  printf 'CPU check (N = 161, fem, 0.1 s, one rank pinned to each CPU) ... ' >&2
  cpu_before=$(cpu_times) || die "CPU check failed"
  echo "$cpu_before s" >&2
fi


echo "benchmark-swing: $(basename "$params"), end time $end_time s, sizes $sizes${overrides[*]+, ${overrides[*]}}" >&2
for n in $sizes; do
  for ((pass = 1; pass <= repeat; ++pass)); do
    for ranks in $ranks_list; do
      for model in $models; do
        directory="$output/N-$n/$model"
        [ "$ranks" -gt 1 ] && directory="$directory-np$ranks"
        [ "$repeat" -gt 1 ] && directory="$directory/run$pass"
        mkdir -p "$directory" || die "cannot create '$directory'"
        key="$n $model $ranks"
        [ "$pass" -eq 1 ] && keys+=("$key")
        printf 'N = %s, %s, %s rank(s)%s ... ' "$n" "$model" "$ranks" \
          "$([ "$repeat" -gt 1 ] && echo ", run $pass of $repeat")" >&2
        launcher=("${pin[@]}")
        [ "$ranks" -gt 1 ] && launcher=("${mpirun[@]}" -np "$ranks")
        "${launcher[@]}" "$clothsim" "$params" --set "Mesh/Mesh file=$repository/meshes/swing-$n.msh" \
          --set "Time/End time=$end_time" --set "Output/Progress=off" "${overrides[@]}" \
          --set "Model=$model" --output-dir "$directory" >"$directory/run.log" 2>&1
        code=$?
        fields=$(measure "$directory")
        if [ $code -eq 0 ]; then
          status=ok
        else
          reached=$(awk -F, 'NR > 1 { t = $2 } END { print t + 0 }' "$directory/statistics.csv" 2>/dev/null)
          status="FAILED (exit $code, t = ${reached:-0} s)"
        fi
        wall=$(cut -f4 <<<"$fields")
        all_walls[$key]+="${all_walls[$key]:+ }$wall"
        if [ -z "${best_row[$key]:-}" ] || [ $code -ne 0 ] ||
          awk -v a="$wall" -v b="${best_wall[$key]}" 'BEGIN { exit !(a < b) }'; then
          best_row[$key]="$n"$'\t'"$model"$'\t'"$ranks"$'\t'"$fields"$'\t'"$status"
          best_wall[$key]=$wall
        fi
        echo "$status, $wall s" >&2
        if [ $code -ne 0 ]; then
          print_table
          message=$(grep -E '^clothsim: (error|simulation failed|output failed|interrupted)' \
            "$directory/run.log" | tail -n 1)
          die "the run N = $n, $model, $ranks rank(s) failed (exit code $code):" \
            "${message:-no message}; log: $directory/run.log"
        fi
      done
    done
  done
done
print_table
if [ "$repeat" -gt 1 ]; then
  echo "each row is the fastest of $repeat runs; every run's wall_s (slowest over fastest):"
  for key in "${keys[@]}"; do
    read -r n model ranks <<<"$key"
    awk -v times="${all_walls[$key]}" -v what="N = $n, $model, $ranks rank(s)" 'BEGIN {
      k = split(times, t, " "); lo = t[1]; hi = t[1]
      for (i = 2; i <= k; ++i) { if (t[i] < lo) lo = t[i]; if (t[i] > hi) hi = t[i] }
      printf "  %s: %s (%.2f)\n", what, times, (lo > 0 ? hi / lo : 0) }'
  done
fi
# The libraries, with the BLAS' kernels: the factorisation's speed depends on them.
echo "libraries: $("$clothsim" --version | tail -n 1)"
if [ "$cpu" = any ]; then
  echo "one-rank runs: not pinned (--cpu any)"
else
  echo "one-rank runs: pinned to CPU $cpu"
fi
if [ -n "$cpu_before" ]; then
  printf 'CPU check again ... ' >&2
  cpu_after=$(cpu_times) || die "CPU check failed"
  echo "$cpu_after s" >&2
  awk -v before="$cpu_before" -v after="$cpu_after" -v ranks="$max_ranks" 'BEGIN {
    n = split(before, b, " "); split(after, a, " ")
    for (when = 1; when <= 2; ++when) {
      line = ""; fastest = 0; slowest = 0
      for (c = 1; c <= n; ++c) {
        t = when == 1 ? b[c] : a[c]
        line = line sprintf("%scpu%d %.2f s", c > 1 ? ", " : "", c - 1, t)
        if (fastest == 0 || t < fastest) fastest = t
        if (t > slowest) slowest = t
      }
      printf "CPU check %s the runs (N = 161, fem, 0.1 s, one rank pinned to each CPU): %s;\n",
        when == 1 ? "before" : "after", line
      printf "  the slowest took %.2f times the fastest, so %d ranks splitting the work evenly\n",
        slowest / fastest, ranks
      printf "  on these CPUs are at most %.2f times faster than one rank on the fastest\n",
        ranks * fastest / slowest
    } }'
fi
finish 0
