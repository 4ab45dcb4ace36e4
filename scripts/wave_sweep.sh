#!/usr/bin/env bash
# wave_sweep.sh: render time and peak resident memory of `montecl render` over a sweep of wave
# sizes, per integrator (the measurement behind the default wave cap, docs/performance.md "Wave
# size and memory"). Prints a markdown table: integrator, --wave-size (planned: the default, rate-sized
# waves under the cap), render seconds (the summary line's), Mrays/s, peak RSS MiB (/usr/bin/time -v).
# Usage: scripts/wave_sweep.sh [SCENE] [SIZES...]   (env: MONTECL, SPP_AO, SPP_DIRECT, SPP_PATH, REPEAT)
set -euo pipefail
cd "$(dirname "$0")/.."
scene=${1:-../shared/scenes/sponza/scene.json}
shift || true
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(planned 16384 65536 262144 1048576)
montecl=${MONTECL:-build/montecl}
repeat=${REPEAT:-1}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| integrator | spp | wave size | render s | Mrays/s | peak RSS MiB |"
echo "|---|---:|---:|---:|---:|---:|"
for integrator in ao direct path; do
  case $integrator in ao) spp=${SPP_AO:-8} ;; direct) spp=${SPP_DIRECT:-2} ;; path) spp=${SPP_PATH:-1} ;; esac
  for size in "${sizes[@]}"; do
    for ((r = 0; r < repeat; r++)); do
      args=(render "$scene" --integrator "$integrator" --spp "$spp" -q -o "$out/i.pfm")
      [ "$size" = planned ] || args+=(--wave-size "$size")
      /usr/bin/time -v "$montecl" "${args[@]}" >"$out/stdout" 2>"$out/time"
      secs=$(sed -n 's/.*: \([0-9.]*\) s, .*/\1/p' "$out/stdout")
      mrays=$(sed -n 's/.*, \([0-9.]*\) Mrays\/s.*/\1/p' "$out/stdout")
      rss=$(awk '/Maximum resident set size/ {printf "%.0f", $6 / 1024}' "$out/time")
      echo "| $integrator | $spp | $size | $secs | $mrays | $rss |"
    done
  done
done
