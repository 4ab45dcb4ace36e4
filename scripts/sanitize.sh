#!/usr/bin/env bash
# Builds montecl and its tests with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan
# (g++, -O1) and runs the CPU, CLI and OpenCL tests under them. UBSan halts on the first report,
# ASan on any memory error, LeakSanitizer on leaks outside third-party libraries
# (host/util/sanitizer_options.cpp). Tests labelled `uninstrumented` are left out here: their time
# is spent in code the sanitizers do not instrument (Oclgrind, Mitsuba 3) and their host paths run in
# other cases; they run in the normal pass (docs/testing.md lists them). MONTECL_UNITY_BUILD=ON as
# in scripts/build.sh.
# scripts/sanitize.sh [build|test] [ctest arguments, e.g. -L cpu]: `build` only builds, `test`
# only runs the tests of the existing build-asan; without either it does both.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=all
case "${1:-}" in build | test) mode=$1; shift ;; esac
start=$(date +%s)
if [ "$mode" != test ]; then
  cmake -S . -B build-asan -DMONTECL_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" -DMONTECL_UNITY_BUILD="${MONTECL_UNITY_BUILD:-OFF}" >/dev/null
  cmake --build build-asan -j"$(nproc)" --target montecl montecl_tests
fi
built=$(date +%s)
if [ "$mode" != build ]; then
  ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -LE uninstrumented "$@"
fi
echo "sanitize: build $((built - start)) s, tests $(( $(date +%s) - built )) s" >&2
