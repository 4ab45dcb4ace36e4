#!/usr/bin/env python3
"""veach_mis_model.py: which material model Tungsten's veach-mis reference was rendered with. Reads the
shared scene-v4.pbrt (its plates, floor, wall and sphere lights), writes them as one Mitsuba 3 XML file
per model, renders it with Mitsuba 3 (and with montecl when --montecl is given) and prints, per copper
plate, the rendered luminance over Tungsten's (TungstenRender.exr box-filtered to the rendered size),
and vs_tungsten.py's block statistics.

    scripts/veach_mis_model.py [--scenes ../shared/scenes-pbrt] [--size 320x180] [--spp 256]
                               [--montecl build/montecl] [--keep DIR]

Models (rows): "file", the pbrt file as pbrt-v4 reads it (GGX of alpha = roughness, no factor on the
Fresnel term); "file, direct light only" (max depth 2); "Tungsten's", what the file lost in its
conversion from Tungsten's scene: Beckmann microfacets and an albedo of 0.3 on the plates, with direct
light only. Mitsuba 3 is the independent renderer: a model whose plate ratios are all 1 is the
reference's.

Runs with the Mitsuba venv's python, as vs_tungsten.py (exit 77 without it or the shared scenes).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import vs_tungsten as vt  # noqa: E402

# The plates' named materials in the file, their roughness (alpha: remaproughness is false) and the
# plate's region in the reference's pixels (x0, y0, x1, y1).
PLATES = [("Smooth", 0.01, (345, 265, 935, 370)), ("Glossy", 0.05, (310, 382, 970, 465)),
          ("Rough", 0.1, (240, 485, 1040, 530)), ("SuperRough", 0.25, (160, 580, 1120, 632))]
# Copper, as the file gives it (Tungsten's "Cu").
ETA, K = "0.200438, 0.924033, 1.102212", "3.912949, 2.452848, 2.142188"
# label, distribution, the plates' reflectance factor, max depth (Mitsuba's convention; -1 unlimited)
MODELS = [("the file (GGX, factor 1), unlimited depth", "ggx", 1.0, -1), ("the file, direct light only", "ggx", 1.0, 2),
          ("Tungsten's (Beckmann, 0.3), direct light only", "beckmann", 0.3, 2)]


def numbers(text):
    return [float(v) for v in text.split()]


def read_scene(path):
    """The file's camera matrix (world to camera), fov, meshes (material, P, indices) and spheres
    (centre, radius, L)."""
    text = open(path).read()
    head, world = text.split("WorldBegin", 1)
    camera = numbers(re.search(r"Transform \[([^\]]*)\]", head).group(1))
    fov = float(re.search(r'"float fov" \[ ([\d.]+) \]', head).group(1))
    meshes, spheres, material, emission = [], [], None, None
    token = re.compile(r'NamedMaterial "(\w+)"|Shape "trianglemesh"(.*?)"integer indices" \[([^\]]*)\]|'
                       r'"rgb L" \[ ([\d.]+)|Transform \[([^\]]*)\]\s*Shape "sphere"\s*"float radius" \[ ([\d.]+)', re.S)
    for m in token.finditer(world):
        if m.group(1):
            material = m.group(1)
        elif m.group(4):
            emission = float(m.group(4))
        elif m.group(6):
            t = numbers(m.group(5))
            spheres.append(((t[12], t[13], t[14]), float(m.group(6)), emission))
        else:
            p = numbers(re.search(r'"point3 P" \[([^\]]*)\]', m.group(2)).group(1))
            meshes.append((material, p, [int(v) for v in m.group(3).split()]))
    return camera, fov, meshes, spheres


def write_ply(path, p, idx):
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(p) // 3}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(idx) // 3}\nproperty list uchar int vertex_indices\nend_header\n")
        for i in range(0, len(p), 3):
            f.write(f"{p[i]} {p[i + 1]} {p[i + 2]}\n")
        for i in range(0, len(idx), 3):
            f.write(f"3 {idx[i]} {idx[i + 1]} {idx[i + 2]}\n")


def write_xml(out_dir, scene, model, w, h, spp):
    import numpy as np
    camera, fov, meshes, spheres = scene
    _, dist, factor, depth = model
    # pbrt's camera space is left-handed (+x right), Mitsuba's right-handed (+x left).
    to_world = np.linalg.inv(np.array(camera).reshape(4, 4).T) @ np.diag([-1.0, 1.0, 1.0, 1.0])
    rough = {name: alpha for name, alpha, _ in PLATES}
    xml = ['<scene version="3.0.0">', f'<integrator type="path"><integer name="max_depth" value="{depth}"/></integrator>',
           '<sensor type="perspective">', f'<float name="fov" value="{fov}"/><string name="fov_axis" value="smaller"/>',
           '<transform name="to_world"><matrix value="' + " ".join(f"{v:.9g}" for v in to_world.ravel()) + '"/></transform>',
           f'<sampler type="independent"><integer name="sample_count" value="{spp}"/></sampler>',
           f'<film type="hdrfilm"><integer name="width" value="{w}"/><integer name="height" value="{h}"/>'
           '<rfilter type="box"/></film></sensor>']
    for i, (material, p, idx) in enumerate(meshes):
        write_ply(os.path.join(out_dir, f"mesh{i}.ply"), p, idx)
        if material in rough:
            bsdf = (f'<bsdf type="roughconductor"><string name="distribution" value="{dist}"/>'
                    f'<float name="alpha" value="{rough[material]}"/><rgb name="eta" value="{ETA}"/>'
                    f'<rgb name="k" value="{K}"/><rgb name="specular_reflectance" value="{factor}"/></bsdf>')
        else:
            bsdf = '<bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>'
        xml.append(f'<shape type="ply"><string name="filename" value="mesh{i}.ply"/>'
                   f'<boolean name="face_normals" value="true"/>{bsdf}</shape>')
    for c, r, L in spheres:
        xml.append(f'<shape type="sphere"><point name="center" x="{c[0]}" y="{c[1]}" z="{c[2]}"/>'
                   f'<float name="radius" value="{r}"/><bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>'
                   f'<emitter type="area"><rgb name="radiance" value="{L}"/></emitter></shape>')
    xml.append("</scene>")
    path = os.path.join(out_dir, "veach-mis.xml")
    with open(path, "w") as f:
        f.write("\n".join(xml) + "\n")
    return path


def render_mitsuba(xml, out):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    mi.Bitmap(mi.render(mi.load_file(xml)), channel_names=["R", "G", "B"]).write(out)


def plate_ratios(image, ref):
    import numpy as np
    lum = vt.luminance(image["R"], image["G"], image["B"])
    h, w = lum.shape
    rh, rw = ref.shape
    fy, fx = rh // h, rw // w
    r = ref.reshape(h, fy, w, fx).mean(axis=(1, 3))
    out = []
    for name, _, (x0, y0, x1, y1) in PLATES:
        sl = (slice(y0 // fy, y1 // fy), slice(x0 // fx, x1 // fx))
        out.append((name, float(lum[sl].mean() / np.maximum(r[sl].mean(), 1e-9))))
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scenes", default=os.path.join(os.path.dirname(os.path.dirname(HERE)), "shared", "scenes-pbrt"))
    p.add_argument("--size", default="320x180")
    p.add_argument("--spp", type=int, default=256)
    p.add_argument("--montecl", help="also render each model's XML with this montecl")
    p.add_argument("--keep", help="write the XML files and renders here (default: a temporary folder)")
    a = p.parse_args()
    folder = os.path.join(a.scenes, "veach-mis")
    if not os.path.isdir(folder):
        print(f"veach_mis_model: no veach-mis at {folder}", file=sys.stderr)
        return vt.EXIT_SKIP
    vt.ensure_numpy_mitsuba()
    w, h = (int(v) for v in a.size.split("x"))
    scene = read_scene(os.path.join(folder, "scene-v4.pbrt"))
    ref_path = os.path.join(folder, "TungstenRender.exr")
    ref = vt.read_layers(ref_path)
    ref_lum = vt.luminance(ref["R"], ref["G"], ref["B"])
    print("| model | renderer | " + " | ".join(n for n, _, _ in PLATES) + " | image mean | block median | 95th percentile |")
    print("|---|---|" + "---|" * (len(PLATES) + 3))
    with tempfile.TemporaryDirectory() as tmp:
        for i, model in enumerate(MODELS):
            out_dir = os.path.join(a.keep or tmp, f"model{i}")
            os.makedirs(out_dir, exist_ok=True)
            xml = write_xml(out_dir, scene, model, w, h, a.spp)
            renders = [("Mitsuba 3", os.path.join(out_dir, "mitsuba.exr"))]
            render_mitsuba(xml, renders[0][1])
            if a.montecl:
                out = os.path.join(out_dir, "montecl.exr")
                cmd = [a.montecl, "render", xml, "-q", "--sampler", "independent", "--seed", "7", "-o", out, "--overwrite"]
                r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                if r.returncode != 0:
                    print(f"veach_mis_model: {' '.join(cmd)}: exit {r.returncode}\n{r.stderr}", file=sys.stderr)
                    return 1
                renders.append(("montecl", out))
            for who, path in renders:
                image = vt.read_layers(path)
                ratios = plate_ratios(image, ref_lum)
                cells = " | ".join(f"{v:.3f}" for _, v in ratios)
                if "var.R" in image:
                    s = vt.compare(image, ref_path, 1)
                    stats = f"{s['mean'] * 100:+.2f}% | {s['median'] * 100:.2f}% | {s['p95'] * 100:.2f}%"
                else:
                    stats = "| |"
                print(f"| {model[0]} | {who} | {cells} | {stats} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
