#!/usr/bin/env bash
# Runs scripts/render.py with ParaView's pvbatch. Without a display (a server, CI, ssh) it
# starts a virtual X server for the run (Xvfb, Debian package xvfb): Debian's ParaView
# renders through X only (--force-offscreen-rendering aborts without one).
# Usage: scripts/render.sh OUTPUT_DIR [render.py options]   (render.sh --help: the options)
set -euo pipefail
script="$(dirname "$0")/render.py"
if [ -n "${DISPLAY:-}" ]; then
  exec pvbatch "$script" "$@"
fi

# Xvfb picks a free display number itself and reports it (-displayfd): no race with other
# X servers starting at the same time (xvfb-run -a can pick a number that is being taken).
# 24-bit colour; -noreset: pvbatch connects more than once, and a server that resets when
# the first connection closes refuses the next one ("bad X server connection", now and
# then). The pictures are rendered off screen at their own size.
number_file="$(mktemp)"
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -noreset 3>"$number_file" 2>/dev/null &
server=$!
trap 'kill "$server" 2>/dev/null || true; wait "$server" 2>/dev/null || true; rm -f "$number_file"' EXIT
# The number is complete once its line ends (a check between two writes would read part
# of it).
for _ in $(seq 1 300); do
  [ "$(wc -l < "$number_file")" -ge 1 ] && break
  kill -0 "$server" 2>/dev/null || { echo "render.sh: Xvfb did not start" >&2; exit 1; }
  sleep 0.1
done
[ "$(wc -l < "$number_file")" -ge 1 ] ||
  { echo "render.sh: Xvfb gave no display within 30 s" >&2; exit 1; }
DISPLAY=":$(head -n 1 "$number_file")" pvbatch "$script" "$@"
