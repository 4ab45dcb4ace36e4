#!/usr/bin/env bash
# Installs what the plot needs, builds, and runs scripts/convergence.py (docs/images/convergence.png).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --plots
bash scripts/build.sh
/usr/bin/python3 scripts/convergence.py "$@"
