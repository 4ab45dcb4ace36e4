#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang-14, ASan + UBSan, build-fuzz/) and fuzzes every loader in
# turn, one job each: scripts/fuzz.sh [seconds per loader, default 300] [loaders...]
# Corpora grow in build-fuzz/corpus/<loader> (seeded by fuzz_seeds); crashes, timeouts and
# out-of-memory inputs land in build-fuzz/findings/<loader>/. Results: docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --fuzz
seconds=${1:-300}
shift || true
loaders=("$@")
[ ${#loaders[@]} -gt 0 ] || loaders=(scene obj exr cache ply gltf)
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DMONTECL_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz
build-fuzz/fuzz_seeds build-fuzz/seeds
for l in "${loaders[@]}"; do
  mkdir -p "build-fuzz/corpus/$l" "build-fuzz/findings/$l"
  echo "fuzz: $l for ${seconds} s" >&2
  # -timeout: an input over 10 s is a hang; -rss_limit_mb: over 2 GiB is a finding (allocation
  # before validation). -fork=1 with -ignore_*: one worker process, which goes on after a finding
  # (saved under findings/) instead of stopping the run. The last "#N:" line gives the executions
  # and the oom/timeout/crash counts.
  build-fuzz/fuzz_"$l" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
    -artifact_prefix="build-fuzz/findings/$l/" "build-fuzz/corpus/$l" "build-fuzz/seeds/$l" \
    >"build-fuzz/fuzz-$l.log" 2>&1 || true
  grep -E "^#[0-9]+:" "build-fuzz/fuzz-$l.log" | tail -1 || true
  ls "build-fuzz/findings/$l" | head -20
done
