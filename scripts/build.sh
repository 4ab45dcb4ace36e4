#!/usr/bin/env bash
# Configures and builds montecl (Release) into build/. Assumes scripts/setup.sh has run.
# MONTECL_UNITY_BUILD=ON (scripts/test.sh sets it) compiles in batches: a clean build in about half
# the CPU time, for CI where no compiler cache helps.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMONTECL_UNITY_BUILD="${MONTECL_UNITY_BUILD:-OFF}" >/dev/null
cmake --build build -j"$(nproc)"
