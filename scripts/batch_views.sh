#!/usr/bin/env bash
# Measures what `montecl render --camera all` saves per extra view: writes the Stanford bunny (read
# from the shared scenes, $MONTECL_SHARED_SCENES, default /work/shared/scenes; never copied into the
# repository) as a glTF file with VIEWS cameras around it, then renders every camera REPEAT times
# both ways, alternating: one process with --camera all, and one process per camera (--camera N),
# each path traced at SIZE x SIZE, SPP samples. Prints each way's median wall time, the saving per
# extra view ((N processes - 1 process) / (VIEWS - 1)) and checks that both ways wrote the same
# bytes. The kernel program cache is warmed first, so neither way pays a compile.
# Usage: scripts/batch_views.sh [BIN] [VIEWS] [SIZE] [SPP] [REPEAT] [DEVICE]
#   (defaults: build/montecl 4 64 4 3, the default OpenCL device)
set -euo pipefail
bin=$(realpath "${1:-build/montecl}")
views=${2:-4}
size=${3:-64}
spp=${4:-4}
repeat=${5:-3}
device=()
[ -n "${6:-}" ] && device=(--device "$6")
shared=${MONTECL_SHARED_SCENES:-/work/shared/scenes}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 - "$shared/bunny/bunny.obj" "$out/bunny.gltf" "$views" <<'PY'
import base64, json, math, struct, sys
obj, path, views = sys.argv[1], sys.argv[2], int(sys.argv[3])
pos, idx = [], []
for line in open(obj):
    p = line.split()
    if not p: continue
    if p[0] == "v": pos += [float(x) for x in p[1:4]]
    elif p[0] == "f":
        c = [int(x.split("/")[0]) - 1 for x in p[1:]]
        for k in range(1, len(c) - 1): idx += [c[0], c[k], c[k + 1]]
n = len(pos) // 3
nor = [0.0] * (3 * n)  # smooth normals (area-weighted), so the views shade through the normal table too
for t in range(0, len(idx), 3):
    a, b, c = idx[t:t + 3]
    e1 = [pos[3 * b + k] - pos[3 * a + k] for k in range(3)]
    e2 = [pos[3 * c + k] - pos[3 * a + k] for k in range(3)]
    fn = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    for v in (a, b, c):
        for k in range(3): nor[3 * v + k] += fn[k]
for v in range(n):
    l = math.sqrt(sum(nor[3 * v + k] ** 2 for k in range(3))) or 1.0
    for k in range(3): nor[3 * v + k] /= l
lo = [min(pos[i::3]) for i in range(3)]; hi = [max(pos[i::3]) for i in range(3)]
centre = [(a + b) / 2 for a, b in zip(lo, hi)]
radius = max(b - a for a, b in zip(lo, hi)) * 1.6
buf = struct.pack("<%df" % len(pos), *pos) + struct.pack("<%df" % len(nor), *nor) + struct.pack("<%dI" % len(idx), *idx)
nodes, cams = [{"mesh": 0}], []
for v in range(views):  # cameras on a circle around the bunny, each looking at its centre
    a = 2 * math.pi * v / views
    t = [centre[0] + radius * math.sin(a), centre[1], centre[2] + radius * math.cos(a)]
    nodes.append({"camera": 0, "translation": t, "rotation": [0, math.sin(a / 2), 0, math.cos(a / 2)]})
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": list(range(views + 1))}], "nodes": nodes,
     "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.01}}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
     "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0}}],
     "buffers": [{"uri": "data:application/octet-stream;base64," + base64.b64encode(buf).decode(), "byteLength": len(buf)}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
                     {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
                     {"buffer": 0, "byteOffset": 24 * n, "byteLength": 4 * len(idx)}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": lo, "max": hi},
                   {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
                   {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]}
json.dump(g, open(path, "w"))
print("bunny.gltf: %d triangles, %d cameras" % (len(idx) // 3, views))
PY
common=(--width "$size" --height "$size" --spp "$spp" -q --overwrite "${device[@]}")
"$bin" render "$out/bunny.gltf" --camera 0 -o "$out/warm.png" "${common[@]}" > /dev/null  # fills the program cache
now() { date +%s.%N; }
one=() many=()
for ((r = 0; r < repeat; ++r)); do
  t0=$(now)
  "$bin" render "$out/bunny.gltf" --camera all -o "$out/batch_{camera}.png" "${common[@]}" > /dev/null
  t1=$(now)
  for ((v = 0; v < views; ++v)); do
    "$bin" render "$out/bunny.gltf" --camera "$v" -o "$out/single_$v.png" "${common[@]}" > /dev/null
  done
  t2=$(now)
  one+=("$(echo "$t1 - $t0" | bc -l)")
  many+=("$(echo "$t2 - $t1" | bc -l)")
done
median() { printf '%s\n' "$@" | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
m1=$(median "${one[@]}")
mn=$(median "${many[@]}")
for ((v = 0; v < views; ++v)); do
  cmp -s "$out/batch_$v.png" "$out/single_$v.png" || { echo "batch_$v.png differs from single_$v.png"; exit 1; }
done
printf 'one process, %d views: %.3f s (median of %d)\n' "$views" "$m1" "$repeat"
printf '%d processes, 1 view each: %.3f s\n' "$views" "$mn"
printf 'saving per extra view: %.3f s\n' "$(echo "($mn - $m1) / ($views - 1)" | bc -l)"
echo "images identical both ways"
