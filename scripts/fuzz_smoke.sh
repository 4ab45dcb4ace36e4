#!/usr/bin/env bash
# CI's short libFuzzer pass: builds the harnesses (clang-14, ASan + UBSan, build-fuzz/) and runs
# each loader's harness over its seed corpus plus a fixed number of mutated inputs with a fixed
# seed, so a harness that no longer links or a loader that crashes on a seed or a near mutant
# fails the suite. The long runs are scripts/fuzz.sh (docs/fuzzing.md).
# scripts/fuzz_smoke.sh [inputs per loader, default 2000]; MONTECL_UNITY_BUILD=ON as in build.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh --fuzz
runs=${1:-2000}
start=$(date +%s)
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DMONTECL_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DMONTECL_UNITY_BUILD="${MONTECL_UNITY_BUILD:-OFF}" >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz >/dev/null
built=$(date +%s)
rm -rf build-fuzz/seeds build-fuzz/smoke
build-fuzz/fuzz_seeds build-fuzz/seeds
failed=0
for l in scene obj exr cache ply gltf; do
  mkdir -p "build-fuzz/smoke/$l"
  # A fresh corpus copy per run: libFuzzer adds new inputs to its first corpus directory.
  cp -r "build-fuzz/seeds/$l/." "build-fuzz/smoke/$l/"
  if ! build-fuzz/fuzz_"$l" -runs="$runs" -seed=1 -timeout=10 -rss_limit_mb=2048 \
      -malloc_limit_mb=2048 -artifact_prefix="build-fuzz/smoke/$l-" "build-fuzz/smoke/$l" \
      >"build-fuzz/smoke-$l.log" 2>&1; then
    echo "fuzz smoke: fuzz_$l failed; log: build-fuzz/smoke-$l.log" >&2
    tail -30 "build-fuzz/smoke-$l.log" >&2
    failed=1
  else
    echo "fuzz smoke: fuzz_$l $(grep -E '^#[0-9]+' "build-fuzz/smoke-$l.log" | tail -1 | cut -c1-80)" >&2
  fi
done
echo "fuzz smoke: build $((built - start)) s, runs $(( $(date +%s) - built )) s" >&2
exit "$failed"
