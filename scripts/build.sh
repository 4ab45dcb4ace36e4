#!/usr/bin/env bash
# Configures and builds montecl and its tests (Release) into build/. Assumes scripts/setup.sh has run.
# scripts/build.sh [targets...] (default: all). MONTECL_UNITY_BUILD=ON (scripts/test.sh sets it)
# compiles in batches: a clean build in about half the CPU time, for CI where no compiler cache helps.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/configure.sh build -DCMAKE_BUILD_TYPE=Release
targets=()
for t in "$@"; do targets+=(--target "$t"); done
cmake --build build -j"$(nproc)" "${targets[@]}"
