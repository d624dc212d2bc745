"""What bench/mitsuba_compare.py and bench/mitsuba_heavy.py share: the report they print and
write, failing with one line, and image statistics."""
import sys

import numpy as np

LINES = []


def say(text=""):
    print(text, flush=True)
    LINES.append(text)


def fail(text):
    print(f"mitsuba_compare: {text}", file=sys.stderr)
    sys.exit(1)


def check_image(name, img, shape):
    if img.shape != shape:
        fail(f"{name}: image shape {img.shape} differs from the reference's {shape}")
    if not np.all(np.isfinite(img)):
        fail(f"{name}: image has NaN or infinite pixels")


def rmse(img, ref):
    return float(np.sqrt(np.mean((img - ref) ** 2)))


def channel_means(img):
    return img.reshape(-1, img.shape[2])[:, :3].mean(axis=0)
