#!/usr/bin/env bash
# One command on a fresh Debian 12 machine (CI: .ci/run): installs what is missing, builds (Release,
# build/) and runs the whole test suite (doctest through CTest, on PoCL). Then the sanitized build
# (scripts/sanitize.sh: clang-14, ASan + UBSan, build-asan/, which also links the libFuzzer
# harnesses) runs the `cpu` and `sanitize` cases (the host-code cases: loaders, images, checkpoints,
# merge, the command line), and each loader's harness runs a short fixed number of inputs
# (scripts/fuzz_smoke.sh), so a harness that stops linking fails CI. docs/testing.md says what runs
# where and when to run the full sanitized suite (scripts/sanitize.sh --all).
# MONTECL_SKIP_SANITIZE=1 skips the sanitized build, its tests and the fuzz runs (a quick local run).
# Also installs Intel's CPU
# OpenCL runtime (setup.sh --intel-opencl: a cached venv, about 270 MB from PyPI once), so the
# conformance tests run on two OpenCL implementations plus Oclgrind; where that install fails (no
# PyPI, not x86-64) its test skips with the reason. MONTECL_NO_INTEL_OPENCL=1 does not install it.
# Mitsuba 3 likewise (setup.sh --mitsuba), so the comparisons with an independent renderer run, and
# Open Image Denoise (setup.sh --oidn), so the --denoise tests run (MONTECL_NO_OIDN=1: not installed).
set -euo pipefail
cd "$(dirname "$0")/.."
# Each step's wall time and the CPU time of its processes (bash's `times`: user + system of the
# waited-for children), printed as each step ends and as a table on exit: on a shared machine wall
# time is noisy, CPU time much less.
steps=()
mark_wall=$SECONDS
mark_cpu=0
cpu_so_far() {
  awk 'NR == 2 { n = split($0, f, /[ ms]+/); s = 0; for (i = 1; i + 1 <= n; i += 2) s += f[i] * 60 + f[i + 1]; print int(s + 0.5) }' "$times_file"
}
step_done() {
  local cpu
  times >"$times_file"  # not in a subshell: that one's children are not these
  cpu=$(cpu_so_far)
  steps+=("$(printf '%-22s %6d s wall %6d s cpu' "$1" $((SECONDS - mark_wall)) $((cpu - mark_cpu)))")
  echo "test: ${steps[-1]}" >&2
  mark_wall=$SECONDS
  mark_cpu=$cpu
}
# A clean checkout has no compiler cache: batched (unity) compiles halve the builds' CPU time.
export MONTECL_UNITY_BUILD=${MONTECL_UNITY_BUILD:-ON}
times_file=$(mktemp)
trap 'rm -f "$times_file"; [ ${#steps[@]} = 0 ] || printf "test: %s\n" "steps so far:" "${steps[@]}" >&2' EXIT
bash scripts/setup.sh
if [ "${MONTECL_NO_INTEL_OPENCL:-0}" != 1 ]; then
  bash scripts/setup.sh --intel-opencl ||
    echo "test: Intel's CPU OpenCL runtime could not be installed; its conformance test will skip" >&2
fi
# Mitsuba 3 (PyPI, a cached venv): the independent renderer the vs_mitsuba tests compare with;
# where the install fails those tests skip with the reason. MONTECL_NO_MITSUBA=1 does not install it.
if [ "${MONTECL_NO_MITSUBA:-0}" != 1 ]; then
  bash scripts/setup.sh --mitsuba ||
    echo "test: Mitsuba 3 could not be installed; the vs_mitsuba tests will skip" >&2
fi
# Open Image Denoise (PyPI pyoidn, a cached venv) for `render --denoise`; where the install fails the
# denoise tests skip with the reason.
if [ "${MONTECL_NO_OIDN:-0}" != 1 ]; then
  bash scripts/setup.sh --oidn ||
    echo "test: Open Image Denoise could not be installed; the denoise tests will skip" >&2
fi
step_done setup
bash scripts/build.sh
step_done build
ctest --test-dir build --output-on-failure -j"$(nproc)"
step_done tests
if [ "${MONTECL_SKIP_SANITIZE:-0}" != 1 ]; then
  bash scripts/sanitize.sh build
  step_done "sanitized build"
  bash scripts/sanitize.sh test
  step_done "sanitized tests"
  bash scripts/fuzz_smoke.sh
  step_done "fuzz runs"
fi
