#!/usr/bin/env python3
"""make_materials.py: writes the material showcase (a Cornell box with a smooth glass sphere, a rough
glass sphere, a rough gold sphere and a mirror on the back wall) as small OBJ files beside this
script; scene.json (hand-written) gives each mesh its material type."""
import math, os

here = os.path.dirname(os.path.abspath(__file__))

def write(name, verts, faces, normals=None, mtl=None, groups=None):
    with open(os.path.join(here, name), "w") as f:
        if mtl: f.write(f"mtllib {mtl}\n")
        for v in verts: f.write("v %.5f %.5f %.5f\n" % v)
        for n in normals or []: f.write("vn %.5f %.5f %.5f\n" % n)
        for i, face in enumerate(faces):
            if groups and i in groups: f.write(f"usemtl {groups[i]}\n")
            if normals: f.write("f " + " ".join(f"{a + 1}//{a + 1}" for a in face) + "\n")
            else: f.write("f " + " ".join(str(a + 1) for a in face) + "\n")

# Box: x, z in [-1, 1], y in [0, 2], open toward +z (the camera); faces wound toward the inside.
V = [(-1, 0, -1), (1, 0, -1), (1, 0, 1), (-1, 0, 1), (-1, 2, -1), (1, 2, -1), (1, 2, 1), (-1, 2, 1)]
F = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (0, 4, 7, 3), (1, 2, 6, 5)]
write("box.obj", V, F, mtl="box.mtl", groups={0: "white", 3: "red", 4: "green"})
with open(os.path.join(here, "box.mtl"), "w") as f:
    f.write("newmtl white\nKd 0.73 0.71 0.68\nnewmtl red\nKd 0.63 0.065 0.05\nnewmtl green\nKd 0.14 0.45 0.091\n")
# Light: a square under the ceiling, front face down.
write("light.obj", [(-0.25, 1.98, -0.25), (0.25, 1.98, -0.25), (0.25, 1.98, 0.25), (-0.25, 1.98, 0.25)], [(0, 1, 2, 3)])
# Mirror: a quad on the back wall, facing +z.
write("mirror.obj", [(-0.55, 0.9, -0.99), (0.55, 0.9, -0.99), (0.55, 1.75, -0.99), (-0.55, 1.75, -0.99)], [(0, 1, 2, 3)])

def sphere(name, c, r, rings=16, segs=32):
    verts, norms, faces = [], [], []
    for i in range(rings + 1):
        th = math.pi * i / rings
        for j in range(segs):
            ph = 2 * math.pi * j / segs
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            verts.append(tuple(c[k] + r * n[k] for k in range(3))); norms.append(n)
    for i in range(rings):
        for j in range(segs):
            a, b = i * segs + j, i * segs + (j + 1) % segs
            cc, d = a + segs, b + segs
            # outward winding: cross(v1 - v0, v2 - v0) points away from the centre
            if i > 0: faces.append((a, b, d))
            if i < rings - 1: faces.append((a, d, cc))
    write(name, verts, faces, normals=norms)

sphere("glass.obj", (-0.5, 0.3, 0.2), 0.3)
sphere("rough_glass.obj", (0.5, 0.3, 0.3), 0.3)
sphere("gold.obj", (0.0, 0.25, -0.5), 0.25)
