"""image_metrics.py: the error metrics of scripts/convergence.py --vs-time, on H x W x 3 linear HDR
numpy arrays (an image and its reference); reads and writes nothing.

relmse: the field's relative MSE (Gharbi et al.'s RelativeMSE, Mueller et al.'s comparisons):
per pixel the mean over R, G, B of (x - r)^2 / (r^2 + eps) with eps = 0.01, then the largest 0.1%
of the per-pixel values dropped (floor(0.001 * pixels) of them: none below 1000 pixels) and the
rest averaged. Under it a bright emitter-edge pixel and a dim indirect one weigh about the same.

ldr / mean_flip: NVlabs' FLIP (PyPI flip-evaluator) on LDR images made the same way from both:
linear values times 2^exposure (fixed: 0 stops by default), clamped to [0, 1], sRGB-encoded.

Checked by scripts/image_metrics_test.py against hand-computed values.
"""
import math

import numpy as np

EPS = 0.01
DROP = 0.001


def relmse_per_pixel(x, r, eps=EPS):
    """H x W: the mean over channels of (x - r)^2 / (r^2 + eps)."""
    x, r = np.asarray(x, dtype=np.float64), np.asarray(r, dtype=np.float64)
    if x.shape != r.shape:
        raise ValueError(f"image {x.shape} and reference {r.shape} differ in shape")
    return np.mean((x - r) ** 2 / (r * r + eps), axis=-1)


def drop_top(values, fraction=DROP):
    """The values without their largest floor(fraction * count) (one array, any order)."""
    v = np.sort(np.ravel(values))
    k = int(math.floor(fraction * v.size))
    return v[:v.size - k]


def relmse(x, r, eps=EPS, drop=DROP):
    return float(np.mean(drop_top(relmse_per_pixel(x, r, eps), drop)))


def srgb_encode(v):
    """Linear [0, 1] to sRGB [0, 1] (IEC 61966-2-1)."""
    v = np.clip(v, 0.0, 1.0)
    return np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1.0 / 2.4) - 0.055)


def ldr(x, exposure=0.0):
    """The LDR image FLIP sees: linear x times 2^exposure, clamped to [0, 1], sRGB-encoded."""
    return srgb_encode(np.asarray(x, dtype=np.float64) * (2.0 ** exposure)).astype(np.float32)


def mean_flip(x, r, exposure=0.0):
    """Mean LDR-FLIP of image x against reference r after the same fixed exposure (0 = identical)."""
    import flip_evaluator
    _, mean, _ = flip_evaluator.evaluate(ldr(r, exposure), ldr(x, exposure), "LDR", inputsRGB=True,
                                         applyMagma=False)
    return float(mean)
