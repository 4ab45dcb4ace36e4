#!/usr/bin/python3
"""Convergence of montecl's estimators: renders AO (uniform, cosine), direct lighting (light,
brdf, mis) and path tracing (unlimited depth) of the Cornell box at 1, 2, 4, ... spp, measures the RMSE against a high-spp reference
of the same estimator family, fits the slope of log RMSE against log spp (Monte Carlo: -1/2), and
plots RMSE vs spp on log-log axes with a 1/sqrt(N) guide. Writes docs/images/convergence.png and prints
the slopes. Needs build/montecl and ../shared/scenes (skips with a message when absent).

Usage: /usr/bin/python3 scripts/convergence.py [--size 48] [--max-spp 256] [--ref-spp 4096]

--vs-time: relMSE, mean FLIP and RMSE against process CPU time instead (median of --seeds runs per
point), montecl (independent, sobol with sub-sequences, the default, the default + --denoise, --adaptive) and
Mitsuba 3 (its samplers) on the Cornell box, 128x128 (scripts/convergence_time.py): writes
docs/images/convergence-time.png and prints the errors at the CPU time Mitsuba's best sampler
needs for 64 spp.
  /usr/bin/python3 scripts/convergence.py --vs-time [--integrator direct|path] [--size 128]
      [--ref-spp 4096] [--seeds 5] [--exposure 0] [--json FILE] [--replot] [--montecl EXE]
      [--mitsuba-samplers independent,multijitter,ldsampler] [--curves default,adaptive]
"""
import argparse
import math
import os
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read_pfm(path):
    """Mean of the three channels per pixel of a PFM written by montecl (little-endian)."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        fmt = "<" if scale < 0 else ">"
        data = struct.unpack(fmt + "%df" % (w * h * 3), f.read(w * h * 12))
    return [sum(data[3 * i:3 * i + 3]) / 3.0 for i in range(w * h)]


def render(exe, scene, out, size, spp, seed, extra):
    cmd = [exe, "render", scene, "-o", out, "--width", str(size), "--height", str(size),
           "--spp", str(spp), "--seed", str(seed), "-q"] + extra
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return read_pfm(out)


def rmse(a, b):
    return math.sqrt(sum((x - y) ** 2 for x, y in zip(a, b)) / len(a))


def slope(xs, ys):
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--size", type=int, default=None, help="default 48 (--vs-time: 128); the width with --height")
    ap.add_argument("--height", type=int, default=None, help="--vs-time: the image height (default: --size)")
    ap.add_argument("--scene", default=None,
                    help="--vs-time: a shared scene's name or a scene file (default: the Cornell box)")
    ap.add_argument("--max-spp", type=int, default=256)
    ap.add_argument("--ref-spp", type=int, default=4096)
    ap.add_argument("--out", default=None, help="default docs/images/convergence.png (--vs-time: convergence-time.png)")
    ap.add_argument("--vs-time", action="store_true", help="RMSE against wall time, montecl and Mitsuba 3")
    ap.add_argument("--json", help="--vs-time: keep the measurements in this file")
    ap.add_argument("--replot", action="store_true", help="--vs-time: plot --json's measurements again, no renders")
    ap.add_argument("--mitsuba-samplers", default="independent,multijitter,ldsampler")
    ap.add_argument("--integrator", choices=["direct", "path"], default="direct", help="--vs-time: direct MIS or path")
    ap.add_argument("--seeds", type=int, default=5, help="--vs-time: runs per point (the median is plotted)")
    ap.add_argument("--exposure", type=float, default=0.0, help="--vs-time: stops before FLIP's LDR clamp")
    ap.add_argument("--montecl", default=os.path.join(ROOT, "build", "montecl"), help="--vs-time: the binary")
    ap.add_argument("--curves", default="",
                    help="--vs-time: only the montecl curves whose labels contain one of these comma-separated words")
    args = ap.parse_args()
    scene = os.path.join(ROOT, "..", "shared", "scenes", "cornell-box", "scene.json")
    if args.vs_time and args.scene:
        named = os.path.join(ROOT, "..", "shared", "scenes", args.scene, "scene.json")
        scene = named if os.path.exists(named) else args.scene
    if args.vs_time:
        import convergence_time
        args.out = args.out or os.path.join(ROOT, "docs", "images", "convergence-time.png")
        args.scene, args.montecl = os.path.abspath(scene), os.path.abspath(args.montecl)
        if args.seeds < 1:
            ap.error("--seeds must be >= 1")
        args.size = args.size or 128
        args.height = args.height or args.size
        if args.replot and not args.json:
            ap.error("--replot needs --json")
        return convergence_time.main(args)
    args.out = args.out or os.path.join(ROOT, "docs", "images", "convergence.png")
    args.size = args.size or 48
    if not os.path.exists(scene):
        print("convergence: skipping: %s not found (../shared/scenes is not beside this checkout)" % scene)
        return 0
    exe = os.path.join(ROOT, "build", "montecl")
    estimators = [
        ("AO uniform", ["--integrator", "ao", "--ao-sampling", "uniform"], "ao"),
        ("AO cosine", ["--integrator", "ao", "--ao-sampling", "cosine"], "ao"),
        ("direct light", ["--integrator", "direct", "--direct-sampling", "light"], "direct"),
        ("direct brdf", ["--integrator", "direct", "--direct-sampling", "brdf"], "direct"),
        ("direct mis", ["--integrator", "direct", "--direct-sampling", "mis"], "direct"),
        ("path", ["--integrator", "path"], "path"),
    ]
    spps = [2 ** k for k in range(int(math.log2(args.max_spp)) + 1)]
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "img.pfm")
        # One reference per family, with the lowest-variance estimator and another seed.
        refs = {
            "ao": render(exe, scene, out, args.size, args.ref_spp, 1000, estimators[1][1]),
            "direct": render(exe, scene, out, args.size, args.ref_spp, 1000, estimators[4][1]),
            "path": render(exe, scene, out, args.size, args.ref_spp, 1000, estimators[5][1]),
        }
        for name, extra, family in estimators:
            errors = [rmse(render(exe, scene, out, args.size, spp, 7, extra), refs[family]) for spp in spps]
            results[name] = errors
            print("%-13s slope of log RMSE vs log spp: %+.3f   RMSE at %d spp: %.4g" %
                  (name, slope(spps, errors), spps[-1], errors[-1]))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for name, errors in results.items():
        ax.loglog(spps, errors, "o-", label="%s (slope %.2f)" % (name, slope(spps, errors)))
    top = max(e[0] for e in results.values())
    ax.loglog(spps, [top / math.sqrt(s) for s in spps], "k--", label="1/sqrt(N)")
    ax.set_xlabel("samples per pixel")
    ax.set_ylabel("RMSE against a %d spp reference" % args.ref_spp)
    ax.set_title("Cornell box, %dx%d" % (args.size, args.size))
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print("wrote", args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
