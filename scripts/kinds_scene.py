#!/usr/bin/env python3
"""kinds_scene.py: writes a scene with the delta and glossy material kinds for the Mitsuba check
(scripts/vs_mitsuba.py, tests/test_vs_mitsuba.cpp): the shared Cornell box plus three icospheres
(OBJ, outward winding, written here): smooth glass on the short box, a rough gold conductor and a
smooth mirror on the floor. Never copies the shared scene: the box is referenced by its path.

    scripts/kinds_scene.py OUTDIR --cornell DIR [--ior 1.5] [--glass-alpha 0] [--gold-alpha 0.1] [--metal Au]
        [--pane-alpha A] [--no-spheres]
--glass-alpha A > 0 makes the glass sphere rough (GGX, alpha A). --pane-alpha A adds a rough glass
pane (index --ior, alpha A, front face down) just below the ceiling light, so the box is lit only
through it; --no-spheres leaves the spheres out.
Writes OUTDIR/scene.json, OUTDIR/sphere_*.obj (and OUTDIR/pane.obj).
"""
import argparse
import json
import math
import os


def icosphere(levels, radius, center):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    v = [tuple(x / math.sqrt(sum(y * y for y in p)) for x in p) for p in v]
    for _ in range(levels):
        cache, nf = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                cache[key] = len(v) - 1
            return cache[key]
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    lines = ["v %.7f %.7f %.7f" % tuple(center[i] + radius * p[i] for i in range(3)) for p in v]
    lines += ["f %d %d %d" % (a + 1, b + 1, c + 1) for a, b, c in f]  # flat faces (no vn): Mitsuba's face normals
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out")
    p.add_argument("--cornell", required=True, help="folder of the shared Cornell box")
    p.add_argument("--ior", type=float, default=1.5)
    p.add_argument("--glass-alpha", type=float, default=0.0)
    p.add_argument("--gold-alpha", type=float, default=0.1)
    p.add_argument("--metal", default="Au")
    p.add_argument("--pane-alpha", type=float, default=None)
    p.add_argument("--no-spheres", action="store_true")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    spheres = [("glass", 0.25, (0.33, 0.85, 0.38), dict({"type": "dielectric", "ior": a.ior},
                                                      **({"alpha": a.glass_alpha} if a.glass_alpha > 0 else {}))),
               ("gold", 0.25, (-0.45, 0.25, 0.45), {"type": "conductor", "metal": a.metal, "alpha": a.gold_alpha}),
               ("mirror", 0.17, (0.55, 0.17, -0.5), {"type": "conductor", "alpha": 0})]
    with open(os.path.join(a.cornell, "scene.json")) as f:
        box = json.load(f)
    meshes = [{"file": os.path.abspath(os.path.join(a.cornell, m["file"]))} for m in box["meshes"]]
    for name, r, c, mat in ([] if a.no_spheres else spheres):
        with open(os.path.join(a.out, f"sphere_{name}.obj"), "w") as f:
            f.write(icosphere(3, r, c))
        meshes.append({"file": f"sphere_{name}.obj", "material": mat})
    if a.pane_alpha is not None:
        # Below the light (y 1.98, x -0.24 .. 0.23, z -0.22 .. 0.16) and larger; wound so that
        # cross(v1 - v0, v2 - v0) points down: the box is the outside (index 1).
        with open(os.path.join(a.out, "pane.obj"), "w") as f:
            f.write("v -0.4 1.9 -0.4\nv 0.4 1.9 -0.4\nv 0.4 1.9 0.35\nv -0.4 1.9 0.35\nf 1 2 3\nf 1 3 4\n")
        meshes.append({"file": "pane.obj", "material": {"type": "dielectric", "ior": a.ior, "alpha": a.pane_alpha}})
    scene = {"camera": box["camera"], "meshes": meshes, "render": box.get("render", {})}
    with open(os.path.join(a.out, "scene.json"), "w") as f:
        json.dump(scene, f, indent=1)


if __name__ == "__main__":
    main()
