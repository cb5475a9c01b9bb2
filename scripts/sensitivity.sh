#!/usr/bin/env bash
# How far ahead a scene is predictable: runs it twice, the second time with its initial
# positions moved by a tiny perturbation (added to the scene's own 'Time/Initial
# displacement'), and prints, per output time, how far the two runs' probes are apart
# (the largest distance over the probes, m), the e-folding rate of that distance since
# the previous row (1/s: ln(d / d_previous) / Δt), and the difference of their total
# energies (J). A distance that grows by orders of magnitude while the perturbation is
# far below any discretisation error means that no scheme, however fine, can pin the
# motion down beyond that time (README, "Folding cloth": the swinging sheet).
# The last lines name the first times the distance exceeds 1 mm and 1 cm.
#
# Usage: scripts/sensitivity.sh [PARAMS] [options]
#   PARAMS                 parameter file (default params/benchmarks/swing.prm)
#   --perturbation "E; E; E"
#                          added to each component of the initial displacement, m, as
#                          expressions of x, y, z (default "0; 0; 1e-8*x*y": at most 10 nm
#                          on the unit square)
#   --set "S/N=V"          passed to both runs (repeatable), e.g. --set "Time/Time step=0.001"
#   --build DIR            build directory holding clothsim (default build/)
#   --output DIR           where the runs write (DIR/reference, DIR/perturbed, each with
#                          run.log); default a temporary directory, removed at the end
#                          unless --keep is given
#   --keep                 keep the temporary output directory (its path is printed)
# Example: scripts/sensitivity.sh --set "Mesh/Mesh file=../../meshes/swing-21.msh"
#            --set "Time/Time step=0.00104166666666666667"
# Time: two runs of the scene.
set -uo pipefail

repository=$(cd "$(dirname "$0")/.." && pwd)
params="$repository/params/benchmarks/swing.prm"
perturbation="0; 0; 1e-8*x*y"
build="$repository/build"
output=""
keep=false
overrides=()

usage() {
  sed -n '/^# Usage:/,/^# Time:/p' "$0" | sed 's/^# \{0,1\}//' | sed '$d'
}
die() {
  echo "sensitivity: error: $*" >&2
  exit 1
}

params_given=false
while [ $# -gt 0 ]; do
  case "$1" in
    --perturbation | --set | --build | --output)
      [ $# -ge 2 ] || die "$1 expects a value"
      case "$1" in
        --perturbation) perturbation=$2 ;;
        --set) overrides+=(--set "$2") ;;
        --build) build=$2 ;;
        --output) output=$2 ;;
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
    -*) die "unknown option '$1' (see --help)" ;;
    *)
      $params_given && die "more than one parameter file given ('$params', '$1')"
      params=$1
      params_given=true
      shift
      ;;
  esac
done

clothsim="$build/clothsim"
[ -x "$clothsim" ] || die "no clothsim executable in '$build' (build first, or --build DIR)"
[ -f "$params" ] || die "no parameter file '$params'"
IFS=';' read -r -a added <<<"$perturbation"
[ ${#added[@]} -eq 3 ] ||
  die "--perturbation: '$perturbation' is not three expressions separated by ';'"

if [ -z "$output" ]; then
  output=$(mktemp -d "${TMPDIR:-/tmp}/clothsim-sensitivity.XXXXXX")
  $keep || trap 'rm -rf "$output"' EXIT
  $keep && echo "sensitivity: output in $output" >&2
fi
mkdir -p "$output" || die "cannot create '$output'"

run() { # name, extra arguments
  local name=$1
  shift
  echo "sensitivity: running the $name scene ..." >&2
  "$clothsim" "$params" "${overrides[@]}" "$@" --output-dir "$output/$name" \
    >"$output/$name.log" 2>&1 || {
    $keep || trap - EXIT
    die "the $name run failed (log: $output/$name.log): $(grep -m1 -i 'error' "$output/$name.log")"
  }
}

run reference
# The scene's own initial displacement, as the reference run expanded it.
own=$(awk '/^ *subsection Time *$/ { inside = 1 } inside && /^ *end *$/ { inside = 0 }
           inside && /set Initial displacement/ { sub(/^[^=]*= */, ""); sub(/ *#.*$/, ""); print; exit }' \
  "$output/reference/parameters.prm")
IFS=';' read -r -a base <<<"${own:-0; 0; 0}"
[ ${#base[@]} -eq 3 ] || die "cannot read the scene's Initial displacement ('$own')"
combined="(${base[0]}) + (${added[0]}); (${base[1]}) + (${added[1]}); (${base[2]}) + (${added[2]})"
run perturbed --set "Time/Initial displacement=$combined"

echo "perturbation: $perturbation (initial displacement $combined)"
awk -F, '
  FNR == 1 { for (i = 1; i <= NF; ++i) column[FILENAME, $i] = i; next }
  FILENAME ~ /statistics/ {
    t = $column[FILENAME, "time"]; e = $column[FILENAME, "total_energy"]
    if (FILENAME ~ /reference/) energy_a[t] = e; else energy_b[t] = e
    next
  }
  {
    t = $column[FILENAME, "time"]; key = t SUBSEP $column[FILENAME, "probe"]
    u = $column[FILENAME, "ux"] SUBSEP $column[FILENAME, "uy"] SUBSEP $column[FILENAME, "uz"]
    if (FILENAME ~ /reference/) { a[key] = u; if (!(t in seen)) { seen[t] = 1; times[n++] = t } }
    else b[key] = u
  }
  END {
    printf "%10s %14s %12s %14s\n", "time_s", "distance_m", "rate_per_s", "energy_diff_J"
    previous_t = ""; previous_d = 0
    for (k = 0; k < n; ++k) {
      t = times[k]; d = 0; found = 0
      for (key in a) {
        split(key, parts, SUBSEP)
        if (parts[1] != t || !(key in b)) continue
        split(a[key], p, SUBSEP); split(b[key], q, SUBSEP)
        s = sqrt((p[1] - q[1])^2 + (p[2] - q[2])^2 + (p[3] - q[3])^2)
        if (s > d) d = s
        found = 1
      }
      if (!found) continue
      rate = sprintf("%12s", "-")
      if (previous_t != "" && previous_d > 0 && d > 0 && t + 0 > previous_t + 0)
        rate = sprintf("%12.1f", log(d / previous_d) / (t - previous_t))
      energy = sprintf("%14s", "-")
      if ((t in energy_a) && (t in energy_b))
        energy = sprintf("%14.3e", energy_b[t] - energy_a[t])
      printf "%10.4f %14.3e %s %s\n", t, d, rate, energy
      if (d > 1e-3 && mm == "") mm = t
      if (d > 1e-2 && cm == "") cm = t
      previous_t = t; previous_d = d
    }
    printf "first beyond 1 mm: %s\n", mm == "" ? "never" : mm " s"
    printf "first beyond 1 cm: %s\n", cm == "" ? "never" : cm " s"
  }' "$output/reference/statistics.csv" "$output/perturbed/statistics.csv" \
  "$output/reference/probes.csv" "$output/perturbed/probes.csv"
