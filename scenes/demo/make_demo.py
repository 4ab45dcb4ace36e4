#!/usr/bin/env python3
"""make_demo.py: writes demo.obj and demo.mtl, montecl's own demo scene: two boxes and two spheres
on a floor in front of a wall (contact shadows and corners for ambient occlusion) and a small
downward-facing emitter quad (Ke) for direct lighting. Every face winds counter-clockwise seen
from outside (front face = cross(v1 - v0, v2 - v0)). Run it from any folder; no dependencies."""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))

MATERIALS = [  # name, Kd, Ke
    ("floor", (0.75, 0.75, 0.72), None),
    ("wall", (0.70, 0.72, 0.75), None),
    ("red", (0.70, 0.15, 0.12), None),
    ("blue", (0.15, 0.25, 0.65), None),
    ("white", (0.80, 0.80, 0.80), None),
    ("gold", (0.80, 0.60, 0.20), None),
    ("light", (0.0, 0.0, 0.0), (15.0, 15.0, 15.0)),
]


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


class Obj:
    def __init__(self):
        self.lines = ["# montecl demo scene, written by make_demo.py", "mtllib demo.mtl"]
        self.ids = {}  # formatted position -> vertex number, so shared corners are written once

    def object(self, name, material):
        self.lines += ["o " + name, "usemtl " + material]

    def vertex(self, p):
        text = "v %.6f %.6f %.6f" % tuple(x + 0.0 for x in p)  # + 0.0 turns -0.0 into 0.0
        text = text.replace("-0.000000", "0.000000")
        if text not in self.ids:
            self.lines.append(text)
            self.ids[text] = len(self.ids) + 1
        return self.ids[text]

    def face(self, points, outward_from=None):
        """One polygon; flipped if needed so that its normal points away from outward_from."""
        if outward_from is not None:
            n = cross(sub(points[1], points[0]), sub(points[2], points[0]))
            if dot(n, sub(points[0], outward_from)) < 0:
                points = list(reversed(points))
        ids = [self.vertex(p) for p in points]
        self.lines.append("f " + " ".join(str(i) for i in ids))


def rect(center, u, v):
    """Corners of center +- u +- v, counter-clockwise around u x v."""
    c, s = center, [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    return [tuple(c[k] + a * u[k] + b * v[k] for k in range(3)) for a, b in s]


def box(obj, name, material, center, size, yaw_degrees):
    obj.object(name, material)
    t = math.radians(yaw_degrees)
    ax = (math.cos(t) * size[0] / 2, 0.0, -math.sin(t) * size[0] / 2)
    ay = (0.0, size[1] / 2, 0.0)
    az = (math.sin(t) * size[2] / 2, 0.0, math.cos(t) * size[2] / 2)
    for n, u, v in [(ax, ay, az), (ay, az, ax), (az, ax, ay)]:
        for sign in (1, -1):
            c = tuple(center[k] + sign * n[k] for k in range(3))
            obj.face(rect(c, u, v), outward_from=center)


def sphere(obj, name, material, center, radius, slices, stacks):
    obj.object(name, material)

    def point(i, j):
        theta, phi = math.pi * i / stacks, 2 * math.pi * j / slices
        return (center[0] + radius * math.sin(theta) * math.cos(phi),
                center[1] + radius * math.cos(theta),
                center[2] + radius * math.sin(theta) * math.sin(phi))

    for i in range(stacks):
        for j in range(slices):
            a, b, c, d = point(i, j), point(i, j + 1), point(i + 1, j + 1), point(i + 1, j)
            if i == 0:
                obj.face([a, c, d], outward_from=center)
            elif i == stacks - 1:
                obj.face([a, b, c], outward_from=center)
            else:
                obj.face([a, b, c], outward_from=center)
                obj.face([a, c, d], outward_from=center)


def main():
    obj = Obj()
    obj.object("floor", "floor")
    obj.face(rect((0, 0, 0.75), (0, 0, 3.75), (4, 0, 0)))  # normal +y
    obj.object("wall", "wall")
    obj.face(rect((0, 1.5, -3), (4, 0, 0), (0, 1.5, 0)))  # normal +z
    box(obj, "cube", "red", (-1.0, 0.4, -0.7), (0.8, 0.8, 0.8), 25)
    box(obj, "tall_box", "blue", (1.55, 0.7, -1.2), (0.6, 1.4, 0.6), -20)
    sphere(obj, "sphere", "white", (0.25, 0.5, 0.3), 0.5, 48, 24)
    sphere(obj, "small_sphere", "gold", (-0.75, 0.25, 0.75), 0.25, 32, 16)
    obj.object("light", "light")
    obj.face(rect((0, 2.6, -0.6), (0.3, 0, 0), (0, 0, 0.3)))  # normal -y: it faces the floor
    with open(os.path.join(HERE, "demo.obj"), "w") as f:
        f.write("\n".join(obj.lines) + "\n")
    with open(os.path.join(HERE, "demo.mtl"), "w") as f:
        f.write("# materials of montecl's demo scene (Kd albedo, Ke emitted radiance)\n")
        for name, kd, ke in MATERIALS:
            f.write("\nnewmtl %s\nKd %g %g %g\n" % ((name,) + kd))
            if ke:
                f.write("Ke %g %g %g\n" % ke)


if __name__ == "__main__":
    main()
