#!/usr/bin/env bash
# One command on a fresh Debian 12 machine: installs what is missing, builds, and runs the whole
# test suite (doctest through CTest, on PoCL); then builds the suite again with ASan + UBSan
# (build-asan, cmake -DMONTECL_SANITIZE=ON) and runs it there (docs/fuzzing.md says what runs).
# MONTECL_SKIP_SANITIZE=1 skips the sanitizer pass (a quick local run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
if [ "${MONTECL_SKIP_SANITIZE:-0}" != 1 ]; then
  bash scripts/sanitize.sh
fi
