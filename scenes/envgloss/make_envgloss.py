#!/usr/bin/env python3
"""make_envgloss.py: writes the environment + glossy example beside itself: sky.hdr (a 256 x 128
latitude-longitude Radiance HDR: blue sky gradient, dim ground, a small warm sun 35 degrees up),
envgloss.mtl (the demo scene's materials with glossy Ks/Ns lobes) and envgloss.obj (../demo/demo.obj
using envgloss.mtl). Map convention: row 0 is straight up (+y), column u looks along
(sin 2 pi u, 0, -cos 2 pi u). No dependencies."""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
W, H = 256, 128
SUN = (math.radians(35.0), 0.30)  # elevation, u
SUN_RADIUS = math.radians(2.5)


def sky(u, v):
    theta, phi = math.pi * v, 2.0 * math.pi * u
    d = (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))
    if d[1] < 0.0:
        return (0.12, 0.10, 0.08)
    t = d[1]
    c = (0.55 + 0.25 * (1 - t), 0.70 + 0.15 * (1 - t), 1.0)
    se, su = SUN
    sd = (math.cos(se) * math.sin(2 * math.pi * su), math.sin(se), -math.cos(se) * math.cos(2 * math.pi * su))
    if sum(a * b for a, b in zip(d, sd)) > math.cos(SUN_RADIUS):
        return (2000.0, 1800.0, 1500.0)
    return c


def rgbe(r, g, b):
    v = max(r, g, b)
    if v < 1e-32:
        return bytes(4)
    m, e = math.frexp(v)
    s = m * 256.0 / v
    return bytes((int(r * s), int(g * s), int(b * s), e + 128))


with open(os.path.join(HERE, "sky.hdr"), "wb") as f:
    f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (H, W))
    for y in range(H):
        f.write(b"".join(rgbe(*sky((x + 0.5) / W, (y + 0.5) / H)) for x in range(W)))

GLOSS = {"floor": ("0.45 0.45 0.43", "0.25 0.25 0.25", 40), "wall": ("0.7 0.72 0.75", "0 0 0", 0)}
with open(os.path.join(HERE, "../demo/demo.mtl")) as f:
    mtl = f.read().splitlines()
out, name = [], None
for line in mtl:
    out.append(line)
    if line.startswith("newmtl "):
        name = line.split()[1]
    elif line.startswith("Kd ") and name != "light":
        kd, ks, ns = GLOSS.get(name, (" ".join(str(0.6 * float(x)) for x in line.split()[1:]), "0.35 0.35 0.35", 300))
        out[-1] = "Kd " + kd
        out.append("Ks " + ks)
        out.append("Ns %d" % ns)
with open(os.path.join(HERE, "envgloss.mtl"), "w") as f:
    f.write("# the demo scene's materials with glossy lobes (make_envgloss.py)\n" + "\n".join(out[1:]) + "\n")
with open(os.path.join(HERE, "../demo/demo.obj")) as f:
    obj = f.read().replace("mtllib demo.mtl", "mtllib envgloss.mtl")
with open(os.path.join(HERE, "envgloss.obj"), "w") as f:
    f.write(obj)
