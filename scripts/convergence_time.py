"""convergence_time.py: error against wall time (`scripts/convergence.py --vs-time`). Reads the
Cornell box or another scene (--scene: a ../shared/scenes name or a file; --size W --height H),
runs build/montecl and Mitsuba 3 (through scripts/vs_mitsuba.py's scene translation and worker,
imported), writes docs/images/convergence-time.png (--out) and prints a table; --json keeps the
measurements.

Curves, each at spp 1, 4, 16, ... up to --max-spp (default 256; montecl one power of 4 further): montecl `--sampler independent`,
montecl `--sampler sobol` (the default, 4 sub-sequences), montecl sobol + `--denoise` (when Open
Image Denoise is installed), and Mitsuba 3 with each of --mitsuba-samplers (default independent,
multijitter, ldsampler: Mitsuba 3.9 has independent, stratified, multijitter, orthogonal and
ldsampler; powers of 4 are valid sample counts for all of these but orthogonal). Integrator: direct
lighting with MIS (montecl `--integrator direct --direct-sampling mis` = Mitsuba `direct`).

Time: the wall time of the whole process that makes the image (montecl: `render ... -o X.exr`,
scene load, BVH, the cached kernel program, denoising included; Mitsuba: the worker process, Python
start and `import mitsuba`, scene load, Dr.Jit's cached kernels, render, output), after one
untimed warm-up run of each configuration; one run per point, so on a shared machine the times are
indicative. Mitsuba's own render time inside the process (mi.render) is kept in the JSON too.

Error: linear RGB RMSE over the whole image against one reference, montecl sobol at --ref-spp with
another seed; its own mean squared error (the mean of its err.R/G/B layers, the sub-sequence
estimate) is subtracted from each MSE, and printed.

The measuring runs in Mitsuba's venv (numpy, mitsuba), the plot in the system python
(matplotlib: `scripts/setup.sh --plots`).
"""
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import vs_mitsuba as vm  # noqa: E402

MONTECL_CURVES = [  # (label, extra montecl arguments)
    ("montecl independent", ["--sampler", "independent"]),
    ("montecl sobol", ["--sampler", "sobol"]),
    ("montecl sobol + denoise", ["--sampler", "sobol", "--denoise"]),
]


def cpu_model():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return platform.machine()


def load_average():
    with open("/proc/loadavg") as f:
        return [float(x) for x in f.read().split()[:3]]


def read_exr_rgb(path, prefix=""):
    """(H x W x 3 float64 of channels <prefix>R/G/B, dict of all channels) of an EXR, by name."""
    import mitsuba as mi
    import numpy as np
    bmp = mi.Bitmap(path)
    names = [bmp.struct_()[i].name for i in range(bmp.channel_count())]
    data = np.array(bmp, dtype=np.float64).reshape(bmp.height(), bmp.width(), len(names))
    ch = {n: data[:, :, i] for i, n in enumerate(names)}
    return np.stack([ch[prefix + c] for c in "RGB"], axis=-1), ch


def measure(a):
    """Runs every curve; returns the measurements (a dict, JSON-ready)."""
    import numpy as np
    import mitsuba as mi
    mi.set_variant("scalar_rgb")  # the driver only reads images
    scene = a.scene
    sc = vm.load_scene(scene)
    size, height = a.size, a.height
    # Mitsuba's spp up to --max-spp, montecl's one step further (it needs more samples for its time).
    levels = [n for n in [1, 4, 16, 64, 256, 1024] if n <= a.max_spp]
    common = ["--width", str(size), "--height", str(height), "--integrator", "direct", "--direct-sampling", "mis",
              "--overwrite", "-q"]
    work = tempfile.mkdtemp(prefix="convergence_time_")
    res = {"scene": os.path.relpath(scene, ROOT), "size": size, "height": height, "ref_spp": a.ref_spp, "curves": {},
           "date": datetime.date.today().isoformat(), "machine": f"{os.cpu_count()} cores, {cpu_model()}",
           "load_before": load_average()}
    ref_exr = os.path.join(work, "ref.exr")
    # Warm-up: a new build compiles its kernel program once (minutes on a loaded machine).
    vm.run_timed([a.montecl, "render", scene, "-o", ref_exr, "--spp", "1"] + common)
    wall, _, _ = vm.run_timed([a.montecl, "render", scene, "-o", ref_exr, "--spp", str(a.ref_spp), "--seed", "1000",
                               "--sampler", "sobol"] + common)
    ref, ch = read_exr_rgb(ref_exr)
    ref_mse = float(np.mean(np.stack([ch["err." + c] for c in "RGB"]))) if "err.R" in ch else 0.0
    res["ref_seconds"], res["ref_rmse_estimate"] = wall, math.sqrt(ref_mse)
    print(f"reference: montecl sobol {a.ref_spp} spp in {wall:.1f} s, its own RMSE estimate {math.sqrt(ref_mse):.3g}",
          flush=True)

    def error(img):
        return math.sqrt(max(float(np.mean((img - ref) ** 2)) - ref_mse, 0.0))

    have_oidn = subprocess.run([a.montecl, "render", scene, "-o", os.path.join(work, "probe.exr"), "--spp", "1",
                                "--width", "4", "--height", "4", "--denoise", "-q"], capture_output=True).returncode == 0
    for label, extra in MONTECL_CURVES:
        denoise = "--denoise" in extra
        if denoise and not have_oidn:
            print(f"{label}: skipped (Open Image Denoise not installed: scripts/setup.sh --oidn)")
            continue
        out = os.path.join(work, "m.exr")
        cmd = lambda spp: [a.montecl, "render", scene, "-o", out, "--spp", str(spp), "--seed", "7"] + common + extra
        vm.run_timed(cmd(1))  # warm-up: the kernel program cache, OIDN's libraries
        pts = []
        for spp in levels + [levels[-1] * 4]:
            wall, cpu, _ = vm.run_timed(cmd(spp))
            img, _ = read_exr_rgb(out, "denoised." if denoise else "")
            pts.append({"spp": spp, "wall_s": wall, "cpu_s": cpu, "rmse": error(img)})
            print(f"{label:28s} {spp:5d} spp {wall:7.2f} s  RMSE {pts[-1]['rmse']:.4g}", flush=True)
        res["curves"][label] = pts

    variant = "llvm_ad_rgb" if os.path.exists(vm.LLVM19) or "DRJIT_LIBLLVM_PATH" in os.environ else "scalar_rgb"
    base = vm.worker_base(sc, work, size, height, variant, "direct", "mis", -1, 5)
    env = vm.mitsuba_env()
    for sampler in a.mitsuba_samplers.split(","):
        label = f"Mitsuba {sampler}"

        def cmd(spp):
            path = os.path.join(work, f"mi-{sampler}-{spp}.json")
            with open(path, "w") as f:
                json.dump(dict(base, spp=spp, seeds=[7], sampler=sampler, out=os.path.join(work, "mi.npz")), f)
            return [sys.executable, os.path.join(HERE, "vs_mitsuba.py"), "--worker", path]

        vm.run_timed(cmd(1), env)  # warm-up: Dr.Jit's kernel cache
        pts = []
        for spp in levels:
            wall, cpu, _ = vm.run_timed(cmd(spp), env)
            npz = np.load(os.path.join(work, "mi.npz"))
            res["mitsuba_variant"] = str(npz["variant"])
            pts.append({"spp": spp, "wall_s": wall, "cpu_s": cpu, "render_s": float(npz["render_s"]),
                        "rmse": error(npz["mean"])})
            print(f"{label:28s} {spp:5d} spp {wall:7.2f} s  RMSE {pts[-1]['rmse']:.4g}", flush=True)
        res["curves"][label] = pts
    res["mitsuba_version"] = mi.__version__
    res["load_after"] = load_average()
    return res


def at_time(pts, t):
    """RMSE of a curve at wall time t: log-log interpolation between its points; past its slowest
    point, that point carried along 1/sqrt(time) (marked extrapolated); None before its fastest
    (no image that fast)."""
    pts = sorted(pts, key=lambda p: p["wall_s"])
    ts, es = [p["wall_s"] for p in pts], [p["rmse"] for p in pts]
    if t < ts[0]:
        return None, False
    if t >= ts[-1]:
        return es[-1] * math.sqrt(ts[-1] / t), True
    for i in range(len(ts) - 1):
        if ts[i] <= t <= ts[i + 1]:
            if ts[i + 1] == ts[i] or es[i] <= 0 or es[i + 1] <= 0:
                return es[i], False
            f = math.log(t / ts[i]) / math.log(ts[i + 1] / ts[i])
            return math.exp(math.log(es[i]) + f * (math.log(es[i + 1]) - math.log(es[i]))), False
    return es[-1], False


def table(res):
    base = res["curves"]["Mitsuba independent"]
    t = next(p["wall_s"] for p in base if p["spp"] == 64)
    e0 = next(p["rmse"] for p in base if p["spp"] == 64)
    lines = [f"RMSE at Mitsuba independent's 64-spp wall time ({t:.2f} s); ratio: Mitsuba independent's RMSE / the curve's",
             "", "| curve | RMSE at %.2f s | ratio to Mitsuba independent |" % t, "|---|---|---|"]
    for label, pts in res["curves"].items():
        e, extra = at_time(pts, t)
        if e is None:
            fastest = min(p["wall_s"] for p in pts)
            lines.append(f"| {label} | none (its fastest image took {fastest:.2f} s) | - |")
            continue
        lines.append(f"| {label} | {e:.4g}{' (extrapolated)' if extra else ''} | {e0 / e:.2f} |")
    return "\n".join(lines)


def plot(res, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for label, pts in res["curves"].items():
        style = "s--" if label.startswith("Mitsuba") else "o-"
        ax.loglog([p["wall_s"] for p in pts], [p["rmse"] for p in pts], style, label=label)
    ax.set_xlabel("wall time of the whole process, s (one run per point: indicative)")
    ax.set_ylabel("RMSE against a %d-spp montecl sobol reference" % res["ref_spp"])
    name = os.path.basename(os.path.dirname(res["scene"]))
    ax.set_title("%s, direct MIS, %dx%d; %s, load %.1f-%.1f" %
                 (name, res["size"], res.get("height", res["size"]), res["date"], res["load_before"][0],
                  res["load_after"][0]), fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print("wrote", out)


def main(a):
    """--vs-time: measures in Mitsuba's venv (this file re-run there with --measure), then plots."""
    if not os.path.exists(a.scene):
        print("convergence: skipping: %s not found (../shared/scenes is not beside this checkout)" % a.scene)
        return 0
    py = os.path.join(vm.VENV, "bin", "python")
    if not os.path.exists(py):
        print(f"convergence --vs-time: Mitsuba 3 is not installed (no venv at {vm.VENV}); run scripts/setup.sh --mitsuba",
              file=sys.stderr)
        return vm.EXIT_SKIP
    data = a.json or os.path.join(tempfile.mkdtemp(prefix="convergence_time_"), "data.json")
    if not a.replot:
        cmd = [py, os.path.abspath(__file__), "--measure", data, "--scene", a.scene, "--size", str(a.size),
               "--height", str(a.height), "--max-spp", str(a.max_spp), "--ref-spp", str(a.ref_spp),
               "--montecl", a.montecl, "--mitsuba-samplers", a.mitsuba_samplers]
        subprocess.run(cmd, env=vm.mitsuba_env(), check=True)
    with open(data) as f:
        res = json.load(f)
    print(table(res))
    print("load average (1, 5, 15 min) before %s, after %s" % (res["load_before"], res["load_after"]))
    plot(res, a.out)
    return 0


if __name__ == "__main__":  # the measuring half, in Mitsuba's venv
    import argparse
    p = argparse.ArgumentParser()
    p.add_argument("--measure", required=True)
    p.add_argument("--scene", required=True)
    p.add_argument("--size", type=int, required=True)
    p.add_argument("--height", type=int, required=True)
    p.add_argument("--max-spp", type=int, required=True)
    p.add_argument("--ref-spp", type=int, required=True)
    p.add_argument("--montecl", required=True)
    p.add_argument("--mitsuba-samplers", required=True)
    args = p.parse_args()
    result = measure(args)
    with open(args.measure, "w") as f:
        json.dump(result, f, indent=1)
