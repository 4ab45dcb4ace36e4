#!/usr/bin/env bash
# Configures one build folder (reads CMakeLists.txt, writes DIR/): scripts/configure.sh DIR [cmake -D...].
# The one place that picks the generator and the batching for every script that builds:
# Ninja where the folder is new (its compiles of a target start while the libraries it links are
# still being built, so both cores stay busy; a folder configured before keeps its generator) and
# MONTECL_UNITY_BUILD (ON in scripts/test.sh: batched compiles, half the CPU of a clean build).
set -euo pipefail
cd "$(dirname "$0")/.."
dir=$1
shift
generator=()
if [ ! -f "$dir/CMakeCache.txt" ] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S . -B "$dir" "${generator[@]}" -DMONTECL_UNITY_BUILD="${MONTECL_UNITY_BUILD:-OFF}" "$@" >/dev/null
