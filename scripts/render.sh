#!/usr/bin/env bash
# Runs scripts/render.py with ParaView's pvbatch; without a display (a server, CI, ssh)
# under a virtual X server (xvfb-run, Debian package xvfb): Debian's ParaView renders
# through X only. Usage: scripts/render.sh OUTPUT_DIR [render.py options]
set -euo pipefail
script="$(dirname "$0")/render.py"
if [ -n "${DISPLAY:-}" ]; then
  exec pvbatch "$script" "$@"
fi
# 24-bit colour (xvfb-run's default screen has 8); the pictures are rendered off screen
# at their own size.
exec xvfb-run -a -s "-screen 0 1280x1024x24" pvbatch "$script" "$@"
