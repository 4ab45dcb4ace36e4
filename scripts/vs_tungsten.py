#!/usr/bin/env python3
"""vs_tungsten.py: renders the shared pbrt-v4 scenes with montecl and compares them with Tungsten's
reference renders (TungstenRender.exr) per block of pixels; prints the table of docs/pbrt-format.md.

    scripts/vs_tungsten.py [--montecl build/montecl] [--scenes ../shared/scenes-pbrt] [--spp 1024]
                           [--only NAME] [--size WxH] [--device P:D|host]

Each row renders one scene with independent samples (`--sampler independent --seed 7`, so that a
pixel's var / n is its squared standard error), the file's camera and materials and the row's depth
and filter, at the compared size (`--filter box`: the reference is box-filtered down to it; the
file's own filter radius is in pixels of the full size) or at `up` times it with spp / up^2 samples
(the same samples per compared pixel) and then box-filtered down like the reference. The
reference's luminance is box-filtered to the compared size; both are averaged over blocks of 8 x 8
pixels of that size (a partial block at the edge is left out). Per row: the image mean's relative
difference, the median and 95th percentile of the blocks' |relative difference|, and the largest
|z| with z = (montecl - Tungsten) / sqrt(se^2 + (0.0025 Tungsten)^2), se the block's standard
error from montecl's var layers (the luminance's deviation bounded by the channels' weighted sum,
so z errs low) and 0.25% a floor for what no sample count removes (the reference's own noise: 64
adaptive samples per pixel); and the blocks' median relative standard error.

The rows "Tungsten's filter" render cornell-box with the settings of Tungsten's own scene
(tungsten-scene.json) where the pbrt conversion changed them: its camera's tent filter of radius 1
pixel at the reference's 1024 x 1024 and 64 bounces (pbrt maxdepth 64, montecl --max-depth 65).
"and lamp" also gives the lamp Tungsten's "null" BSDF (light passes through it; pbrt's
`interface`, written into a copy of the file in place of the conversion's opaque black `diffuse`).

veach-mis's reference was rendered from Tungsten's own scene, whose plates (Beckmann, albedo 0.3) and
direct-light-only setting the pbrt-v4 file cannot carry: its rows show what pbrt-v4's semantics give;
scripts/veach_mis_model.py renders Tungsten's model (as Mitsuba XML) and shows the agreement.

Reads EXR through Mitsuba 3's Bitmap: run with any python3, the script re-runs itself with the
Mitsuba venv's python (scripts/setup.sh --mitsuba; $MONTECL_MITSUBA_VENV overrides). Exit 77 when
that venv or the shared scenes are missing.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
VENV = os.environ.get("MONTECL_MITSUBA_VENV",
                      os.path.join(os.path.expanduser("~"), ".cache", "montecl", "mitsuba-venv"))
EXIT_SKIP = 77
FLOOR = 0.0025
BLOCK = 8

# label, scene, compared width and height, rendered at `up` times that size (spp / up^2 samples per
# pixel: the same samples per compared pixel), montecl's filter, max depth, Tungsten's lamp.
ROWS = [
    ("cornell-box", "cornell-box", 64, 64, 1, "box", -1, False),
    ("cornell-box", "cornell-box", 256, 256, 1, "box", -1, False),
    ("cornell-box, Tungsten's filter", "cornell-box", 256, 256, 4, "triangle,radius=1", 65, False),
    ("cornell-box, Tungsten's filter and lamp", "cornell-box", 256, 256, 4, "triangle,radius=1", 65, True),
    ("veach-mis", "veach-mis", 160, 90, 1, "box", -1, False),
    ("veach-mis, direct light only", "veach-mis", 160, 90, 1, "box", 2, False),
]


def ensure_numpy_mitsuba():
    try:
        import mitsuba  # noqa: F401
        import numpy  # noqa: F401
        return
    except ImportError:
        pass
    py = os.path.join(VENV, "bin", "python")
    if os.path.exists(py) and os.path.realpath(sys.prefix) != os.path.realpath(VENV):
        os.execv(py, [py, os.path.abspath(sys.argv[0])] + sys.argv[1:])  # the script run, which may import this one
    print(f"vs_tungsten: needs numpy and Mitsuba 3 (no venv at {VENV}); run scripts/setup.sh --mitsuba",
          file=sys.stderr)
    sys.exit(EXIT_SKIP)


def read_layers(path):
    import mitsuba as mi
    import numpy as np
    mi.set_variant("scalar_rgb")
    bmp = mi.Bitmap(path)
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    data = np.array(bmp, dtype=np.float64).reshape(bmp.height(), bmp.width(), len(names))
    return {n: data[:, :, i] for i, n in enumerate(names)}


def luminance(r, g, b):
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def tungsten_lamp_copy(scene_file, out_dir):
    """A copy of cornell-box's file whose lamp is Tungsten's null BSDF (pbrt's interface) and whose
    integrator has Tungsten's 64 bounces."""
    text = open(scene_file).read()
    lamp = re.compile(r'MakeNamedMaterial "Light"\s+"string type" \[ "diffuse" \]\s+"rgb reflectance" \[ 0 0 0 \]')
    if not lamp.search(text):
        raise SystemExit(f"vs_tungsten: {scene_file}: the lamp's material is not the conversion's black diffuse")
    text = lamp.sub('MakeNamedMaterial "Light" "string type" [ "interface" ]', text)
    text = re.sub(r'"integer maxdepth" \[ \d+ \]', '"integer maxdepth" [ 64 ]', text)
    path = os.path.join(out_dir, "cornell-box-tungsten-lamp.pbrt")
    with open(path, "w") as f:
        f.write(text)
    return path


def compare(render, ref_path, up):
    """Block statistics of a render `up` times the compared size against the reference."""
    import numpy as np
    ref = read_layers(ref_path)
    h, w = render["R"].shape[0] // up, render["R"].shape[1] // up
    rh, rw = ref["R"].shape
    if rh % h or rw % w:
        raise SystemExit(f"vs_tungsten: {w}x{h} does not divide the reference's {rw}x{rh}")
    fy, fx = rh // h, rw // w
    ref_lum = luminance(ref["R"], ref["G"], ref["B"]).reshape(h, fy, w, fx).mean(axis=(1, 3))
    lum = luminance(render["R"], render["G"], render["B"])
    n = np.maximum(render["samples"], 1.0)
    sd = (0.2126 * np.sqrt(np.maximum(render["var.R"], 0)) + 0.7152 * np.sqrt(np.maximum(render["var.G"], 0)) +
          0.0722 * np.sqrt(np.maximum(render["var.B"], 0)))
    var = sd * sd / n  # each pixel's own samples: the pixels are independent
    bh, bw = h // BLOCK, w // BLOCK

    def blocks(a, k):  # means of (BLOCK k)^2 pixels of an image k times the compared size
        b = BLOCK * k
        return a[:bh * b, :bw * b].reshape(bh, b, bw, b).mean(axis=(1, 3))

    m, r = blocks(lum, up), blocks(ref_lum, 1)
    se = np.sqrt(blocks(var, up) / (BLOCK * up) ** 2)
    rel = np.abs(m - r) / np.maximum(r, 1e-6)
    sz = np.sqrt(se ** 2 + (FLOOR * r) ** 2)
    z = np.abs(m - r) / np.where(sz > 0, sz, 1.0)  # a block black in both (no samples' spread): z 0
    worst = np.unravel_index(np.argmax(z), z.shape)
    return {
        "mean": (m.sum() - r.sum()) / r.sum(),
        "median": float(np.sort(rel.ravel())[rel.size // 2]),
        "p95": float(np.sort(rel.ravel())[int(np.ceil(0.95 * rel.size)) - 1]),
        "maxz": float(z.max()),
        "worst": (int(worst[1]), int(worst[0]), float((m - r)[worst] / r[worst])),
        "se": float(np.median(se / np.maximum(r, 1e-6))),
    }


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--montecl", default=os.path.join(ROOT, "build", "montecl"))
    p.add_argument("--scenes", default=os.path.join(os.path.dirname(ROOT), "shared", "scenes-pbrt"))
    p.add_argument("--spp", type=int, default=1024)
    p.add_argument("--only", help="rows of this scene only (cornell-box, veach-mis)")
    p.add_argument("--size", help="compared size WxH for every row (default: each row's own); it must divide the reference's")
    p.add_argument("--device", help="montecl's --device (default: its own choice)")
    a = p.parse_args()
    if a.size and not re.fullmatch(r"[1-9][0-9]*x[1-9][0-9]*", a.size):
        p.error(f"--size {a.size}: give WxH, e.g. 320x180")
    if not os.path.isdir(a.scenes):
        print(f"vs_tungsten: no shared pbrt scenes at {a.scenes}", file=sys.stderr)
        return EXIT_SKIP
    ensure_numpy_mitsuba()
    print("| scene | rendered, spp | filter | depth | time | image mean | block median abs | 95th percentile "
          "| max z (block x, y: rel) | median se |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for label, name, w, h, up, filt, depth, lamp in ROWS:
            if a.only and name != a.only:
                continue
            if a.size:
                w, h = (int(v) for v in a.size.split("x"))
            scene = os.path.join(a.scenes, name, "scene-v4.pbrt")
            if lamp:
                scene = tungsten_lamp_copy(scene, tmp)
            out = os.path.join(tmp, "out.exr")
            spp = max(1, a.spp // (up * up))
            cmd = [a.montecl, "render", scene, "-q", "--width", str(w * up), "--height", str(h * up), "--spp",
                   str(spp), "--sampler", "independent", "--seed", "7", "--filter", filt, "--max-depth", str(depth),
                   "-o", out]
            if a.device:
                cmd += ["--device", a.device]
            t0 = time.time()
            r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            took = time.time() - t0
            if r.returncode != 0:
                print(f"vs_tungsten: {' '.join(cmd)}: exit {r.returncode}\n{r.stderr}", file=sys.stderr)
                return 1
            s = compare(read_layers(out), os.path.join(a.scenes, name, "TungstenRender.exr"), up)
            wx, wy, wrel = s["worst"]
            size = f"{w} x {h}, {a.spp}" if up == 1 else f"{w * up} x {h * up}, {spp}, to {w} x {h}"
            print(f"| {label} | {size} | {filt} | {'unlimited' if depth < 0 else depth} | {took:.0f} s | "
                  f"{s['mean'] * 100:+.2f}% | {s['median'] * 100:.2f}% | {s['p95'] * 100:.2f}% | "
                  f"{s['maxz']:.1f} ({wx}, {wy}: {wrel * 100:+.1f}%) | {s['se'] * 100:.2f}% |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
