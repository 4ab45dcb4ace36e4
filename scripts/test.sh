#!/usr/bin/env bash
# One command on a fresh Debian 12 machine: installs what is missing, builds, and runs the whole
# test suite (doctest through CTest, on PoCL); then builds the suite again with ASan + UBSan
# (build-asan, cmake -DMONTECL_SANITIZE=ON) and runs it there (docs/fuzzing.md says what runs).
# Then builds the libFuzzer harnesses (clang-14, build-fuzz) and runs each loader's harness for a
# short fixed number of inputs (scripts/fuzz_smoke.sh), so a harness that stops linking fails CI.
# MONTECL_SKIP_SANITIZE=1 skips the sanitizer pass and MONTECL_SKIP_FUZZ=1 the fuzz pass (a quick
# local run). Also installs Intel's CPU
# OpenCL runtime (setup.sh --intel-opencl: a cached venv, about 270 MB from PyPI once), so the
# conformance tests run on two OpenCL implementations plus Oclgrind; where that install fails (no
# PyPI, not x86-64) its test skips with the reason. MONTECL_NO_INTEL_OPENCL=1 does not install it.
# Mitsuba 3 likewise (setup.sh --mitsuba), so the comparisons with an independent renderer run, and
# Open Image Denoise (setup.sh --oidn), so the --denoise tests run (MONTECL_NO_OIDN=1: not installed).
set -euo pipefail
cd "$(dirname "$0")/.."
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
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
if [ "${MONTECL_SKIP_SANITIZE:-0}" != 1 ]; then
  bash scripts/sanitize.sh
fi
if [ "${MONTECL_SKIP_FUZZ:-0}" != 1 ]; then
  bash scripts/fuzz_smoke.sh
fi
