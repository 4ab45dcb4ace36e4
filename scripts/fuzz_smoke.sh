#!/usr/bin/env bash
# CI's short libFuzzer pass (reads build-asan/, writes build-asan/seeds, smoke/, smoke-*.log): runs
# each loader's harness of the sanitized build (scripts/sanitize.sh builds them with the suite)
# over its seed corpus plus a fixed number of mutated inputs with a fixed seed, so a harness that
# no longer links or a loader that crashes on a seed or a near mutant fails the suite. The long
# runs are scripts/fuzz.sh (docs/fuzzing.md).
# scripts/fuzz_smoke.sh [inputs per loader, default 2000]; builds the harnesses first where
# build-asan lacks them.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-2000}
start=$(date +%s)
[ -x build-asan/fuzz_seeds ] || bash scripts/sanitize.sh build
built=$(date +%s)
rm -rf build-asan/seeds build-asan/smoke
build-asan/fuzz_seeds build-asan/seeds
failed=0
for l in scene obj exr cache ply gltf pbrt mitsuba; do
  mkdir -p "build-asan/smoke/$l"
  # A fresh corpus copy per run: libFuzzer adds new inputs to its first corpus directory.
  cp -r "build-asan/seeds/$l/." "build-asan/smoke/$l/"
  if ! build-asan/fuzz_"$l" -runs="$runs" -seed=1 -timeout=10 -rss_limit_mb=2048 \
      -malloc_limit_mb=2048 -artifact_prefix="build-asan/smoke/$l-" "build-asan/smoke/$l" \
      >"build-asan/smoke-$l.log" 2>&1; then
    echo "fuzz smoke: fuzz_$l failed; log: build-asan/smoke-$l.log" >&2
    tail -30 "build-asan/smoke-$l.log" >&2
    failed=1
  else
    echo "fuzz smoke: fuzz_$l $(grep -E '^#[0-9]+' "build-asan/smoke-$l.log" | tail -1 | cut -c1-80)" >&2
  fi
done
echo "fuzz smoke: build $((built - start)) s, runs $(( $(date +%s) - built )) s" >&2
exit "$failed"
