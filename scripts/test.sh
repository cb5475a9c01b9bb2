#!/usr/bin/env bash
# Set-up (scripts/setup.sh), then the whole test suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
# Open MPI refuses to run as root unless told; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd build
# A test without a TIMEOUT of its own fails after 900 s (the longest takes about 90 s; 5
# times that under the sanitizers), so that a hang (say, one MPI rank stopped and the
# other waiting for it) ends in a failure with its output, not in CI's own time limit.
ctest --output-on-failure --timeout 900 -j "$(nproc)"
