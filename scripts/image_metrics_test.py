"""image_metrics_test.py: checks scripts/image_metrics.py (relMSE, the dropped top 0.1%, the LDR
FLIP sees) against values worked out by hand; reads and writes nothing. Prints PASS and exits 0,
or prints each failure and exits 1; exits 77 (skipped) without numpy or flip_evaluator (Mitsuba's
venv has both after scripts/setup.sh --mitsuba). Run by tests/test_convergence_metrics.cpp.
"""
import math
import os
import sys

try:
    import numpy as np
    import flip_evaluator  # noqa: F401
except ImportError as e:
    print(f"image_metrics_test: skipped: {e} (run scripts/setup.sh --mitsuba and use its venv's python)")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import image_metrics as im  # noqa: E402

failures = []


def near(name, got, want, tol=1e-9):
    if not math.isclose(got, want, rel_tol=tol, abs_tol=tol):
        failures.append(f"{name}: got {got!r}, want {want!r}")


def image(pixels):
    """A 1 x N x 3 image from N RGB triples."""
    return np.array([pixels], dtype=np.float64)


# relMSE per pixel, eps = 0.01: (1 - 0.5)^2 / (0.25 + 0.01) = 0.25 / 0.26 in every channel of
# the first pixel; (0 - 0.1)^2 / (0.01 + 0.01) = 0.5 in the second; under 1000 pixels none is dropped.
near("relmse of two grey pixels", im.relmse(image([[1, 1, 1], [0, 0, 0]]), image([[0.5] * 3, [0.1] * 3])),
     (0.25 / 0.26 + 0.5) / 2)
# Channels averaged within the pixel: red off by 1 on black, (1 / 0.01 + 0 + 0) / 3.
near("relmse of one red pixel on black", im.relmse(image([[1, 0, 0]]), image([[0, 0, 0]])), 100.0 / 3)
# Symmetric in sign, relative to the reference: 2 against 1 is (1 / 1.01), 0 against 1 the same.
near("relmse of +1 and -1 on 1", im.relmse(image([[2] * 3, [0] * 3]), image([[1] * 3, [1] * 3])), 1 / 1.01)
near("relmse of an exact image", im.relmse(image([[0.3, 2, 7]]), image([[0.3, 2, 7]])), 0.0)

# The dropped 0.1%: 2000 pixels with relMSE 1 (x = r + 0.1 on r = 0: 0.01 / 0.01), k of them
# with 0.01 * 1000 / 0.01 = 1000 instead. floor(0.001 * 2000) = 2 are dropped.
def outliers(n, k):
    r = np.zeros((1, n, 3))
    x = np.full((1, n, 3), 0.1)
    x[0, :k] = math.sqrt(0.01 * 1000)
    return x, r


near("2 outliers in 2000: both dropped", im.relmse(*outliers(2000, 2)), 1.0)
near("3 outliers in 2000: one stays", im.relmse(*outliers(2000, 3)), (1997 + 1000) / 1998)
near("1 outlier in 999: none dropped", im.relmse(*outliers(999, 1)), (998 + 1000) / 999)
near("drop_top keeps the smallest", float(np.sum(im.drop_top(np.arange(3000.0)))), float(np.sum(np.arange(2997.0))))

# The LDR image: linear 0.5 -> 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357; 0.002 -> 12.92 * 0.002;
# one stop up, 0.5 -> 1; the light's 17 clamps to 1; negative clamps to 0.
ldr = im.ldr(image([[0.5, 0.002, 17.0]]))[0, 0]
near("ldr(0.5)", float(ldr[0]), 0.7353569830524495, 1e-6)
near("ldr(0.002)", float(ldr[1]), 0.02584, 1e-6)
near("ldr(17)", float(ldr[2]), 1.0)
near("ldr(0.5) one stop up", float(im.ldr(image([[0.5, -1, 0]]), 1.0)[0, 0, 0]), 1.0)
near("ldr(-1)", float(im.ldr(image([[0.5, -1, 0]]))[0, 0, 1]), 0.0)

# FLIP: 0 for the same image; values that differ only above 1 clamp to the same LDR image at
# exposure 0 but not two stops down; and it is FLIP of those LDR images (flip_evaluator's own).
rng = np.random.default_rng(1)
ref = rng.uniform(0, 0.8, (32, 32, 3))
near("flip of an exact image", im.mean_flip(ref, ref), 0.0)
hot_a, hot_b = ref.copy(), ref.copy()
hot_a[8:24, 8:24] = 2.0
hot_b[8:24, 8:24] = 3.0
near("flip of images differing only above 1, exposure 0", im.mean_flip(hot_a, hot_b), 0.0)
if not im.mean_flip(hot_a, hot_b, -2.0) > 0.01:
    failures.append("flip of 2.0 against 3.0 two stops down should be > 0.01")
noisy = np.clip(ref + rng.normal(0, 0.1, ref.shape), 0, None)
_, want, _ = flip_evaluator.evaluate(im.ldr(ref), im.ldr(noisy), "LDR", applyMagma=False)
near("flip of a noisy image is flip_evaluator's on the LDR images", im.mean_flip(noisy, ref), float(want), 1e-6)
if not 0.01 < want < 0.5:
    failures.append(f"flip of a noisy image {want} should lie in (0.01, 0.5)")

for f in failures:
    print("FAIL", f)
print("FAIL" if failures else "PASS")
sys.exit(1 if failures else 0)
