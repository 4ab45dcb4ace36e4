#!/usr/bin/env bash
# Writes a scene of 10,000 instances of the Stanford bunny (one scene-file mesh entry with an
# "instances" list: one mesh, a two-level BVH) and the same scene with one bunny (a plain mesh
# entry: the one-level BVH), renders each once
# with AO at 1 spp under /usr/bin/time -v, and prints their peak RSS; with --picture also renders
# the 10,000 at 64 spp into docs/images/bunny-instances.png. The mesh is read from the shared
# scenes ($MONTECL_SHARED_SCENES, default /work/shared/scenes), never copied into the repository.
# Usage: scripts/bunny_instances.sh [--picture] [BIN] [OUT_DIR] [DEVICE]  (DEVICE: a --device spec;
# default: the default OpenCL device)
set -euo pipefail
picture=0
if [ "${1:-}" = "--picture" ]; then picture=1; shift; fi
bin=${1:-build/montecl}
out=${2:-$(mktemp -d)}
device=()
[ -n "${3:-}" ] && device=(--device "$3")
shared=${MONTECL_SHARED_SCENES:-/work/shared/scenes}
bunny=$(realpath "$shared/bunny/bunny.obj")
mkdir -p "$out"
python3 - "$bunny" "$out" <<'PY'
import json, math, random, sys
bunny, out = sys.argv[1], sys.argv[2]
random.seed(1)
with open(out + "/floor.obj", "w") as f:
    f.write("v -16 0.0333 -16\nv -16 0.0333 16\nv 16 0.0333 16\nv 16 0.0333 -16\nf 1 2 3 4\n")
def scene(n):
    side = int(round(math.sqrt(n)))
    placements = []
    for k in range(n):
        i, j = k % side, k // side
        s = random.uniform(0.8, 1.3)
        placements.append({"translate": [0.3 * (i - (side - 1) / 2), 0.0333 * (1 - s), 0.3 * (j - (side - 1) / 2)],
                           "rotate": [0, 1, 0, random.uniform(0, 360)], "scale": s})
    return {"camera": {"position": [0.1, 0.5, 1.6], "target": [0, 0.05, 0], "fov_y": 50, "width": 320, "height": 240},
            "render": {"integrator": "ao", "spp": 1, "seed": 0, "ao_distance": 0.1},
            # one bunny: a plain mesh entry (no "instances": the one-level BVH, as any scene)
            "meshes": [{"file": "floor.obj"},
                       {"file": bunny, "transform": placements[0]} if n == 1 else {"file": bunny, "instances": placements}]}
for n in (1, 10000):
    with open("%s/scene-%d.json" % (out, n), "w") as f:
        json.dump(scene(n), f)
PY
for n in 1 10000; do
  /usr/bin/time -v "$bin" render "$out/scene-$n.json" -o "$out/bunny-$n.png" -q "${device[@]}" --overwrite \
    > /dev/null 2> "$out/time-$n.txt"
  rss=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$out/time-$n.txt")
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {print $2}' "$out/time-$n.txt")
  echo "bunnies $n: peak RSS $((rss / 1024)) MiB, wall $wall (${device[*]:-default device})"
done
if [ "$picture" = 1 ]; then
  "$bin" render "$out/scene-10000.json" -o docs/images/bunny-instances.png --spp 64 -q "${device[@]}" --overwrite
  echo "wrote docs/images/bunny-instances.png"
fi
