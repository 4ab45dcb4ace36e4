#!/usr/bin/env python3
"""make_emissive.py: writes glow.png (8x8, black but for an off-centre 3x2 white block, so a
flipped or mirrored texture lookup moves the light) and glow-quad.obj/.mtl (a 1.6 x 1.6 quad at
y = 1.5 facing down, map_Ke glow.png) for the emission-texture comparison with Mitsuba 3."""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png(path, rows):
    raw = b"".join(b"\0" + bytes(v for px in row for v in px) for row in rows)
    chunk = lambda tag, data: struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


rows = [[(255, 255, 255) if 1 <= x <= 3 and 4 <= y <= 5 else (0, 0, 0) for x in range(8)] for y in range(8)]
png(os.path.join(HERE, "glow.png"), rows)
with open(os.path.join(HERE, "glow-quad.mtl"), "w") as f:
    f.write("# glow-quad.mtl: written by make_emissive.py\nnewmtl glow\nKd 0 0 0\nKe 12 10 9\nmap_Ke glow.png\n")
with open(os.path.join(HERE, "glow-quad.obj"), "w") as f:
    f.write("# glow-quad.obj: written by make_emissive.py; front face (cross(v1-v0, v2-v0)) down\n"
            "mtllib glow-quad.mtl\nv -0.8 1.5 -0.8\nv 0.8 1.5 -0.8\nv 0.8 1.5 0.8\nv -0.8 1.5 0.8\n"
            "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl glow\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
