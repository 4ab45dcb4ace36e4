#!/usr/bin/env bash
# oclgrind_check.sh: runs `montecl conformance` on tiny images under Oclgrind, the OpenCL device
# simulator, with its API, data-race and uninitialised-value checks (--check-api --data-races
# --uninitialized); fails if Oclgrind reports anything (on stderr) or if the images disagree with
# the host backend. The test suite runs it (tests/test_conformance.cpp).
#
# The kernels are built with -cl-opt-disable (OCLGRIND_BUILD_OPTIONS, part of the program cache
# key): Debian 12's Oclgrind 21.10 aborts on LLVM's `freeze` instruction in optimised kernels under
# --uninitialized. Its uninitialised-value check also keeps the definedness of a released buffer
# for the next buffer given the same slot; montecl therefore creates its kernel-written scratch
# buffers on Oclgrind from one host write of NaN canaries (ClSession::scratch,
# docs/portability.md).
#
# Usage: scripts/oclgrind_check.sh [path/to/montecl [conformance options...]]
#   default executable: build/montecl; further options are passed to `montecl conformance` (the
#   suite adds --json); OCLGRIND_EXTRA adds Oclgrind options.
set -euo pipefail
cd "$(dirname "$0")/.."
exe="${1:-build/montecl}"
[[ $# -gt 0 ]] && shift
command -v oclgrind > /dev/null || { echo "oclgrind not installed (apt-get install oclgrind)" >&2; exit 1; }
export OCLGRIND_BUILD_OPTIONS="${OCLGRIND_BUILD_OPTIONS:--cl-opt-disable}"
err="$(mktemp)"
trap 'rm -f "$err"' EXIT
status=0
oclgrind --check-api --data-races --uninitialized ${OCLGRIND_EXTRA:-} "$exe" conformance \
  --size 4 --spp 2 --cornell-size 4 --cornell-spp 1 "$@" 2> "$err" || status=$?
if [[ -s "$err" ]]; then
  echo "oclgrind reported:" >&2
  cat "$err" >&2
  exit 1
fi
exit "$status"
