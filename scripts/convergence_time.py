"""convergence_time.py: error against time (`scripts/convergence.py --vs-time`). Reads the
Cornell box or another scene (--scene: a ../shared/scenes name or a file; --size W --height H),
runs build/montecl and Mitsuba 3 (through scripts/vs_mitsuba.py's scene translation and worker,
imported), writes docs/images/convergence-time.png (--out) and prints a table; --json keeps the
measurements.

Curves, each at spp 1, 4, 16, ... up to --max-spp (default 256; montecl one power of 4 further):
montecl `--sampler independent`; montecl sobol with 4 sub-sequences and its error estimate
(`--sobol-splits 4 --error-estimate`, what every sobol render used before the estimate became
opt-in); montecl's default (sobol, one Owen-scrambled sequence per pixel); the default +
`--denoise` (when Open Image Denoise is installed); montecl `--adaptive` (sobol, its first pass of
16 then the budget shared out by estimated relative error; `--max-spp` 16x the budget); and Mitsuba 3 with each of --mitsuba-samplers
(default independent, multijitter, ldsampler: powers of 4 are valid sample counts for all of them).
--curves keeps the montecl curves whose labels contain one of its comma-separated words (default: all).
Integrator: --integrator direct (MIS: montecl `--direct-sampling mis` = Mitsuba `direct`) or path
(unlimited depth, Russian roulette from depth 5 in both).

Time: the CPU time (user + system, every thread) of the whole process that makes the image
(montecl: `render ... -o X.exr`, scene load, BVH, the cached kernel program, denoising included;
Mitsuba: the worker process, Python start and `import mitsuba`, scene load, Dr.Jit's cached
kernels, render, output), after one untimed warm-up run of each configuration. CPU time rather
than wall time because the machine is shared and Mitsuba is multithreaded; wall time is kept too.

Errors, each point the median over --seeds runs (seeds 1..N; time the median too): relMSE (ε =
0.01, the largest 0.1% of per-pixel errors dropped) and mean LDR-FLIP (exposure --exposure stops,
clamped, sRGB) from scripts/image_metrics.py, and whole-image linear RMSE, against one reference:
montecl at --ref-spp with seed 1000 (sobol, 4 sub-sequences: its own relMSE, from their spread, is
printed: it should be far below every curve's).

The measuring runs in Mitsuba's venv (numpy, mitsuba, flip_evaluator), the plot in the system python
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
    ("montecl sobol, 4 sub-sequences + estimate", ["--sampler", "sobol", "--sobol-splits", "4", "--error-estimate"]),
    ("montecl default (sobol)", ["--sampler", "sobol"]),
    ("montecl default + denoise", ["--sampler", "sobol", "--denoise"]),
    ("montecl adaptive", ["--sampler", "sobol", "--adaptive"]),
]
# The reference: sobol with its sub-sequence error estimate, so its own error can be printed.
REFERENCE_ARGS = ["--sampler", "sobol", "--sobol-splits", "4", "--error-estimate"]
METRICS = ("relmse", "flip", "rmse")


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


def median(xs):
    xs = sorted(xs)
    n = len(xs)
    return xs[n // 2] if n % 2 else 0.5 * (xs[n // 2 - 1] + xs[n // 2])


def measure(a):
    """Runs every curve; returns the measurements (a dict, JSON-ready)."""
    import numpy as np
    import mitsuba as mi
    import image_metrics as im  # numpy and flip_evaluator: Mitsuba's venv
    mi.set_variant("scalar_rgb")  # the driver only reads images
    scene = a.scene
    sc = vm.load_scene(scene)
    # The scene's render block over montecl's own defaults (light_samples ...), as vs_mitsuba.py does.
    defaults = subprocess.run([a.montecl, "settings", "--json"], check=True, capture_output=True, text=True).stdout
    sc["render"] = {**json.loads(defaults), **sc["render"]}
    size, height = a.size, a.height
    # Mitsuba's spp up to --max-spp, montecl's one step further (it needs more samples for its time).
    levels = [n for n in [1, 4, 16, 64, 256, 1024] if n <= a.max_spp]
    integ = ["--integrator", "direct", "--direct-sampling", "mis"] if a.integrator == "direct" else \
        ["--integrator", "path", "--max-depth", "-1", "--rr-depth", "5"]
    common = ["--width", str(size), "--height", str(height), "--overwrite", "-q"] + integ
    seeds = list(range(1, a.seeds + 1))
    work = tempfile.mkdtemp(prefix="convergence_time_")
    res = {"scene": os.path.relpath(scene, ROOT), "size": size, "height": height, "ref_spp": a.ref_spp, "curves": {},
           "integrator": a.integrator, "seeds": a.seeds, "exposure": a.exposure,
           "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
           "machine": f"{os.cpu_count()} cores, {cpu_model()}", "load_before": load_average()}
    ref_exr = os.path.join(work, "ref.exr")
    # Warm-up: a new build compiles its kernel program once (minutes on a loaded machine).
    vm.run_timed([a.montecl, "render", scene, "-o", ref_exr, "--spp", "1"] + common + REFERENCE_ARGS)
    wall, cpu, _ = vm.run_timed([a.montecl, "render", scene, "-o", ref_exr, "--spp", str(a.ref_spp), "--seed",
                                 "1000"] + common + REFERENCE_ARGS)
    ref, ch = read_exr_rgb(ref_exr)
    err = np.stack([ch["err." + c] for c in "RGB"], axis=-1)  # the reference's own squared error, per channel
    ref_mse = float(np.mean(err))
    ref_relmse = float(np.mean(err / (ref * ref + im.EPS)))
    res.update(ref_seconds=wall, ref_cpu_s=cpu, ref_rmse_estimate=math.sqrt(ref_mse), ref_relmse_estimate=ref_relmse)
    print(f"reference: montecl sobol {a.ref_spp} spp, {wall:.0f} s wall, {cpu:.0f} s CPU; its own error estimate: "
          f"RMSE {math.sqrt(ref_mse):.3g}, relMSE {ref_relmse:.3g}", flush=True)

    def errors(img):
        return {"relmse": im.relmse(img, ref), "flip": im.mean_flip(img, ref, a.exposure),
                "rmse": math.sqrt(float(np.mean((img - ref) ** 2)))}

    def point(spp, runs):
        """One point: the median over seeds of each error and of the times; every run kept."""
        p = {"spp": spp, "runs": runs}
        for k in ("wall_s", "cpu_s") + METRICS:
            p[k] = median([r[k] for r in runs])
        return p

    def show(label, p):
        print(f"{label:42s} {p['spp']:5d} spp {p['cpu_s']:7.2f} CPU s {p['wall_s']:6.2f} s  relMSE {p['relmse']:.4g}"
              f"  FLIP {p['flip']:.4f}  RMSE {p['rmse']:.4g}", flush=True)

    have_oidn = subprocess.run([a.montecl, "render", scene, "-o", os.path.join(work, "probe.exr"), "--spp", "1",
                                "--width", "4", "--height", "4", "--denoise", "-q"], capture_output=True).returncode == 0
    wanted = [w for w in a.curves.split(",") if w]
    for label, extra in MONTECL_CURVES:
        if wanted and not any(w in label for w in wanted):
            continue
        denoise = "--denoise" in extra
        if denoise and not have_oidn:
            print(f"{label}: skipped (Open Image Denoise not installed: scripts/setup.sh --oidn)")
            continue
        out = os.path.join(work, "m.exr")
        # --adaptive: the most one pixel may take, 16x the budget (it must be at least the budget).
        cap = lambda spp: ["--max-spp", str(16 * spp)] if "--adaptive" in extra else []
        cmd = lambda spp, seed: [a.montecl, "render", scene, "-o", out, "--spp", str(spp), "--seed", str(seed)] + \
            common + extra + cap(spp)
        vm.run_timed(cmd(1, 1))  # warm-up: the kernel program cache, OIDN's libraries
        pts = []
        for spp in levels + [levels[-1] * 4]:
            runs = []
            for seed in seeds:
                wall, cpu, _ = vm.run_timed(cmd(spp, seed))
                img, _ = read_exr_rgb(out, "denoised." if denoise else "")
                runs.append(dict(errors(img), seed=seed, wall_s=wall, cpu_s=cpu))
            pts.append(point(spp, runs))
            show(label, pts[-1])
        res["curves"][label] = pts

    variant = "llvm_ad_rgb" if os.path.exists(vm.LLVM19) or "DRJIT_LIBLLVM_PATH" in os.environ else "scalar_rgb"
    base = vm.worker_base(sc, work, size, height, variant, a.integrator, "mis", -1, 5)
    env = vm.mitsuba_env()
    for sampler in a.mitsuba_samplers.split(","):
        label = f"Mitsuba {sampler}"

        def cmd(spp, seed):
            path = os.path.join(work, f"mi-{sampler}-{spp}.json")
            with open(path, "w") as f:
                json.dump(dict(base, spp=spp, seeds=[seed], sampler=sampler, out=os.path.join(work, "mi.npz")), f)
            return [sys.executable, os.path.join(HERE, "vs_mitsuba.py"), "--worker", path]

        vm.run_timed(cmd(1, 1), env)  # warm-up: Dr.Jit's kernel cache
        pts = []
        for spp in levels:
            runs = []
            for seed in seeds:
                wall, cpu, _ = vm.run_timed(cmd(spp, seed), env)
                npz = np.load(os.path.join(work, "mi.npz"))
                res["mitsuba_variant"] = str(npz["variant"])
                runs.append(dict(errors(npz["mean"]), seed=seed, wall_s=wall, cpu_s=cpu, render_s=float(npz["render_s"])))
            pts.append(point(spp, runs))
            show(label, pts[-1])
        res["curves"][label] = pts
    res["mitsuba_version"] = mi.__version__
    res["load_after"] = load_average()
    return res


def at_time(pts, t, metric="relmse", clock="cpu_s"):
    """A curve's metric at time t: log-log interpolation between its points; past its slowest
    point, that point carried along 1/time (relMSE, the MSE rate; sqrt of it for RMSE and FLIP),
    marked extrapolated; None before its fastest (no image that fast)."""
    pts = sorted(pts, key=lambda p: p[clock])
    ts, es = [p[clock] for p in pts], [p.get(metric) for p in pts]
    if t < ts[0]:
        return None, False
    if t >= ts[-1]:
        return es[-1] * (ts[-1] / t) ** (1.0 if metric == "relmse" else 0.5), True
    for i in range(len(ts) - 1):
        if ts[i] <= t <= ts[i + 1]:
            if ts[i + 1] == ts[i] or es[i] <= 0 or es[i + 1] <= 0:
                return es[i], False
            f = math.log(t / ts[i]) / math.log(ts[i + 1] / ts[i])
            return math.exp(math.log(es[i]) + f * (math.log(es[i + 1]) - math.log(es[i]))), False
    return es[-1], False


def best_mitsuba(res, spp=64):
    """(label, its point) of the Mitsuba sampler with the lowest relMSE at spp (64, else its largest)."""
    cands = []
    for lab, pts in res["curves"].items():
        if lab.startswith("Mitsuba"):
            at = [p for p in pts if p["spp"] <= spp]
            cands.append((lab, max(at, key=lambda p: p["spp"])))
    return min(cands, key=lambda c: c[1]["relmse"])


def table(res):
    label0, p0 = best_mitsuba(res)
    t = p0["cpu_s"]
    lines = [f"At the CPU time {label0} (Mitsuba's best sampler here, by relMSE) needs for {p0['spp']} spp: "
             f"{t:.2f} s (median of {res.get('seeds', 1)} seeds per point); ratio = the curve's / {label0}'s",
             "", "| curve | relMSE | ratio | mean FLIP | ratio | RMSE |", "|---|---|---|---|---|---|"]
    for label, pts in res["curves"].items():
        e, extra = at_time(pts, t, "relmse")
        if e is None:
            fastest = min(p["cpu_s"] for p in pts)
            lines.append(f"| {label} | none (its fastest image took {fastest:.2f} CPU s) | - | - | - | - |")
            continue
        f, _ = at_time(pts, t, "flip")
        r, _ = at_time(pts, t, "rmse")
        mark = " (extrapolated)" if extra else ""
        lines.append(f"| {label} | {e:.4g}{mark} | {e / p0['relmse']:.2f} | {f:.4f} | {f / p0['flip']:.2f} | {r:.4g} |")
    lines += ["", f"At equal spp ({p0['spp']}): relMSE, mean FLIP, CPU s", "", "| curve | relMSE | FLIP | CPU s |",
              "|---|---|---|---|"]
    for label, pts in res["curves"].items():
        p = next((p for p in pts if p["spp"] == p0["spp"]), None)
        if p:
            lines.append(f"| {label} | {p['relmse']:.4g} | {p['flip']:.4f} | {p['cpu_s']:.2f} |")
    return "\n".join(lines)


def plot(res, out):
    try:
        import matplotlib
    except ImportError:
        print("convergence --vs-time: no plot (matplotlib is missing: scripts/setup.sh --plots)")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    for ax, metric, name in ((axes[0], "relmse", "relMSE (eps 0.01, top 0.1% dropped)"), (axes[1], "flip", "mean LDR-FLIP")):
        for label, pts in res["curves"].items():
            style = "s--" if label.startswith("Mitsuba") else "o-"
            ax.loglog([p["cpu_s"] for p in pts], [p[metric] for p in pts], style, label=label)
        ax.set_xlabel("CPU time of the whole process, s (median of %d seeds)" % res.get("seeds", 1))
        ax.set_ylabel(name)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=7)
    scene = os.path.basename(os.path.dirname(res["scene"]))
    fig.suptitle("%s, %s, %dx%d, reference %d spp; %s, load %.1f-%.1f" %
                 (scene, res.get("integrator", "direct"), res["size"], res.get("height", res["size"]), res["ref_spp"],
                  res["date"], res["load_before"][0], res["load_after"][0]), fontsize=9)
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
    if not a.replot and subprocess.run([py, "-c", "import flip_evaluator"], capture_output=True).returncode != 0:
        print(f"convergence --vs-time: FLIP is not installed in {vm.VENV}; run scripts/setup.sh --mitsuba",
              file=sys.stderr)
        return vm.EXIT_SKIP
    data = a.json or os.path.join(tempfile.mkdtemp(prefix="convergence_time_"), "data.json")
    if not a.replot:
        cmd = [py, os.path.abspath(__file__), "--measure", data, "--scene", a.scene, "--size", str(a.size),
               "--height", str(a.height), "--max-spp", str(a.max_spp), "--ref-spp", str(a.ref_spp),
               "--montecl", a.montecl, "--mitsuba-samplers", a.mitsuba_samplers, "--integrator", a.integrator,
               "--seeds", str(a.seeds), "--exposure", str(a.exposure), "--curves", a.curves]
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
    p.add_argument("--integrator", choices=["direct", "path"], required=True)
    p.add_argument("--seeds", type=int, required=True)
    p.add_argument("--exposure", type=float, required=True)
    p.add_argument("--curves", default="")
    args = p.parse_args()
    result = measure(args)
    with open(args.measure, "w") as f:
        json.dump(result, f, indent=1)
