#!/usr/bin/env bash
# The sanitized build (reads the tree, writes build-asan/): clang-14 with ASan + UBSan, -O1 -g1,
# also instrumented for libFuzzer, so the same build holds montecl, montecl_tests and the fuzz
# harnesses (fuzz_<loader>, fuzz_seeds; scripts/fuzz_smoke.sh and scripts/fuzz.sh run them). UBSan
# halts on the first report, ASan on any memory error, LeakSanitizer on leaks outside third-party
# libraries (host/util/sanitizer_options.cpp).
# scripts/sanitize.sh [build|test] [--all] [ctest arguments]: `build` only builds, `test` only runs
# the tests of the existing build-asan; without either it does both. The tests run by default
# (CI) are the `cpu` cases and the `sanitize` ones (loader, image, checkpoint, merge, MPI and
# command-line cases whose work is host code); `--all` runs every case but the `uninstrumented` ones
# (as CI did before: the g++ build took 395 s for it; docs/testing.md says when). MONTECL_UNITY_BUILD as in
# scripts/configure.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
mode=all
case "${1:-}" in build | test) mode=$1; shift ;; esac
select=(-L '^(cpu|sanitize)$')
if [ "${1:-}" = --all ]; then select=(); shift; fi
start=$(date +%s)
if [ "$mode" != test ]; then
  CC=clang-14 CXX=clang++-14 bash scripts/configure.sh build-asan -DMONTECL_SANITIZE=ON \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1"
  cmake --build build-asan -j"$(nproc)" --target montecl montecl_tests fuzz
fi
built=$(date +%s)
if [ "$mode" != build ]; then
  ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -LE uninstrumented "${select[@]}" "$@"
fi
echo "sanitize: build $((built - start)) s, tests $(( $(date +%s) - built )) s" >&2
