#!/usr/bin/env bash
# bench_scaling.sh: generates seeded terrains of increasing triangle count (`montecl generate
# terrain`), benchmarks each and writes bench/scaling.md: BVH build time (montecl and Embree),
# peak RSS of the bench process, BVH bytes, Mrays/s per ray kind for montecl and Embree.
# Environment: BUILD_DIR (default build), COUNTS (default "1000 10000 100000 1000000"),
# WIDTH/HEIGHT of the primary ray grid (default 512x512), REPEAT (default 3).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
counts=${COUNTS:-"1000 10000 100000 1000000"}
out=bench
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
command -v jq >/dev/null || { echo "bench_scaling: jq is needed (run scripts/setup.sh)" >&2; exit 1; }
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)" --target montecl >/dev/null
mkdir -p "$out"
status=0
rows=()
for n in $counts; do
  echo "bench_scaling: $n triangles"
  "$build/montecl" generate terrain --triangles "$n" -o "$work/terrain.obj" --scene "$work/terrain.json" \
    --width "${WIDTH:-512}" --height "${HEIGHT:-512}" >/dev/null
  if ! "$build/montecl" bench "$work/terrain.json" --repeat "${REPEAT:-3}" --json "$out/scaling-$n.json" -q >/dev/null; then
    echo "bench_scaling: $n: mismatches or failure" >&2; status=1
  fi
  rows+=("$(jq -r --arg n "$n" '
    def r2: . * 100 | round / 100; def r1: . * 10 | round / 10;
    def k($kind): (.rays[] | select(.kind == $kind));
    "| \($n) | \(.bvh.build_ms | r1) | \((.embree.build_ms // 0) | r1) | \(.peak_rss_mb | r1) | \(.bvh.bytes / 1048576 | r1) | \(.bvh.sah_cost | r2) | \(k("primary").mrays_per_s | r2) / \((k("primary").embree_mrays_per_s // 0) | r2) | \(k("ao").mrays_per_s | r2) / \((k("ao").embree_mrays_per_s // 0) | r2) | \(k("shadow").mrays_per_s | r2) / \((k("shadow").embree_mrays_per_s // 0) | r2) | \([.rays[].mismatches] | add) |"' "$out/scaling-$n.json")")
  rm -f "$work"/terrain*
done
first=$(ls "$out"/scaling-*.json | head -1)
{
  echo "# montecl scaling (generated terrain)"
  echo
  echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), $(nproc) cores; $(jq -r '.device' "$first"), driver $(jq -r '.driver_version' "$first"); Embree $(jq -r '.embree_version // "n/a"' "$first") on $(jq -r '.threads' "$first") threads. ${WIDTH:-512}x${HEIGHT:-512} primary rays, 8 AO rays per hit, 1 shadow ray per hit; median of ${REPEAT:-3} runs. $(date -u +%Y-%m-%d)."
  echo
  echo "Peak RSS is the whole bench process (scene, BVH, Embree scene, ray sets, OpenCL buffers)."
  echo
  echo "| triangles | BVH build ms | Embree build ms | peak RSS MiB | BVH MiB | SAH | primary Mrays/s montecl / Embree | AO | shadow | mismatches |"
  echo "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  printf '%s\n' "${rows[@]}"
} > "$out/scaling.md.tmp"
mv "$out/scaling.md.tmp" "$out/scaling.md"
cat "$out/scaling.md"
exit $status
