#!/usr/bin/env bash
# Builds montecl and its tests with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan
# (g++, -O1) and runs the CPU, CLI and OpenCL tests under them. UBSan halts on the first report,
# ASan on any memory error, LeakSanitizer on leaks outside third-party libraries
# (host/util/sanitizer_options.cpp). Extra arguments go to ctest (e.g. -L cpu).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
cmake -S . -B build-asan -DMONTECL_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" >/dev/null
cmake --build build-asan -j"$(nproc)" --target montecl montecl_tests
built=$(date +%s)
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" "$@"
echo "sanitize: build $((built - start)) s, tests $(( $(date +%s) - built )) s" >&2
