#!/usr/bin/env bash
# Renders a fixed set of scenes x integrators with one montecl binary into a folder of PFMs, or
# compares two such folders byte for byte: refactors that must not change an image are checked
# with it (golden.sh render BIN DIR; golden.sh compare DIR_A DIR_B). MONTECL_GOLDEN_ARGS: options
# added to every render (e.g. --error-estimate, to compare with a set made before the default
# sobol render dropped its sub-sequences).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
shared="$here/../shared/scenes"
case "$1" in
  render)
    bin="$2"; out="$3"; mkdir -p "$out"
    read -r -a extra <<<"${MONTECL_GOLDEN_ARGS:-}"
    scenes=("$here/scenes/demo/scene.json" "$here/scenes/envgloss/scene.json")
    for s in cornell-box/scene.json sponza-textured/scene.json; do
      [ -f "$shared/$s" ] && scenes+=("$shared/$s")
    done
    for dev in host portable; do
      for s in "${scenes[@]}"; do
        name="$(basename "$(dirname "$s")")"
        for cfg in "ao:--integrator ao --ao-sampling cosine" "aou:--integrator ao --ao-sampling uniform --ao-distance 0.3" \
                   "light:--integrator direct --direct-sampling light --light-samples 2" \
                   "brdf:--integrator direct --direct-sampling brdf" "mis:--integrator direct --direct-sampling mis" \
                   "path:--integrator path --max-depth 5 --rr-depth 2" "path1:--integrator path --max-depth -1"; do
          tag="${cfg%%:*}"; opts="${cfg#*:}"
          # shellcheck disable=SC2086
          "$bin" render "$s" -q --device "$dev" --width 48 --height 32 --spp 4 --seed 7 $opts \
            "${extra[@]}" -o "$out/$dev-$name-$tag.pfm" --overwrite
        done
        "$bin" render "$s" -q --device "$dev" --width 40 --height 24 --spp 3 --integrator path --aov all \
          "${extra[@]}" -o "$out/$dev-$name-aov.exr" --overwrite
      done
    done ;;
  compare)
    a="$2"; b="$3"; bad=0; n=0
    for f in "$a"/*.pfm; do
      n=$((n + 1))
      if ! cmp -s "$f" "$b/$(basename "$f")"; then echo "DIFFERS: $(basename "$f")"; bad=1; fi
    done
    for f in "$a"/*.exr; do
      n=$((n + 1))
      idiff -q -fail 0 -failpercent 0 "$f" "$b/$(basename "$f")" >/dev/null 2>&1 || { echo "DIFFERS: $(basename "$f")"; bad=1; }
    done
    echo "compared $n images"; exit $bad ;;
esac
