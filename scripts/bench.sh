#!/usr/bin/env bash
# bench.sh: builds montecl if needed, runs `montecl bench` on every shared scene (../shared/scenes,
# or $SCENES_DIR) and writes bench/<scene>.json plus bench/results.md, a Markdown table of
# montecl vs Embree per ray kind with the machine (CPU model, cores, PoCL version).
# Skips with a message (exit 0) when the scenes folder is absent. Exit 1 if any run mismatched.
# The SAH column gives the binned build's cost and its ratio to a full-sweep build's (--sah-reference).
# Then sponza-textured's AO and direct render times against sponza's (bench/textures.md).
# Environment: BUILD_DIR (default build), REPEAT (default 5), DEVICE (--device), THREADS (--threads),
# TEX_SPP (samples of the texture comparison, default 8).
# Whole renders: when Mitsuba 3's venv exists (scripts/setup.sh --mitsuba), also montecl vs Mitsuba 3
# wall times (scripts/vs_mitsuba.py: Cornell box 128x128 direct MIS 1024 spp and path 256 spp, Sponza
# 480x270 direct 64 spp and path 16 spp; medians of REPEAT alternated whole processes) into
# bench/vs_mitsuba-<scene>-<integrator>.json and a second table; VS_MITSUBA=0 skips it.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
scenes=${SCENES_DIR:-../shared/scenes}
out=bench

if [ ! -d "$scenes" ]; then
  echo "bench: no shared scenes at $scenes; skipping (set SCENES_DIR or add ../shared/scenes)"
  exit 0
fi
command -v jq >/dev/null || { echo "bench: jq is needed (run scripts/setup.sh)" >&2; exit 1; }
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)" --target montecl >/dev/null
mkdir -p "$out"

args=(--repeat "${REPEAT:-5}" --sah-reference)
[ -n "${DEVICE:-}" ] && args+=(--device "$DEVICE")
[ -n "${THREADS:-}" ] && args+=(--threads "$THREADS")

status=0
jsons=()
for dir in "$scenes"/*/; do
  name=$(basename "$dir")
  [ -f "$dir/scene.json" ] || { echo "bench: $name: no scene.json, skipped"; continue; }
  echo "bench: $name"
  if "$build/montecl" bench "$dir/scene.json" "${args[@]}" --json "$out/$name.json" -q; then :; else
    rc=$?; echo "bench: $name: exit $rc" >&2; status=1
  fi
  [ -f "$out/$name.json" ] && jsons+=("$out/$name.json")
done
[ ${#jsons[@]} -gt 0 ] || { echo "bench: no scene ran"; exit 1; }

first=${jsons[0]}
cpu=$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')
pocl=$(jq -r '.driver_version' "$first")
platform=$(jq -r '.platform' "$first")
{
  echo "# montecl bench"
  echo
  echo "Machine: $cpu, $(nproc) cores; OpenCL device $(jq -r '.device' "$first") ($(jq -r '.compute_units' "$first") compute units), driver $pocl ($platform); Embree $(jq -r '.embree_version // "n/a"' "$first") on $(jq -r '.threads' "$first") threads. $(date -u +%Y-%m-%d)."
  echo
  echo "Mrays/s from the median of ${REPEAT:-5} timed kernel runs (OpenCL profiling events) after a warm-up; ratio = montecl / Embree Mrays/s (higher is better);"
  echo "build ratio = montecl ms / Embree ms (lower is better). Closest hit (intersect kernel): primary rays and bounce (diffuse bounce: 4 unbounded cosine rays per primary hit, the incoherent continuation rays of path tracing); any hit (intersect_shadow): AO (8 cosine rays per primary hit) and shadow rays."
  echo
  echo "| scene | triangles | BVH ms | Embree build ms | build ratio | nodes | B/tri | SAH (/ full sweep) | kind | rays | Mrays/s (best) | Embree Mrays/s | ratio | mismatches |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|"
  for j in "${jsons[@]}"; do
    jq -r --arg name "$(basename "$j" .json)" '
      . as $r | .rays[] |
      "| \($name) | \($r.triangles) | \($r.bvh.build_ms * 10 | round / 10) | \(($r.embree.build_ms // 0) * 10 | round / 10) | \(($r.build_ratio // 0) * 100 | round / 100) | \($r.bvh.nodes) | \($r.bvh.bytes_per_triangle * 10 | round / 10) | \($r.bvh.sah_cost * 100 | round / 100) (\(($r.bvh.sah_ratio // 0) * 1000 | round / 1000)) | \(.kind) | \(.count) | \(.mrays_per_s * 100 | round / 100) (\(.best_mrays_per_s * 100 | round / 100)) | \((.embree_mrays_per_s // 0) * 100 | round / 100) | \((.ratio // 0) * 100 | round / 100) | \(.mismatches) |"' "$j"
  done
  venv=${MONTECL_MITSUBA_VENV:-$HOME/.cache/montecl/mitsuba-venv}
  if [ "${VS_MITSUBA:-1}" != 0 ] && [ -x "$venv/bin/python" ]; then
    echo
    echo "Whole renders against Mitsuba 3 (scripts/vs_mitsuba.py: whole processes alternated, median of ${REPEAT:-5}; ratio = montecl / Mitsuba wall, lower is better; the target is <= 0.8):"
    echo
    echo "| scene | size | spp | estimator | montecl s (CPU s) | Mitsuba 3 s (CPU s) | Mitsuba variant | ratio |"
    echo "|---|---|---:|---|---:|---:|---|---:|"
    # scene, width, height, spp, integrator: the equal-spp comparisons of the performance page.
    for row in "cornell-box 128 128 1024 direct" "cornell-box 128 128 256 path" \
               "sponza 480 270 64 direct" "sponza 480 270 16 path"; do
      read -r name w h spp integ <<< "$row"
      [ -f "$scenes/$name/scene.json" ] || continue
      echo "bench: $name $integ vs Mitsuba 3 (whole renders)" >&2
      json="$out/vs_mitsuba-$name-$integ.json"
      extra=(--direct-sampling mis)
      [ "$integ" = path ] && extra=(--max-depth -1)
      if "$venv/bin/python" scripts/vs_mitsuba.py "$scenes/$name/scene.json" --montecl "$build/montecl" \
          --width "$w" --height "$h" --spp "$spp" --integrator "$integ" "${extra[@]}" --repeat "${REPEAT:-5}" \
          --no-agreement --json "$json" >&2; then
        jq -r --arg name "$name" '"| \($name) | \(.width)x\(.height) | \(.spp) | \(.integrator) \(.direct_sampling // "") | \(.montecl_wall_s * 100 | round / 100) (\(.montecl_cpu_s * 100 | round / 100)) | \(.mitsuba_wall_s * 100 | round / 100) (\(.mitsuba_cpu_s * 100 | round / 100)) | \(.mitsuba_variant) | \(.wall_ratio * 100 | round / 100) |"' "$json"
      else
        echo "bench: vs_mitsuba.py failed on $name $integ" >&2; status=1
      fi
    done
  fi
} > "$out/results.md.tmp"
mv "$out/results.md.tmp" "$out/results.md"
cat "$out/results.md"

# Textures: sponza-textured against the untextured sponza (same triangles, camera and lights) at
# the same settings, AO and direct, best of 3 alternated runs: the wave loop's time ("wrote ...:
# N s") and the whole process's wall time (texture loading included) -> bench/textures.md.
tex_spp=${TEX_SPP:-8}
if [ -f "$scenes/sponza/scene.json" ] && [ -f "$scenes/sponza-textured/scene.json" ]; then
  declare -A best_render best_wall
  for run in 1 2 3; do
    for name in sponza sponza-textured; do
      for integ in ao direct; do
        t0=$(date +%s.%N)
        line=$("$build/montecl" render "$scenes/$name/scene.json" -o "$out/tex.png" --overwrite -q \
               --spp "$tex_spp" --integrator "$integ" ${DEVICE:+--device "$DEVICE"} 2>&1 | grep '^wrote')
        wall=$(echo "$(date +%s.%N) - $t0" | bc)
        render=$(echo "$line" | sed -E 's/.*spp: ([0-9.]+) s.*/\1/')
        key="$name/$integ"
        if [ -z "${best_render[$key]:-}" ] || [ "$(echo "$render < ${best_render[$key]}" | bc)" = 1 ]; then best_render[$key]=$render; fi
        if [ -z "${best_wall[$key]:-}" ] || [ "$(echo "$wall < ${best_wall[$key]}" | bc)" = 1 ]; then best_wall[$key]=$wall; fi
      done
    done
  done
  rm -f "$out/tex.png"
  {
    echo "# Textures: sponza-textured vs sponza ($tex_spp spp, the scenes' camera, best of 3)"
    echo
    echo "| integrator | sponza render s | textured render s | ratio | sponza wall s | textured wall s | ratio |"
    echo "|---|---:|---:|---:|---:|---:|---:|"
    for integ in ao direct; do
      a=${best_render[sponza/$integ]}; b=${best_render[sponza-textured/$integ]}
      c=${best_wall[sponza/$integ]}; d=${best_wall[sponza-textured/$integ]}
      printf '| %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n' "$integ" "$a" "$b" "$(echo "$b / $a" | bc -l)" \
        "$c" "$d" "$(echo "$d / $c" | bc -l)"
    done
  } > "$out/textures.md"
  cat "$out/textures.md"
fi
exit $status
