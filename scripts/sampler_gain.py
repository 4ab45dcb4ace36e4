"""sampler_gain.py: the MSE gain of sobol over independent sampling at equal spp. Renders a scene
with build/montecl (or --montecl) under independent, sobol (one sequence, the default) and sobol
with 4 sub-sequences (--error-estimate) over --seeds seeds, reads the PFMs, and prints per spp each
sampler's MSE and relMSE, taken as the spread of the pixel means over the seeds (the estimators are
unbiased, so that spread is their MSE; no reference needed), and the gains over independent.
Runs in Mitsuba's venv (numpy). Writes only temporary PFMs.

  ~/.cache/montecl/mitsuba-venv/bin/python scripts/sampler_gain.py SCENE [--width 64 --height 64]
      [--spp 16,64] [--seeds 8] [--integrator path]
"""
import argparse
import os
import subprocess
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SAMPLERS = {"independent": ["--sampler", "independent"], "sobol": ["--sampler", "sobol"],
            "sobol, 4 sub-sequences": ["--sampler", "sobol", "--error-estimate", "--sobol-splits", "4"]}


def read_pfm(path):
    with open(path, "rb") as f:
        f.readline()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    return data.reshape(h, w, 3).astype(np.float64)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("--montecl", default=os.path.join(ROOT, "build", "montecl"))
    ap.add_argument("--width", default="64")
    ap.add_argument("--height", default="64")
    ap.add_argument("--spp", default="16,64")
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--integrator", default="path")
    a = ap.parse_args()
    if a.seeds < 2:
        ap.error("--seeds must be >= 2 (the MSE is the spread over seeds)")
    out = os.path.join(tempfile.mkdtemp(prefix="sampler_gain_"), "img.pfm")
    for spp in [int(x) for x in a.spp.split(",")]:
        res = {}
        for name, extra in SAMPLERS.items():
            imgs = []
            for seed in range(100, 100 + a.seeds):
                subprocess.run([a.montecl, "render", a.scene, "-q", "--width", a.width, "--height", a.height, "--spp",
                                str(spp), "--seed", str(seed), "--integrator", a.integrator, "--overwrite", "-o", out]
                               + extra, check=True, capture_output=True)
                imgs.append(read_pfm(out))
            stack = np.stack(imgs)
            var, mean = stack.var(axis=0, ddof=1), stack.mean(axis=0)
            res[name] = (float(var.mean()), float((var / (mean * mean + 0.01)).mean()))
            print(f"{spp:5d} spp {name:24s} MSE {res[name][0]:.4g}  relMSE {res[name][1]:.4g}", flush=True)
        base = res["independent"]
        for name in list(SAMPLERS)[1:]:
            print(f"{spp:5d} spp gain over independent, {name}: MSE {base[0] / res[name][0]:.2f}, "
                  f"relMSE {base[1] / res[name][1]:.2f}", flush=True)


if __name__ == "__main__":
    main()
