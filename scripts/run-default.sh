#!/usr/bin/env bash
# Set-up (scripts/setup.sh), then the default scene: output in output/default/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build/clothsim params/default.prm
