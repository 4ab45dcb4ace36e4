#!/usr/bin/env bash
# Builds the sanitized build with its libFuzzer harnesses (scripts/sanitize.sh build: clang-14,
# ASan + UBSan, build-asan/) and fuzzes every loader in turn, one job each:
# scripts/fuzz.sh [seconds per loader, default 300] [loaders...]
# Corpora grow in build-asan/corpus/<loader> (seeded by fuzz_seeds); crashes, timeouts and
# out-of-memory inputs land in build-asan/findings/<loader>/. Results: docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
loaders=("$@")
[ ${#loaders[@]} -gt 0 ] || loaders=(scene obj exr cache ply gltf pbrt mitsuba)
bash scripts/sanitize.sh build
build-asan/fuzz_seeds build-asan/seeds
for l in "${loaders[@]}"; do
  mkdir -p "build-asan/corpus/$l" "build-asan/findings/$l"
  echo "fuzz: $l for ${seconds} s" >&2
  # -timeout: an input over 10 s is a hang; -rss_limit_mb: over 2 GiB is a finding (allocation
  # before validation). -fork=1 with -ignore_*: one worker process, which goes on after a finding
  # (saved under findings/) instead of stopping the run. The last "#N:" line gives the executions
  # and the oom/timeout/crash counts.
  build-asan/fuzz_"$l" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -artifact_prefix="build-asan/findings/$l/" "build-asan/corpus/$l" "build-asan/seeds/$l" \
    >"build-asan/fuzz-$l.log" 2>&1 || true
  grep -E "^#[0-9]+:" "build-asan/fuzz-$l.log" | tail -1 || true
  ls "build-asan/findings/$l" | head -20
done
