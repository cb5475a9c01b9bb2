#!/usr/bin/env bash
# Cost of self-contact (issue 17): each scene as shipped (Contact/Self contact = true)
# against the same scene without self-contact, for the same simulated time, all measured in
# this one invocation (compare the ratios, not the absolute times of different machines).
# Runs one simulation at a time. Without self-contact the cloth passes through itself, and
# Newton may fail later on: the default end time 0.5 s is the strip pile's stretch that
# both runs complete.
#
# Prints one table (progress on stderr, the table on stdout). Per run:
#   steps, halvings   time steps taken and step halvings ("done:" line of the run)
#   wall_s            the run's wall time
#   newton/step       Newton iterations per step, failed attempts included
#   broad%, barrier%, ccd%, gather%, report%
#                     the shares of the run's wall time in self-contact's phases ("self
#                     contact phases:" line of the run): the near-pair list's checks and
#                     rebuilds; the pairs' barrier in the energy, gradient and tangent;
#                     the CCD cap of Newton's line search; gathering positions across
#                     ranks; the statistics' distance report
#   cap%              the share of the timer's "line search: step cap" (all terms' caps:
#                     self-contact's CCD, the obstacles', the bending tilts')
#   x_off             wall time and Newton iterations per step against the run without
#                     self-contact (the issue's target: less than 3x on the pile, and the
#                     CCD below a third of the step)
# A failed run is marked FAILED, the others still run, the output directory is kept and
# the exit code is 1.
#
# Usage: scripts/benchmark-self-contact.sh [options]
#   --scenes "S ..."    scenes in params/contact/ (default "strip-pile")
#   --end-time T        simulated time, s (default 0.5)
#   --set "S/N=V"       passed to every run (repeatable)
#   --output DIR        where the runs write (DIR/<scene>-<on|off>/, run.log); default a
#                       temporary directory, removed at the end unless --keep
#   --keep              keep the temporary output directory
#   CLOTHSIM=path       the executable (default build/clothsim of the source tree)
# Example: scripts/benchmark-self-contact.sh --scenes "strip-pile sheet-folds"
# Time (one core): the strip pile's 0.5 s about 3 s with self-contact and 1 s without.
set -euo pipefail

repository=$(cd "$(dirname "$0")/.." && pwd)
clothsim=${CLOTHSIM:-$repository/build/clothsim}
scenes="strip-pile"
end_time=0.5
output=""
keep=false
overrides=()

die() {
  echo "benchmark-self-contact: error: $*" >&2
  exit 1
}
while [ $# -gt 0 ]; do
  case "$1" in
    --scenes | --end-time | --set | --output)
      [ $# -ge 2 ] || die "$1 expects a value"
      case "$1" in
        --scenes) scenes=$2 ;;
        --end-time) end_time=$2 ;;
        --set) overrides+=(--set "$2") ;;
        --output) output=$2 ;;
      esac
      shift 2
      ;;
    --keep) keep=true && shift ;;
    -h | --help) sed -n '/^# Usage:/,/^# Example:/p' "$0" | sed 's/^# \{0,1\}//' && exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done
[ -x "$clothsim" ] || die "no executable '$clothsim' (build first, or set CLOTHSIM)"
for scene in $scenes; do
  [ -f "$repository/params/contact/$scene.prm" ] || die "--scenes: no params/contact/$scene.prm"
done
if [ -z "$output" ]; then
  output=$(mktemp -d "${TMPDIR:-/tmp}/benchmark-self-contact.XXXXXX")
  temporary=true
else
  mkdir -p "$output" && output=$(cd "$output" && pwd)
  temporary=false
fi

# measure DIR: "steps halvings wall newton broad barrier ccd gather report cap status".
measure() {
  local log="$1/run.log" done_line
  done_line=$(grep '^done: ' "$log" | tail -n 1 || true)
  if [ -z "$done_line" ]; then
    echo "0 0 0 0 0 0 0 0 0 0 FAILED"
    return
  fi
  sed 's/^done: \([0-9]*\) steps in \([0-9.e+-]*\) s; Newton iterations \([0-9]*\) .*step halvings \([0-9]*\).*/\1 \4 \2 \3/' \
    <<<"$done_line" | tr '\n' ' '
  # "self contact phases: broad phase 0.1 s, barrier 0.5 s, CCD 0.2 s, gather ..."
  sed -n 's/^self contact phases: //p' "$log" | tr ',' '\n' | awk '
    { v[$1] = $(NF - 1) }
    END { printf "%s %s %s %s %s ", v["broad"] + 0, v["barrier"] + 0, v["CCD"] + 0,
          v["gather"] + 0, v["report"] + 0 }'
  # The timer table's row "| line search: step cap |  calls |  1.23s |  8.6% |".
  awk -F'|' '$2 ~ /line search: step cap/ { s = $4; sub(/s *$/, "", s); t = s + 0 }
    END { printf "%s ", t + 0 }' "$log"
  echo ok
}

rows=()
failed=false
echo "benchmark-self-contact: $clothsim, end time $end_time s, scenes $scenes" >&2
for scene in $scenes; do
  for self in on off; do
    directory="$output/$scene-$self"
    mkdir -p "$directory"
    printf '%s, self-contact %s ... ' "$scene" "$self" >&2
    [ "$self" = on ] && value=true || value=false
    "$clothsim" "$repository/params/contact/$scene.prm" --set "Time/End time=$end_time" \
      --set "Output/Write VTK=false" --set "Output/Progress=off" \
      --set "Contact/Self contact=$value" ${overrides[@]+"${overrides[@]}"} \
      --output-dir "$directory" >"$directory/run.log" 2>&1 || failed=true
    row="$scene $self $(measure "$directory")"
    [ "${row##* }" = ok ] || failed=true
    rows+=("$row")
    echo "$(cut -d' ' -f13 <<<"$row"), $(cut -d' ' -f5 <<<"$row") s" >&2
  done
done

printf '%s\n' "${rows[@]}" | awk '
  function pct(a, w) { return w > 0 ? sprintf("%.1f", 100 * a / w) : "-" }
  function r(a, b) { return b > 0 ? sprintf("%.2f", a / b) : "-" }
  { line[NR] = $0; wall[$1, $2] = $5; nps[$1, $2] = $3 ? $6 / $3 : 0 }
  END {
    f = "%-14s %4s %5s %4s %8s %7s %7s %8s %6s %7s %7s %6s %7s %7s  %s\n"
    printf f, "scene", "self", "steps", "halv", "wall_s", "newton/", "broad%", "barrier%",
      "ccd%", "gather%", "report%", "cap%", "wall", "newton/", "status"
    printf f, "", "", "", "", "", "step", "", "", "", "", "", "", "x_off", "x_off", ""
    for (i = 1; i <= NR; ++i) {
      split(line[i], v, " "); w = v[5]
      printf f, v[1], v[2], v[3], v[4], sprintf("%.2f", w), sprintf("%.2f", nps[v[1], v[2]]),
        pct(v[7], w), pct(v[8], w), pct(v[9], w), pct(v[10], w), pct(v[11], w), pct(v[12], w),
        r(w, wall[v[1], "off"]), r(nps[v[1], v[2]], nps[v[1], "off"]), v[13]
    }
  }'

if [ "$failed" = true ]; then
  echo "benchmark-self-contact: a run failed; runs kept in $output" >&2
  exit 1
elif [ "$temporary" = true ] && [ "$keep" = false ]; then
  rm -rf "$output"
else
  echo "runs kept in $output" >&2
fi
