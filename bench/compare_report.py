"""What bench/mitsuba_compare.py and bench/mitsuba_heavy.py share: the report they print and
write, failing with one line, a command's CPU seconds, and image statistics; and the log-log
reading of error against time that bench/adaptive_report.py, bench/cycles_adaptive.py and
bench/error_vs_time.py share. Plain Python and numpy: it runs in any of the venvs."""
import math
import resource
import subprocess
import sys

import numpy as np

LINES = []


def say(text=""):
    print(text, flush=True)
    LINES.append(text)


def fail(text):
    print(f"mitsuba_compare: {text}", file=sys.stderr)
    sys.exit(1)


def cpu_of(cmd, env=None):
    """Runs a command (in `env`, else this process's environment); returns its CPU seconds
    (every thread's, user + system)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)} failed (exit {r.returncode}): {r.stderr.strip()}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def exr_float_attribute(path, name):
    """A float attribute of an OpenEXR file's header, or None. OpenEXR's file layout: magic,
    version, then attributes (name, NUL, type, NUL, int32 size, value) until an empty name.
    Plain Python: Blender's Python has no OIIO, and bpy's images hide custom attributes."""
    import struct
    with open(path, "rb") as f:
        data = f.read(1 << 16)
    if data[:4] != b"\x76\x2f\x31\x01":
        fail(f"{path}: not an OpenEXR file")
    at = 8
    while at < len(data) and data[at] != 0:
        end = data.index(b"\0", at)
        key = data[at:end].decode()
        kind_end = data.index(b"\0", end + 1)
        kind = data[end + 1:kind_end].decode()
        (size,) = struct.unpack_from("<i", data, kind_end + 1)
        value = kind_end + 5
        if key == name and kind == "float" and size == 4:
            return struct.unpack_from("<f", data, value)[0]
        at = value + size
    return None


def render_cpu_of(cmd, out, env=None):
    """Runs a tray-render command writing `out`; returns the CPU seconds of its render alone
    (tray:renderCpuSeconds: scene loading, start-up and writing left out, as Mitsuba's timing
    leaves out its scene loading)."""
    cpu_of(cmd, env)  # runs it, failing with its message; the whole process's time unused
    cpu = exr_float_attribute(out, "tray:renderCpuSeconds")
    if cpu is None:
        fail(f"{out}: no tray:renderCpuSeconds (a tray-render older than the render CPU time)")
    return cpu


def check_image(name, img, shape):
    if img.shape != shape:
        fail(f"{name}: image shape {img.shape} differs from the reference's {shape}")
    if not np.all(np.isfinite(img)):
        fail(f"{name}: image has NaN or infinite pixels")


def rmse(img, ref):
    return float(np.sqrt(np.mean((img - ref) ** 2)))


def relmse(img, ref, trimmed=False):
    """bench/image_error.cpp's relMSE: the mean over pixels and RGB of (x - r)^2 / (r^2 + 0.01);
    `trimmed` leaves out the 0.1% pixels (at least one) of largest error summed over RGB."""
    rel = ((img - ref) ** 2 / (ref ** 2 + 1e-2))[:, :, :3].sum(axis=2).ravel()
    if trimmed:
        cut = max(1, rel.size // 1000)
        rel = np.partition(rel, rel.size - cut)[:rel.size - cut]
    return float(rel.mean() / 3)


def channel_means(img):
    return img.reshape(-1, img.shape[2])[:, :3].mean(axis=0)


def loglog_crossing(points, value, axis=0):
    """Along the (x, y) points in x order, the first segment whose coordinate `axis` (0: x,
    1: y) brackets `value`: the other coordinate there, interpolated linearly in log-log. None
    when no segment does. With (time, error) points: axis 0 reads the error at a time, axis 1
    the time at which the line reaches an error."""
    points = sorted(points)
    for p0, p1 in zip(points, points[1:]):
        v0, v1 = p0[axis], p1[axis]
        if min(v0, v1) <= value <= max(v0, v1) and v0 != v1:
            a = (math.log(value) - math.log(v0)) / (math.log(v1) - math.log(v0))
            o0, o1 = p0[1 - axis], p1[1 - axis]
            return math.exp((1 - a) * math.log(o0) + a * math.log(o1))
    return None
