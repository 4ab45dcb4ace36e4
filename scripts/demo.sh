#!/usr/bin/env bash
# One command on a fresh Debian 12 machine: installs what is missing, builds, and renders the
# bundled demo scene to out/demo.png, printing its path.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
build/montecl render scenes/demo/scene.json -o out/demo.png
echo "$(pwd)/out/demo.png"
