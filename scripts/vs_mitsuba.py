#!/usr/bin/env python3
"""vs_mitsuba.py: renders one montecl scene with montecl and with Mitsuba 3 (an independent
renderer), then reports per-pixel agreement (z-scores) and both wall times.

    scripts/vs_mitsuba.py SCENE.json|SCENE.xml [--spp N] [--width W --height H] [--seed S]
        [--integrator direct|path] [--max-depth D] [--rr-depth R] [--direct-sampling light|brdf|mis]
        [--repeat N] [--ref-factor F] [--ref-seeds K] [--montecl build/montecl] [--variant auto|llvm|scalar]
        [--montecl-arg ARG]... [--montecl-scene SCENE] [--block B] [--lum-blocks B [--lum-limits M,MED,P95]]
        [--mean-z-limit L] [--keep DIR] [--json FILE] [--no-agreement]
        [--no-timing]

Mitsuba's scene is built from ours as Python dicts: the pinhole camera from the camera keys
(look_at, fov_axis 'y', the same width and height), a box pixel filter (a sample counts for its own
pixel only, as in montecl), an `independent` sampler, one PLY mesh per (mesh, material) (with the
OBJ's per-corner vn normals, as montecl shades) with a two-sided Lambertian BSDF of albedo Kd
(montecl's surfaces are two-sided), times the MTL's `map_Kd` (decoded as montecl decodes it: 8-bit
sRGB to linear, half floats; bilinear, repeat) and cut out by its `map_d` (a `mask` whose 0/1
opacity is montecl's own test, bilinear alpha >= 0.5, sampled at 4x the texture's resolution; then
Mitsuba's `volpath`, whose shadow rays pass the cut-outs as montecl's do, stands for `path`), and,
where Ke (or the mesh's "emission") is non-zero, a one-sided `area` emitter (front face =
cross(v1-v0, v2-v0), as montecl's), textured by the MTL's `map_Ke` (x Ke, per-corner UVs, bilinear,
repeat). montecl mip-maps textures (trilinear, ray-cone footprints) and Mitsuba does not: pixels of
minified textures differ, blocks of pixels agree (--lum-blocks); the scene's "lights" as Mitsuba's
`point`, `spot` and `directional` emitters, and a `sun` as a black disk SUN_DISTANCE away whose
area emitter has the sun's radiance and cone. A mesh
entry's "material" of type dielectric / thin_dielectric / conductor becomes Mitsuba's dielectric or
roughdielectric / thindielectric / conductor or roughconductor (the rough ones GGX, visible normals,
for alpha > 0) with the same ior or RGB eta, k.
--block B compares B x B block means (heavy-tailed caustic pixels). --lum-blocks B decides PASS by
B x B blocks of luminance instead: the image mean's relative difference, the median and 95th
percentile of the blocks' absolute relative differences, within --lum-limits (percent), with the
blocks' z-scores printed beside them (textured scenes). Integrators: montecl `--integrator direct --direct-sampling mis` with K light samples
= Mitsuba `direct` (emitter_samples K, bsdf_samples 1); `light` = (K, 0); `brdf` = (0, 1);
montecl `--integrator path --max-depth D --rr-depth R` = Mitsuba `path` (max_depth D, rr_depth R):
the same depth convention.

A Mitsuba 3 scene (.xml, which montecl reads too: docs/mitsuba-format.md) goes to Mitsuba as it
is, in a copy that sets what the comparison decides: the film's size with a box filter, the
independent sampler, the integrator, and montecl's vertical field of view for the file's own film
(montecl keeps it when --width / --height change the size); relative names resolve against the
original's folder.

Agreement: montecl's EXR carries each pixel's mean, sample count and sample variance, so its
standard error is sqrt(var/n); that holds for i.i.d. samples, so montecl runs `--sampler
independent` (as Mitsuba does here) unless a --montecl-arg names a sampler. Mitsuba's pixels are
the mean of --ref-seeds independent renders at
--ref-factor x spp in all; their standard error comes from the spread of those renders. Per pixel
and channel z = (montecl - Mitsuba) / sqrt(se_montecl^2 + se_mitsuba^2). PASS when |z| > 4 on at
most 0.1% of pixel channels and |mean z| <= 0.1; pixel channels with zero variance in both must be
equal (to 1e-5 relative) or count as |z| > 4. Exit 0 PASS, 1 FAIL, 2 bad input, 77 Mitsuba missing.

Timing: whole processes, montecl (`render ... -o X.exr`) and a Mitsuba process (import, scene
build, JIT, render at spp, EXR write), alternated --repeat times after one untimed warm-up each
(kernel caches), medians of wall and CPU (user + sys) seconds, ratio montecl / Mitsuba.

Mitsuba comes from PyPI in a venv: `scripts/setup.sh --mitsuba` makes
~/.cache/montecl/mitsuba-venv ($MONTECL_MITSUBA_VENV overrides). Run with any python3: the script
re-runs itself with the venv's python. The `llvm_ad_rgb` variant needs Debian's libllvm19
(DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1, set here when that file exists);
without it, `scalar_rgb` (much slower).
"""
import argparse
import json
import math
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
VENV = os.environ.get("MONTECL_MITSUBA_VENV",
                      os.path.join(os.path.expanduser("~"), ".cache", "montecl", "mitsuba-venv"))
LLVM19 = "/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1"
EXIT_FAIL, EXIT_BAD, EXIT_SKIP = 1, 2, 77
# Mitsuba renders at most this many samples per pass (memory); more spp are averaged passes.
MAX_LANES = 1 << 24


class BadInput(Exception):
    pass


def mitsuba_env():
    env = dict(os.environ)
    if "DRJIT_LIBLLVM_PATH" not in env and os.path.exists(LLVM19):
        env["DRJIT_LIBLLVM_PATH"] = LLVM19
    return env


def ensure_mitsuba():
    """Imports mitsuba, re-running this script with the venv's python when this one lacks it."""
    try:
        import mitsuba  # noqa: F401
        import numpy  # noqa: F401
        return
    except ImportError:
        pass
    py = os.path.join(VENV, "bin", "python")
    if os.path.exists(py) and os.path.realpath(sys.prefix) != os.path.realpath(VENV):
        os.execve(py, [py, os.path.abspath(__file__)] + sys.argv[1:], mitsuba_env())
    print(f"vs_mitsuba: Mitsuba 3 is not installed (no venv at {VENV}); run scripts/setup.sh --mitsuba",
          file=sys.stderr)
    sys.exit(EXIT_SKIP)


# ---------------------------------------------------------------- scene: our JSON + OBJ/MTL

def read_mtl(path):
    mats, cur = {}, None
    with open(path) as f:
        for line in f:
            t = line.split("#", 1)[0].split()
            if not t:
                continue
            if t[0] == "newmtl":
                cur = mats.setdefault(" ".join(t[1:]), {"Kd": [0.5] * 3, "Ke": [0.0] * 3, "Ks": [0.0] * 3})
            elif cur is not None and t[0] in ("Kd", "Ke", "Ks") and len(t) >= 2:
                v = [float(x) for x in t[1:4]]
                cur[t[0]] = v if len(v) == 3 else [v[0]] * 3
            elif cur is not None and t[0] in ("map_Ke", "map_Kd", "map_d") and len(t) == 2:  # textures without options
                cur[t[0]] = os.path.join(os.path.dirname(path), t[1])
            elif cur is not None and t[0].startswith("map_"):
                cur.setdefault("maps", []).append(t[0])
    return mats


def read_obj(path):
    """Returns ({material name: list of (i0, i1, i2)}, positions, materials, {material: corner UVs},
    {material: corner normals}), triangulated as montecl's loader (tinyobjloader) does: quads along
    the shorter diagonal (a non-planar quad's two splits are different surfaces: the Cornell box's
    boxes have such quads), larger polygons as fans. A triangle's corner UVs (normals) are None
    unless all three corners have one, as montecl reads them."""
    import numpy as np
    pos, uvs, nrm, groups, mats, cur = [], [], [], {}, {}, None
    tuv, tn = {}, {}
    base = os.path.dirname(path)

    def ref(part, n):  # a 1-based (or negative, relative) OBJ index as 0-based; -1 when absent
        if not part:
            return -1
        i = int(part)
        return i - 1 if i > 0 else n + i

    with open(path) as f:
        for line in f:
            t = line.split("#", 1)[0].split()
            if not t:
                continue
            if t[0] == "v":
                pos.append([float(x) for x in t[1:4]])
            elif t[0] == "vt":
                uvs.append([float(x) for x in t[1:3]])
            elif t[0] == "vn":
                nrm.append([float(x) for x in t[1:4]])
            elif t[0] == "f":
                idx, tex, nor = [], [], []
                for c in t[1:]:
                    parts = c.split("/") + ["", ""]
                    idx.append(ref(parts[0], len(pos)))
                    tex.append(ref(parts[1], len(uvs)))
                    nor.append(ref(parts[2], len(nrm)))
                if len(idx) == 4:  # as tinyobjloader (montecl's OBJ loader): split along the shorter diagonal
                    p4 = [np.asarray(pos[i], dtype=np.float32) for i in idx]
                    d02, d13 = p4[2] - p4[0], p4[3] - p4[1]
                    corners = [(0, 1, 2), (0, 2, 3)] if np.dot(d02, d02) < np.dot(d13, d13) else [(0, 1, 3), (1, 2, 3)]
                else:  # triangles; larger polygons as fans (tinyobjloader may split non-convex ones otherwise)
                    corners = [(0, k, k + 1) for k in range(1, len(idx) - 1)]
                tris = groups.setdefault(cur, [])
                for c in corners:
                    tris.append(tuple(idx[k] for k in c))
                    tuv.setdefault(cur, []).append([uvs[tex[k]] for k in c] if min(tex[k] for k in c) >= 0 else None)
                    tn.setdefault(cur, []).append([nrm[nor[k]] for k in c] if min(nor[k] for k in c) >= 0 else None)
            elif t[0] == "usemtl":
                cur = " ".join(t[1:])
            elif t[0] == "mtllib":
                for name in t[1:]:
                    mats.update(read_mtl(os.path.join(base, name)))
    return groups, pos, mats, tuv, tn


def corner_array(rows, fallback):
    """(T, 3, k) float32 of per-triangle corner values; a None row becomes fallback(triangle index)."""
    import numpy as np
    return np.asarray([r if r is not None else fallback(i) for i, r in enumerate(rows)], dtype=np.float32)


def load_scene(path):
    import numpy as np
    if path.endswith(".xml"):  # Mitsuba's own scene: both renderers read the file
        return load_xml_scene(path)
    if not path.endswith(".json"):
        raise BadInput(f"{path}: a scene file (.json or Mitsuba .xml) is needed (a bare .obj has no camera to share)")
    with open(path) as f:
        s = json.load(f)
    for key in s:
        if key not in ("camera", "meshes", "render", "environment", "lights"):
            raise BadInput(f"{path}: {key}: not supported by vs_mitsuba.py")
    cam = s.get("camera")
    if not cam:
        raise BadInput(f"{path}: camera: required")
    shapes = []
    for mi_, mesh in enumerate(s.get("meshes", [])):
        for key in mesh:
            if key not in ("file", "emission", "two_sided_emission", "material"):
                raise BadInput(f"{path}: meshes[{mi_}].{key}: not supported by vs_mitsuba.py")
        kind_bsdf = mitsuba_kind_bsdf(path, mi_, mesh.get("material"))
        if mesh.get("two_sided_emission"):
            raise BadInput(f"{path}: meshes[{mi_}].two_sided_emission: Mitsuba's area emitters are one-sided")
        obj = os.path.join(os.path.dirname(path), mesh["file"])
        if not obj.lower().endswith(".obj"):
            raise BadInput(f"{path}: meshes[{mi_}].file: only OBJ meshes are supported by vs_mitsuba.py")
        groups, pos, mats, uvs, normals = read_obj(obj)
        P = np.asarray(pos, dtype=np.float32).reshape(-1, 3)
        for name, faces in groups.items():
            m = mats.get(name, {"Kd": [0.5] * 3, "Ke": [0.0] * 3, "Ks": [0.0] * 3})
            if any(m.get("Ks", [0.0])) or m.get("maps"):
                print(f"vs_mitsuba: warning: {obj}: material {name}: Ks and {', '.join(m.get('maps', [])) or 'no map'} "
                      "are ignored (Kd, Ke, map_Kd, map_d, map_Ke only)", file=sys.stderr)
            ke = mesh.get("emission", m["Ke"])
            if "map_Ke" in m and ("emission" in mesh or any(uv is None for uv in uvs.get(name, []))):
                raise BadInput(f"{obj}: material {name}: map_Ke needs triangles with UVs and no mesh-entry emission")
            if kind_bsdf is not None and ("map_Kd" in m or "map_d" in m):
                raise BadInput(f"{obj}: material {name}: map_Kd / map_d under a mesh entry's material are not "
                               "supported by vs_mitsuba.py")
            F = np.asarray(faces, dtype=np.int64)
            # Drop zero-area triangles as montecl does (they cannot be hit or sampled anyway).
            e1 = P[F[:, 1]] - P[F[:, 0]]
            e2 = P[F[:, 2]] - P[F[:, 0]]
            cross = np.cross(e1, e2)
            area = np.linalg.norm(cross, axis=1)
            keep = area > 0
            F = F[keep]
            textured = any(k in m for k in ("map_Ke", "map_Kd", "map_d"))
            # montecl reads a triangle without UVs at (0, 0) and one without (usable) vn flat: the
            # same values per corner here.
            UV = corner_array(uvs[name], lambda i: [[0.0, 0.0]] * 3)[keep] if textured else None
            N = None
            if any(n is not None for n in normals[name]):
                flat = cross / np.maximum(area, 1e-30)[:, None]
                N = corner_array(normals[name], lambda i: [flat[i]] * 3)[keep]
                ln = np.linalg.norm(N, axis=2, keepdims=True)
                bad = (ln == 0).any(axis=(1, 2))  # a zero-length vn: montecl shades the face flat
                N = np.where(ln > 0, N / np.maximum(ln, 1e-30), 0.0)
                N[bad] = flat[keep][bad][:, None, :]
            if len(F):
                shapes.append({"name": f"m{mi_}_{len(shapes)}", "P": P, "F": F, "Kd": m["Kd"], "Ke": ke,
                               "bsdf": kind_bsdf, "map_Ke": m.get("map_Ke"), "map_Kd": m.get("map_Kd"),
                               "map_d": m.get("map_d"), "UV": UV, "N": N})
    env = s.get("environment")
    if env is not None and ("radiance" not in env or len(env) != 1):
        raise BadInput(f"{path}: environment: only a constant {{\"radiance\": [r, g, b]}} is supported by vs_mitsuba.py")
    lights = s.get("lights", [])
    for li, light in enumerate(lights):
        if light.get("type") not in ("point", "spot", "directional", "sun"):
            raise BadInput(f"{path}: lights[{li}].type: not supported by vs_mitsuba.py")
    return {"camera": cam, "shapes": shapes, "render": s.get("render", {}), "environment": env, "lights": lights}


# montecl's metal table (host/scene/material_params.cpp: Mitsuba 3's own RGB values for these names).
METALS = {"Au": ([0.143036, 0.375307, 1.44205], [3.983, 2.38556, 1.60336]),
          "Ag": ([0.155276, 0.116728, 0.138388], [4.82835, 3.12222, 2.1469]),
          "Cu": ([0.201005, 0.92375, 1.10222], [3.91326, 2.45305, 2.14209]),
          "Al": ([1.6575, 0.880405, 0.521244], [9.22381, 6.2695, 4.837]),
          "Cr": ([4.36967, 2.91651, 1.6549], [5.20655, 4.23131, 3.7547])}


def mitsuba_kind_bsdf(path, index, mat):
    """The Mitsuba BSDF of a mesh entry's material override (None: the file's diffuse materials).
    dielectric -> dielectric (int_ior, ext_ior 1) or, with alpha (or roughness^2) > 0, roughdielectric
    (GGX, visible normals), thin_dielectric -> thindielectric, conductor -> conductor (alpha 0) or
    roughconductor (GGX, visible normals) with montecl's RGB eta / k."""
    if mat is None:
        return None
    where = f"{path}: meshes[{index}].material"
    kind = mat.get("type")
    for key in mat:
        if key not in ("type", "ior", "eta", "k", "metal", "alpha", "roughness"):
            raise BadInput(f"{where}.{key}: not supported by vs_mitsuba.py")
    alpha = float(mat["roughness"]) ** 2 if "roughness" in mat else float(mat.get("alpha", 0.0))
    if kind == "dielectric" and alpha > 0:
        return {"type": "roughdielectric", "distribution": "ggx", "alpha": alpha, "sample_visible": True,
                "int_ior": float(mat.get("ior", 1.5)), "ext_ior": 1.0}
    if kind in ("dielectric", "thin_dielectric"):
        return {"type": "dielectric" if kind == "dielectric" else "thindielectric",
                "int_ior": float(mat.get("ior", 1.5)), "ext_ior": 1.0}
    if kind == "conductor":
        eta, k = METALS[mat["metal"]] if "metal" in mat else (mat.get("eta", [0.0] * 3), mat.get("k", [1.0] * 3))
        b = {"eta": {"type": "rgb", "value": eta}, "k": {"type": "rgb", "value": k}}
        if alpha > 0:
            b.update(type="roughconductor", distribution="ggx", alpha=alpha, sample_visible=True)
        else:
            b["type"] = "conductor"
        return b
    raise BadInput(f"{where}.type: {kind!r}: not supported by vs_mitsuba.py")


def write_ply(path, P, F, UV=None, N=None):
    """Binary PLY with only the vertices F uses (compact), faces as uchar count + int indices. With
    UV or N (per corner), three vertices per triangle carrying (u, 1 - v) (Mitsuba's PLY texture
    coordinates have v = 0 at the image's top row, OBJ's at the bottom) and the corner's normal."""
    import numpy as np
    props = "property float x\nproperty float y\nproperty float z\n"
    if UV is None and N is None:
        used, inv = np.unique(F.ravel(), return_inverse=True)
        V = P[used].astype("<f4")
        idx = inv.reshape(-1, 3)
    else:
        cols = [P[F.ravel()]]
        if N is not None:
            cols.append(N.reshape(-1, 3))
            props += "property float nx\nproperty float ny\nproperty float nz\n"
        if UV is not None:
            uv = UV.reshape(-1, 2).astype(np.float32)
            cols += [uv[:, :1], 1.0 - uv[:, 1:]]
            props += "property float u\nproperty float v\n"
        V = np.concatenate(cols, axis=1).astype("<f4")
        idx = np.arange(len(V)).reshape(-1, 3)
    faces = np.zeros(len(F), dtype=[("n", "u1"), ("i", "<i4", (3,))])
    faces["n"] = 3
    faces["i"] = idx
    with open(path, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(V)}\n{props}"
                 f"element face {len(F)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        f.write(V.tobytes())
        f.write(faces.tobytes())


# ---------------------------------------------------------------- the Mitsuba worker process

def mitsuba_integrator(spec):
    if spec["integrator"] == "path":
        # Cut-outs: Mitsuba's `path` blocks shadow rays at a mask's transparent part; `volpath`
        # (no media here: otherwise the same estimator) lets them through, as montecl's traversal does.
        cutouts = spec.get("cutouts") or any(sh.get("map_d") for sh in spec["shapes"])
        return {"type": "volpath" if cutouts else "path", "max_depth": spec["max_depth"], "rr_depth": spec["rr_depth"]}
    k = spec["light_samples"]
    em, bs = {"mis": (k, 1), "light": (k, 0), "brdf": (0, 1)}[spec["direct_sampling"]]
    return {"type": "direct", "emitter_samples": em, "bsdf_samples": bs}


SUN_DISTANCE = 1e4  # the stand-in disk's distance in scene units (scenes here are a few units across): image
# means agree with montecl's sun to 4e-4 at 1e4 - 1e5 (1e3: 0.99995, the finite distance; 1e6: 1.0006, float precision)


def mitsuba_light(mi, light):
    """montecl's point, spot and directional lights as Mitsuba's emitters of the same names (the
    same radiometric units; spot: the same falloff, its axis the to_world +z)."""
    rgb = lambda v: {"type": "rgb", "value": v}
    if light["type"] == "point":
        return {"type": "point", "position": light["position"], "intensity": rgb(light["intensity"])}
    if light["type"] == "directional":
        return {"type": "directional", "direction": light["direction"], "irradiance": rgb(light["irradiance"])}
    if light["type"] == "sun":
        # Mitsuba has no sun disk of given irradiance: a black disk SUN_DISTANCE away whose one-sided
        # area emitter of radiance E / (pi sin^2 a) subtends the half-angle a (the same cone and
        # radiance as montecl's sun, to ~scene size / SUN_DISTANCE).
        d = light["direction"]
        n = math.sqrt(sum(x * x for x in d))
        a = math.radians(light.get("angle", 0.53)) / 2
        radius = SUN_DISTANCE * math.tan(a)
        c = [-SUN_DISTANCE * x / n for x in d]
        up = [0, 1, 0] if abs(d[1]) < 0.9 * n else [1, 0, 0]
        to_world = mi.ScalarTransform4f().look_at(origin=c, target=[c[i] + d[i] for i in range(3)], up=up) \
            @ mi.ScalarTransform4f().scale([radius, radius, 1])
        L = [e / (math.pi * math.sin(a) ** 2) for e in light["irradiance"]]
        return {"type": "disk", "to_world": to_world, "bsdf": {"type": "diffuse", "reflectance": rgb([0, 0, 0])},
                "emitter": {"type": "area", "radiance": rgb(L)}}
    p, d = light["position"], light["direction"]
    up = [0, 1, 0] if abs(d[1]) < 0.9 * math.sqrt(sum(x * x for x in d)) else [1, 0, 0]
    cutoff = light.get("cutoff_angle", 20.0)
    return {"type": "spot", "intensity": rgb(light["intensity"]), "cutoff_angle": cutoff,
            "beam_width": light.get("beam_width", cutoff * 0.75),
            "to_world": mi.ScalarTransform4f().look_at(origin=p, target=[p[i] + d[i] for i in range(3)], up=up)}


# Cut-outs: montecl keeps a hit where the bilinear alpha (finest level, repeat) is >= the cutoff, for
# every ray; Mitsuba's `mask` is a stochastic blend by its opacity. A 0/1 opacity made here from
# montecl's own test at MASK_SUPERSAMPLE x the texture's resolution (nearest filter) draws the same
# edge to 1 / (2 MASK_SUPERSAMPLE) of a texel.
MASK_SUPERSAMPLE = 4
ALPHA_CUTOFF = 0.5  # montecl's cutoff for MTL map_d (MaterialDesc::alphaCutoff)


def half(a):
    """Values as montecl stores texels (half floats)."""
    import numpy as np
    return np.asarray(a, dtype=np.float32).astype(np.float16).astype(np.float32)


def albedo_bitmap(mi, path, kd):
    """map_Kd x Kd as montecl reads it: integer images sRGB-decoded (Mitsuba marks 8- and 16-bit
    files sRGB and decodes them on conversion), float images as stored, grey as RGB, half floats,
    times Kd; a raw (linear) Mitsuba bitmap, bilinear, repeat."""
    import numpy as np
    rgb = np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False),
                   dtype=np.float32)
    tex = (half(rgb) * np.asarray(kd, dtype=np.float32)).astype(np.float32)
    return {"type": "bitmap", "bitmap": mi.Bitmap(tex), "raw": True, "filter_type": "bilinear", "wrap_mode": "repeat"}


def bilinear_repeat_rows(a, n_out, axis):
    """a resampled along axis at n_out evenly spaced sample centres, bilinear with repeat wrap and
    texel centres at half-integers, as montecl's texture_bilinear_wrap."""
    import numpy as np
    n = a.shape[axis]
    x = (np.arange(n_out) + 0.5) * (n / n_out) - 0.5
    x0 = np.floor(x)
    f = (x - x0).astype(np.float32)
    i0 = x0.astype(np.int64) % n
    i1 = (i0 + 1) % n
    shape = [1, 1]
    shape[axis] = n_out
    f = f.reshape(shape)
    return np.take(a, i0, axis=axis) * (1 - f) + np.take(a, i1, axis=axis) * f


def opacity_bitmap(mi, path):
    """map_d as montecl tests it: the image's alpha channel (else its first channel), never
    sRGB-decoded, half floats, bilinear, kept where >= ALPHA_CUTOFF; as a 0/1 Mitsuba bitmap."""
    import numpy as np
    bmp = mi.Bitmap(path)
    raw = np.array(bmp)
    if raw.ndim == 2:
        raw = raw[:, :, None]
    scale = {np.dtype("uint8"): 255.0, np.dtype("uint16"): 65535.0}.get(raw.dtype, 1.0)
    ch = raw.shape[2] - 1 if raw.shape[2] in (2, 4) else 0
    a = half(raw[:, :, ch].astype(np.float64) / scale)
    h, w = a.shape
    up = bilinear_repeat_rows(bilinear_repeat_rows(a, h * MASK_SUPERSAMPLE, 0), w * MASK_SUPERSAMPLE, 1)
    keep = (up >= ALPHA_CUTOFF).astype(np.float32)[:, :, None]
    return {"type": "bitmap", "bitmap": mi.Bitmap(keep), "raw": True, "filter_type": "nearest", "wrap_mode": "repeat"}


def dict_scene(mi, spec):
    """The scene translated from montecl's JSON (load_scene) as Mitsuba's dict."""
    import numpy as np
    cam = spec["camera"]
    d = {"type": "scene", "integrator": mitsuba_integrator(spec)}
    lens = {}
    if cam.get("aperture_radius", 0) > 0:  # montecl's thin lens: Mitsuba's thinlens camera
        lens = {"type": "thinlens", "aperture_radius": cam["aperture_radius"],
                "focus_distance": cam.get("focus_distance", math.dist(cam["position"], cam["target"]))}
    d["sensor"] = {
        "type": "perspective", "fov": cam["fov_y"], "fov_axis": "y",
        "to_world": mi.ScalarTransform4f().look_at(origin=cam["position"], target=cam["target"],
                                                   up=cam.get("up", [0, 1, 0])),
        "film": {"type": "hdrfilm", "width": spec["width"], "height": spec["height"],
                 "rfilter": {"type": "box"}, "pixel_format": "rgb", "component_format": "float32"},
        # independent unless the spec names another (scripts/convergence.py --vs-time compares them).
        # Its sample count is the pass's (below): a stratified sampler lays its strata out for it.
        "sampler": {"type": spec.get("sampler", "independent"),
                    "sample_count": max(1, min(spec["spp"], MAX_LANES // max(1, spec["width"] * spec["height"])))},
    }
    d["sensor"].update(lens)
    for sh in spec["shapes"]:
        reflectance = albedo_bitmap(mi, sh["map_Kd"], sh["Kd"]) if sh.get("map_Kd") else \
            {"type": "rgb", "value": sh["Kd"]}
        bsdf = sh.get("bsdf") or {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": reflectance}}
        if sh.get("map_d"):
            bsdf = {"type": "mask", "opacity": opacity_bitmap(mi, sh["map_d"]), "bsdf": bsdf}
        s = {"type": "ply", "filename": sh["ply"], "face_normals": not sh.get("normals"), "bsdf": bsdf}
        if sh.get("map_Ke"):  # Ke x the texture, decoded from sRGB by Mitsuba's own bitmap reader
            tex = np.array(mi.Bitmap(sh["map_Ke"]).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32,
                                                           srgb_gamma=False), dtype=np.float32)
            tex = (tex * np.asarray(sh["Ke"], dtype=np.float32)).astype(np.float32)
            s["emitter"] = {"type": "area", "radiance": {"type": "bitmap", "bitmap": mi.Bitmap(tex), "raw": True,
                                                         "filter_type": "bilinear", "wrap_mode": "repeat"}}
        elif any(x > 0 for x in sh["Ke"]):
            s["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": sh["Ke"]}}
        d[sh["name"]] = s
    for li, light in enumerate(spec.get("lights", [])):
        d[f"light{li}"] = mitsuba_light(mi, light)
    if spec["environment"] is not None:
        d["environment"] = {"type": "constant", "radiance": {"type": "rgb", "value": spec["environment"]["radiance"]}}
    return mi.load_dict(d)


def xml_scene(mi, spec):
    """A Mitsuba XML scene as given, but for what the comparison sets: the film's size and a box
    filter, an independent sampler at the pass's sample count, the integrator (xml_override)."""
    import xml.etree.ElementTree as ET
    tree = ET.parse(spec["xml"])
    xml_override(tree.getroot(), spec)
    path = os.path.join(os.path.dirname(spec["out"]), "scene.xml")
    tree.write(path)
    # The copy's relative names (meshes, textures, includes) resolve against the original's folder.
    mi.Thread.thread().file_resolver().prepend(os.path.dirname(os.path.abspath(spec["xml"])))
    return mi.load_file(path)


def xml_override(root, spec):
    import xml.etree.ElementTree as ET

    def prop(parent, tag, name, value):
        for e in parent.findall(tag):
            if e.get("name") == name:
                parent.remove(e)
        ET.SubElement(parent, tag, name=name, value=str(value))
    sensors = root.findall("sensor") or [ET.SubElement(root, "sensor", type="perspective")]
    for sensor in sensors:
        prop(sensor, "float", "fov", spec["camera"]["fov_y"])
        prop(sensor, "string", "fov_axis", "y")
        film = sensor.find("film")
        if film is None:
            film = ET.SubElement(sensor, "film", type="hdrfilm")
        prop(film, "integer", "width", spec["width"])
        prop(film, "integer", "height", spec["height"])
        for rf in film.findall("rfilter"):
            film.remove(rf)
        ET.SubElement(film, "rfilter", type="box")
        for sm in sensor.findall("sampler"):
            sensor.remove(sm)
        sampler = ET.SubElement(sensor, "sampler", type=spec.get("sampler", "independent"))
        prop(sampler, "integer", "sample_count", max(1, min(spec["spp"], MAX_LANES // max(1, spec["width"] * spec["height"]))))
    for e in root.findall("integrator"):
        root.remove(e)
    integ = ET.Element("integrator")
    desc = mitsuba_integrator(spec)
    integ.set("type", desc.pop("type"))
    for k, v in desc.items():
        ET.SubElement(integ, "integer", name=k, value=str(v))
    root.insert(0, integ)


def load_xml_scene(path):
    """What the driver needs of a Mitsuba XML scene (montecl and Mitsuba both read the file
    itself): the film's size, the sample count, the integrator and its depths, whether it has
    cut-outs (masks), with $name replaced by the file's <default> values."""
    import xml.etree.ElementTree as ET
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise BadInput(f"{path}: {e}")
    defaults = {d.get("name"): d.get("value") for d in root.findall("default")}

    def value(parent, tag, name, fallback):
        for e in (parent.findall(tag) if parent is not None else []):
            if e.get("name") == name:
                v = e.get("value", "")
                for k, dv in defaults.items():
                    v = v.replace("$" + k, dv)
                return v
        return fallback
    sensor = root.find("sensor")
    film = sensor.find("film") if sensor is not None else None
    sampler = sensor.find("sampler") if sensor is not None else None
    integ = root.find("integrator")
    render = {"spp": int(value(sampler, "integer", "sample_count", 4))}
    if integ is not None:
        render["integrator"] = "direct" if integ.get("type") == "direct" else "path"
        render["max_depth"] = int(value(integ, "integer", "max_depth", -1))
        render["rr_depth"] = int(value(integ, "integer", "rr_depth", 5))
    else:
        render.update(integrator="path", max_depth=-1, rr_depth=5)
    w, h = int(value(film, "integer", "width", 768)), int(value(film, "integer", "height", 576))
    # montecl keeps the vertical field of view of the file's own film when --width / --height change
    # it (its camera has fov_y): Mitsuba gets that fov on its y axis.
    fov = float(value(sensor, "float", "fov", 39.3077))
    axis = value(sensor, "string", "fov_axis", "x")
    t = math.tan(math.radians(fov) / 2)
    scale = {"y": 1.0, "diagonal": h / math.hypot(w, h)}.get(axis, h / w)
    if (axis == "smaller" and h < w) or (axis == "larger" and h > w):
        scale = 1.0
    return {"xml": os.path.abspath(path), "shapes": [], "environment": None, "lights": [], "render": render,
            "camera": {"width": w, "height": h, "fov_y": math.degrees(2 * math.atan(t * scale))},
            "cutouts": any(b.get("type") == "mask" for b in root.iter("bsdf"))}


def worker(spec_path):
    import numpy as np
    with open(spec_path) as f:
        spec = json.load(f)
    import mitsuba as mi
    variant = spec["variant"]
    try:
        mi.set_variant(variant)
    except Exception as e:  # llvm without a usable LLVM: fall back
        if variant == "scalar_rgb":
            raise
        print(f"vs_mitsuba: {variant} unavailable ({e}); using scalar_rgb", file=sys.stderr)
        variant = "scalar_rgb"
        mi.set_variant(variant)
    msc = xml_scene(mi, spec) if spec.get("xml") else dict_scene(mi, spec)
    pixels = spec["width"] * spec["height"]
    images = []
    t_render = time.perf_counter()
    for seed in spec["seeds"]:  # one independent render per seed, each at spec["spp"]
        spp, done, acc = spec["spp"], 0, None
        per_pass = max(1, min(spp, MAX_LANES // max(1, pixels)))
        p = 0
        while done < spp:
            n = min(per_pass, spp - done)
            img = np.array(mi.render(msc, seed=seed * 65536 + p, spp=n), dtype=np.float64)[:, :, :3]
            acc = img * n if acc is None else acc + img * n
            done += n
            p += 1
        images.append(acc / spp)
    stack = np.stack(images)
    mean = stack.mean(axis=0)
    out = {"variant": variant, "mean": mean, "render_s": time.perf_counter() - t_render}
    if len(images) > 1:
        out["se"] = stack.std(axis=0, ddof=1) / math.sqrt(len(images))
    if spec.get("exr"):
        mi.Bitmap(mean.astype(np.float32)).write(spec["exr"])
    np.savez(spec["out"], **out)


# ---------------------------------------------------------------- driver

def run_timed(cmd, env=None):
    """Runs cmd to completion; returns (wall s, CPU s of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        sys.stderr.write(r.stdout + r.stderr)
        raise RuntimeError(f"{cmd[0]} exited {r.returncode}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu, r


def read_montecl_exr(path):
    """Returns montecl's per-pixel mean and standard error sqrt(var/n) (H x W x 3), by channel name."""
    import mitsuba as mi
    import numpy as np
    bmp = mi.Bitmap(path)
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    data = np.array(bmp, dtype=np.float64).reshape(bmp.height(), bmp.width(), len(names))
    need = ["R", "G", "B", "samples", "var.R", "var.G", "var.B"]
    missing = [c for c in need if c not in names]
    if missing:
        raise RuntimeError(f"{path}: no channel {', '.join(missing)} (montecl's EXR should have them)")
    ch = {c: data[:, :, names.index(c)] for c in need}
    mean = np.stack([ch["R"], ch["G"], ch["B"]], axis=-1)
    var = np.stack([ch["var.R"], ch["var.G"], ch["var.B"]], axis=-1)
    n = np.maximum(ch["samples"], 1.0)[:, :, None]
    return mean, np.sqrt(np.maximum(var, 0.0) / n)


def block_average(mean, se, b):
    """Means of b x b pixel blocks (a partial edge block is left out) and their standard errors."""
    import numpy as np
    h, w = (mean.shape[0] // b) * b, (mean.shape[1] // b) * b
    m = mean[:h, :w].reshape(h // b, b, w // b, b, 3).mean(axis=(1, 3))
    v = (se[:h, :w] ** 2).reshape(h // b, b, w // b, b, 3).sum(axis=(1, 3)) / (b * b) ** 2
    return m, np.sqrt(v)


def agreement(m_mean, m_se, r_mean, r_se):
    import numpy as np
    diff = m_mean - r_mean
    se = np.sqrt(m_se ** 2 + r_se ** 2)
    exact = se == 0
    scale = np.maximum(np.abs(m_mean), np.abs(r_mean))
    same = np.abs(diff) <= 1e-5 * np.maximum(scale, 1e-30)
    z = np.where(exact, np.where(same, 0.0, np.inf), diff / np.where(exact, 1.0, se))
    finite = z[np.isfinite(z) & ~exact]
    big = np.count_nonzero(np.abs(z) > 4)
    return {
        "channels": int(z.size),
        "zero_variance_channels": int(np.count_nonzero(exact)),
        "frac_abs_z_gt_4": big / z.size,
        "abs_z_gt_4": int(big),
        "mean_z": float(finite.mean()) if finite.size else 0.0,
        "rms_z": float(np.sqrt((finite ** 2).mean())) if finite.size else 0.0,
        "max_abs_z": float(np.abs(z).max()),
        "mean_ratio": float(m_mean.sum() / r_mean.sum()) if r_mean.sum() > 0 else float("nan"),
        "mean_ratio_se": float(math.sqrt((m_se ** 2).sum() + (r_se ** 2).sum()) / r_mean.sum())
        if r_mean.sum() > 0 else float("nan"),
    }


LUMA = (0.2126, 0.7152, 0.0722)  # Rec. 709 / linear sRGB luminance


def lum_blocks(m_mean, m_se, r_mean, r_se, b):
    """Luminance of both images in b x b blocks (a partial edge block is left out): each block's
    relative difference (montecl - Mitsuba) / Mitsuba, and its standard error from both images'
    (the channels' errors added as if independent)."""
    import numpy as np
    w = np.asarray(LUMA)
    h, wd = (m_mean.shape[0] // b) * b, (m_mean.shape[1] // b) * b

    def blocks(x):
        return x[:h, :wd].reshape(h // b, b, wd // b, b).sum(axis=(1, 3)) / (b * b)
    m, r = blocks(m_mean @ w), blocks(r_mean @ w)
    var = blocks((m_se ** 2) @ (w ** 2) + (r_se ** 2) @ (w ** 2)) / (b * b)
    ok = r > 0
    return m[ok], r[ok], np.sqrt(var[ok]), int(np.count_nonzero(~ok))


def lum_agreement(m_mean, m_se, r_mean, r_se, b, limits):
    """Per b x b block of luminance: the image mean's relative difference, the median and 95th
    percentile of the blocks' absolute relative differences (percent), the median block's relative
    standard error (the noise those figures sit on); PASS when each is within limits (percent)."""
    import numpy as np
    m, r, se, dropped = lum_blocks(m_mean, m_se, r_mean, r_se, b)
    rel = np.abs(m - r) / r
    out = {"block": b, "blocks": int(m.size), "blocks_left_out_black": dropped,
           "mean_pct": float(100 * (m.sum() / r.sum() - 1)) if m.size else float("nan"),
           "median_pct": float(100 * np.median(rel)) if m.size else float("nan"),
           "p95_pct": float(100 * np.percentile(rel, 95)) if m.size else float("nan"),
           "max_pct": float(100 * rel.max()) if m.size else float("nan"),
           "median_se_pct": float(100 * np.median(se / r)) if m.size else float("nan"),
           # the same differences over their standard errors: noise alone gives rms z about 1
           "rms_z": float(np.sqrt(np.mean(((m - r) / np.maximum(se, 1e-30)) ** 2))) if m.size else float("nan"),
           "max_abs_z": float(np.max(np.abs(m - r) / np.maximum(se, 1e-30))) if m.size else float("nan"),
           "limits_pct": list(limits)}
    out["pass"] = bool(m.size and abs(out["mean_pct"]) <= limits[0] and out["median_pct"] <= limits[1]
                       and out["p95_pct"] <= limits[2])
    return out


def worker_base(sc, work, width, height, variant, integ, sampling, max_depth, rr_depth):
    """The worker's spec but for spp, seeds and outputs. Mitsuba reads the meshes as PLY files
    written here into work once (untimed), with its own C++ loader, as montecl parses the OBJ in its
    own process."""
    shapes = []
    for sh in sc["shapes"]:
        ply = os.path.join(work, sh["name"] + ".ply")
        write_ply(ply, sh["P"], sh["F"], sh["UV"], sh["N"])
        shapes.append({"name": sh["name"], "ply": ply, "Kd": sh["Kd"], "Ke": list(sh["Ke"]), "bsdf": sh["bsdf"],
                       "map_Ke": sh["map_Ke"], "map_Kd": sh["map_Kd"], "map_d": sh["map_d"],
                       "normals": sh["N"] is not None})
    return {"camera": sc["camera"], "shapes": shapes, "environment": sc["environment"], "lights": sc["lights"],
            "width": width, "height": height, "variant": variant, "integrator": integ, "direct_sampling": sampling,
            "light_samples": sc["render"]["light_samples"], "max_depth": max_depth, "rr_depth": rr_depth,
            "xml": sc.get("xml"), "cutouts": sc.get("cutouts", False)}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene", nargs="?")
    p.add_argument("--spp", type=int, default=None, help="samples per pixel (default: the scene's)")
    p.add_argument("--width", type=int)
    p.add_argument("--height", type=int)
    p.add_argument("--seed", type=int, default=None)
    p.add_argument("--integrator", choices=["direct", "path"], default=None)
    p.add_argument("--direct-sampling", choices=["light", "brdf", "mis"], default=None)
    p.add_argument("--max-depth", type=int, default=None, help="path: default the scene's max_depth, else montecl's (montecl settings --json)")
    p.add_argument("--rr-depth", type=int, default=None, help="path: default the scene's rr_depth, else montecl's")
    p.add_argument("--repeat", type=int, default=3, help="timed runs of each renderer (median)")
    p.add_argument("--ref-factor", type=int, default=4, help="Mitsuba reference spp = factor x spp")
    p.add_argument("--ref-seeds", type=int, default=16, help="independent Mitsuba renders in the reference")
    p.add_argument("--montecl", default=os.path.join(ROOT, "build", "montecl"))
    p.add_argument("--montecl-arg", action="append", default=[], help="extra montecl render argument")
    p.add_argument("--montecl-scene", help="render this scene with montecl instead (same camera and size; "
                   "e.g. a converted model, or a deliberately changed one to see the check fail)")
    p.add_argument("--variant", choices=["auto", "llvm", "scalar"], default="auto")
    p.add_argument("--block", type=int, default=1, help="compare means of B x B pixel blocks (caustics)")
    p.add_argument("--lum-blocks", type=int, default=0, metavar="B",
                   help="decide PASS per B x B block of luminance (relative differences: image mean, block median, "
                   "95th percentile within --lum-limits) instead of by z; for textured scenes, where montecl's "
                   "mip-mapped texels and Mitsuba's bilinear ones differ per pixel but not per block")
    p.add_argument("--lum-limits", default="1,2,5", metavar="MEAN,MEDIAN,P95",
                   help="--lum-blocks limits in percent (default 1,2,5)")
    p.add_argument("--mean-z-limit", type=float, default=0.1,
                   help="PASS needs |mean z| <= this (few block channels: their mean z has a larger SE)")
    p.add_argument("--keep", help="keep the images in this folder")
    p.add_argument("--json", help="write the results to this JSON file")
    p.add_argument("--no-timing", action="store_true", help="agreement only (one montecl run)")
    p.add_argument("--no-agreement", action="store_true", help="timing only")
    p.add_argument("--worker", help=argparse.SUPPRESS)
    a = p.parse_args(argv)
    if a.worker:
        return a
    if not a.scene:
        p.error("a scene file is needed")
    if a.repeat < 1 or a.ref_factor < 1 or a.ref_seeds < 2:
        p.error("--repeat and --ref-factor must be >= 1, --ref-seeds >= 2")
    try:
        a.lum_limits = [float(x) for x in a.lum_limits.split(",")]
    except ValueError:
        a.lum_limits = []
    if len(a.lum_limits) != 3 or any(not (x >= 0) for x in a.lum_limits) or a.lum_blocks < 0:
        p.error("--lum-limits needs three percentages MEAN,MEDIAN,P95 >= 0 and --lum-blocks B >= 1")
    return a


def main(argv):
    a = parse_args(argv)
    ensure_mitsuba()
    if a.worker:
        worker(a.worker)
        return 0
    import numpy as np
    import mitsuba as mi
    mi.set_variant("scalar_rgb")  # the driver only reads images
    if not os.path.exists(a.montecl):
        raise BadInput(f"{a.montecl}: no montecl executable (build it, or pass --montecl)")
    sc = load_scene(a.scene)  # checks what the worker will do, before any render
    # The scene's render block over montecl's own defaults (`montecl settings --json`), not a copy of them.
    defaults = subprocess.run([a.montecl, "settings", "--json"], check=True, capture_output=True, text=True).stdout
    sc["render"] = {**json.loads(defaults), **sc["render"]}
    cam, rnd = sc["camera"], sc["render"]
    width, height = a.width or cam.get("width", 512), a.height or cam.get("height", 512)
    spp = a.spp or rnd["spp"]
    seed = a.seed if a.seed is not None else rnd["seed"]
    integ = a.integrator or rnd["integrator"]
    if integ not in ("direct", "path"):
        raise BadInput(f"{a.scene}: render.integrator: {integ}: Mitsuba has no '{integ}' (use --integrator)")
    sampling = a.direct_sampling or rnd["direct_sampling"]
    a.max_depth = a.max_depth if a.max_depth is not None else rnd["max_depth"]
    a.rr_depth = a.rr_depth if a.rr_depth is not None else rnd["rr_depth"]
    variant = {"llvm": "llvm_ad_rgb", "scalar": "scalar_rgb"}[
        a.variant if a.variant != "auto" else ("llvm" if os.path.exists(LLVM19) or
                                               "DRJIT_LIBLLVM_PATH" in os.environ else "scalar")]
    work = a.keep or tempfile.mkdtemp(prefix="vs_mitsuba_")
    os.makedirs(work, exist_ok=True)
    env = mitsuba_env()

    m_exr = os.path.join(work, "montecl.exr")
    mcl = [a.montecl, "render", a.montecl_scene or a.scene, "--spp", str(spp), "--seed", str(seed), "--width", str(width),
           "--height", str(height), "--integrator", integ, "-o", m_exr, "--overwrite", "-q"]
    if integ == "direct":
        mcl += ["--direct-sampling", sampling]
    else:
        mcl += ["--max-depth", str(a.max_depth), "--rr-depth", str(a.rr_depth)]
    # The z-scores take montecl's error from var/n, which holds for i.i.d. samples only (Sobol points
    # are correlated: var/n misstates their error either way), and Mitsuba's sampler here is
    # `independent`: montecl's too, unless a --montecl-arg names one.
    if "--sampler" not in a.montecl_arg:
        mcl += ["--sampler", "independent"]
    mcl += a.montecl_arg
    # The settings' rules are montecl's (its settings table): a one-pixel render checks them first.
    probe = list(mcl)
    for opt, value in (("--spp", "1"), ("--width", "1"), ("--height", "1"), ("-o", os.path.join(work, "probe.pfm"))):
        probe[probe.index(opt) + 1] = value
    probe = subprocess.run(probe, capture_output=True, text=True)
    if probe.returncode == 2:
        raise BadInput(probe.stderr.strip().removeprefix("montecl: error: "))
    if integ == "direct" and any(sh["map_d"] for sh in sc["shapes"]):
        print("vs_mitsuba: warning: Mitsuba's `direct` blocks shadow rays at cut-outs (map_d), montecl does not; "
              "compare cut-out scenes with --integrator path (Mitsuba's volpath)", file=sys.stderr)
    base = worker_base(sc, work, width, height, variant, integ, sampling, a.max_depth, a.rr_depth)

    def mitsuba_cmd(name, spec):
        path = os.path.join(work, name + ".json")
        with open(path, "w") as f:
            json.dump(dict(base, **spec), f)
        return [sys.executable, os.path.abspath(__file__), "--worker", path]

    res = {"scene": a.scene, "width": width, "height": height, "spp": spp, "seed": seed, "integrator": integ,
           "montecl_command": " ".join(mcl)}
    if integ == "direct":
        res["direct_sampling"] = sampling
    else:
        res.update(max_depth=a.max_depth, rr_depth=a.rr_depth)
    print(f"vs_mitsuba: {a.scene} {width}x{height}, {spp} spp, {integ}"
          + (f" ({sampling})" if integ == "direct" else f" (max depth {a.max_depth}, rr depth {a.rr_depth})"))

    if not a.no_timing:
        timed = mitsuba_cmd("timed", {"spp": spp, "seeds": [seed], "out": os.path.join(work, "timed.npz"),
                                      "exr": os.path.join(work, "mitsuba.exr")})
        run_timed(mcl)  # warm-ups: kernel caches (montecl's program cache, Dr.Jit's kernel cache)
        run_timed(timed, env)
        times = {"montecl": [], "mitsuba": []}
        for _ in range(a.repeat):
            times["montecl"].append(run_timed(mcl)[:2])
            times["mitsuba"].append(run_timed(timed, env)[:2])
        res["mitsuba_variant"] = str(np.load(os.path.join(work, "timed.npz"))["variant"])
        for k, v in times.items():
            res[k + "_wall_s"] = statistics.median(w for w, _ in v)
            res[k + "_cpu_s"] = statistics.median(c for _, c in v)
            res[k + "_wall_all_s"] = [round(w, 3) for w, _ in v]
        res["wall_ratio"] = res["montecl_wall_s"] / res["mitsuba_wall_s"]
        print(f"wall (median of {a.repeat}, whole processes, alternated): montecl {res['montecl_wall_s']:.2f} s "
              f"(CPU {res['montecl_cpu_s']:.2f} s), Mitsuba {res['mitsuba_variant']} {res['mitsuba_wall_s']:.2f} s "
              f"(CPU {res['mitsuba_cpu_s']:.2f} s): ratio montecl/Mitsuba {res['wall_ratio']:.2f}")
    status = 0
    if not a.no_agreement:
        if a.no_timing:
            run_timed(mcl)
        ref_spp = max(1, spp * a.ref_factor // a.ref_seeds)
        seeds = [1000 + seed * a.ref_seeds + k for k in range(a.ref_seeds)]
        t0 = time.perf_counter()
        run_timed(mitsuba_cmd("ref", {"spp": ref_spp, "seeds": seeds, "out": os.path.join(work, "ref.npz")}), env)
        ref = np.load(os.path.join(work, "ref.npz"))
        res["mitsuba_variant"] = str(ref["variant"])
        res["reference_spp"] = ref_spp * a.ref_seeds
        res["reference_seconds"] = time.perf_counter() - t0
        m_mean, m_se = read_montecl_exr(m_exr)
        if m_mean.shape != ref["mean"].shape:
            raise RuntimeError(f"image sizes differ: montecl {m_mean.shape}, Mitsuba {ref['mean'].shape}")
        r_mean, r_se = ref["mean"], ref["se"]
        if a.block > 1:  # block means: heavy-tailed pixels (caustics) average toward normal
            m_mean, m_se = block_average(m_mean, m_se, a.block)
            r_mean, r_se = block_average(r_mean, r_se, a.block)
        ag = agreement(m_mean, m_se, r_mean, r_se)
        ag["block"] = a.block
        ok = ag["frac_abs_z_gt_4"] <= 1e-3 and abs(ag["mean_z"]) <= a.mean_z_limit
        ag["pass"] = bool(ok)
        res["agreement"] = ag
        unit = "pixel channels" if a.block == 1 else f"{a.block}x{a.block}-block channels"
        print(f"agreement vs Mitsuba {res['mitsuba_variant']} ({res['reference_spp']} spp in {a.ref_seeds} "
              f"independent renders): |z| > 4 on {ag['abs_z_gt_4']} of {ag['channels']} {unit} "
              f"({100 * ag['frac_abs_z_gt_4']:.3f}%, limit 0.1%), mean z {ag['mean_z']:+.3f} (limit {a.mean_z_limit:g}), "
              f"rms z {ag['rms_z']:.3f}, max |z| {ag['max_abs_z']:.2f}; image mean montecl/Mitsuba "
              f"{ag['mean_ratio']:.5f} +- {ag['mean_ratio_se']:.5f}")
        if a.lum_blocks:  # the z figures above stay for information; the blocks decide
            lum = lum_agreement(*read_montecl_exr(m_exr), ref["mean"], ref["se"], a.lum_blocks, a.lum_limits)
            res["lum_blocks"] = lum
            ok = lum["pass"]
            print(f"luminance per {a.lum_blocks}x{a.lum_blocks} block ({lum['blocks']} blocks): image mean "
                  f"{lum['mean_pct']:+.3f}%, block median |diff| {lum['median_pct']:.3f}%, 95th percentile "
                  f"{lum['p95_pct']:.3f}%, max {lum['max_pct']:.2f}% (median block standard error "
                  f"{lum['median_se_pct']:.3f}%; block z rms {lum['rms_z']:.2f}, max {lum['max_abs_z']:.2f}); "
                  f"limits {', '.join(f'{x:g}%' for x in a.lum_limits)}")
        print("PASS" if ok else "FAIL")
        status = 0 if ok else EXIT_FAIL
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=2)
    if not a.keep:
        shutil.rmtree(work, ignore_errors=True)
    return status


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except (BadInput, FileNotFoundError, KeyError, json.JSONDecodeError) as e:
        print(f"vs_mitsuba: {e}", file=sys.stderr)
        sys.exit(EXIT_BAD)
