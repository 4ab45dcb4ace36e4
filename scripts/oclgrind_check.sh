#!/usr/bin/env bash
# oclgrind_check.sh: runs `montecl conformance` on tiny images under Oclgrind, the OpenCL device
# simulator, with its API and data-race checks; fails if Oclgrind reports anything (on stderr) or
# if the images disagree with the host backend. --uninitialized is not used by default: Debian 12's
# Oclgrind 21.10 aborts on LLVM's `freeze` instruction, and with OCLGRIND_BUILD_OPTIONS=-cl-opt-disable
# it reports float3's undefined fourth lane (jrprice/Oclgrind#126); OCLGRIND_EXTRA="--uninitialized"
# adds it anyway.
# Usage: scripts/oclgrind_check.sh [path/to/montecl]   (default: build/montecl)
set -euo pipefail
cd "$(dirname "$0")/.."
exe="${1:-build/montecl}"
command -v oclgrind > /dev/null || { echo "oclgrind not installed (apt-get install oclgrind)" >&2; exit 1; }
err="$(mktemp)"
trap 'rm -f "$err"' EXIT
status=0
oclgrind --check-api --data-races ${OCLGRIND_EXTRA:-} "$exe" conformance \
  --size 4 --spp 2 --cornell-size 4 --cornell-spp 1 2> "$err" || status=$?
if [[ -s "$err" ]]; then
  echo "oclgrind reported:" >&2
  cat "$err" >&2
  exit 1
fi
exit "$status"
