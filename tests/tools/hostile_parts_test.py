#!/usr/bin/env python3
"""Hostile parts and checkpoints: tray-merge and `tray-render --resume` given EXRs whose header
numbers or state layer ('tray': each pixel's sums as double bit patterns, and `done`) were
edited or damaged. TRay's promise for bad input holds for each: exit 2 and one line naming the
file, nothing written (no merged output; the checkpoint's bytes unchanged), no crash.

What failed before the checks in io/image_input.h (metadataCount, metadataAmount) and
film/render_state.h (checkedSums, checkedFlag):
  - a part without one of the state channels made tray-merge read past its row buffer
    (valgrind: "Invalid read of size 4" in addPart) and merge with exit 0;
  - header numbers that are NaN, infinite, negative or fractions were converted to int
    (undefined behaviour): "pixel (0, 0) has -2147483648 of its 8 samples", "unfinished part
    (-9223372036854775808 of 320 pixels)", a begin of 4.5 taken as 4 and merged;
  - a float NaN or infinity written into a sum's high word (a finite double near 2^1020)
    merged into an image of 65504s with exit 0, a done flag of 0.5 or NaN counted as done,
    and NaN seconds were summed into the merged header; in an adaptive checkpoint's progress
    layer such sums resumed, and a pending flag of 0.5 counted as pending.
All 164 merge and path-checkpoint cases fail on the code before those checks (the adaptive
checkpoint's sample counts were already checked). The unedited parts merge and the unedited
checkpoints resume (exit 0): the edits decide.

Usage: hostile_parts_test.py BIN_DIR SHARED_DIR WORK_DIR"""

import os
import resource
import shutil
import signal
import struct
import subprocess
import sys

import numpy as np
import OpenImageIO as oiio

BIN, SHARED, WORK = (os.path.abspath(a) for a in sys.argv[1:4])
RENDER, MERGE = os.path.join(BIN, "tray-render"), os.path.join(BIN, "tray-merge")
CORNELL = os.path.join(SHARED, "reference", "cornell-box.gltf")
PART_JOB = [CORNELL, "--integrator", "path", "--spp", "8", "--filter", "tent", "--aov",
            "depth,samples", "--resolution", "40x8", "--threads", "1"]
# Long enough that the first progress line comes well before the end (about 3 s on 1 thread).
CHECKPOINT_JOB = [CORNELL, "--integrator", "path", "--spp", "384", "--resolution", "101x93",
                  "--seed", "7", "--threads", "1"]
# Adaptive sampling in passes (about 2.5 s): its checkpoint has the progress layer too
# ('tray_progress': each pixel's earlier sums, its sample count and whether a step is owed).
ADAPTIVE_JOB = [CORNELL, "--integrator", "path", "--spp", "4096", "--noise-threshold", "0.004",
                "--resolution", "101x93", "--seed", "7", "--threads", "1"]
ENV = dict(os.environ, OPENBLAS_NUM_THREADS="1")
NAN, INF = float("nan"), float("inf")
failures = []


def run(cmd, memory_limit=None):
    """`memory_limit`: bytes of address space the child may have (a refusal must not need more)."""
    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (memory_limit, memory_limit))
    return subprocess.run(cmd, capture_output=True, text=True, timeout=300, env=ENV,
                          preexec_fn=limit if memory_limit else None)


def load(path):
    i = oiio.ImageInput.open(path)
    spec, pixels = oiio.ImageSpec(i.spec()), i.read_image(format="float")
    i.close()
    return spec, pixels


def save(path, spec, pixels):
    o = oiio.ImageOutput.create(path)
    o.open(path, spec)
    o.write_image(pixels)
    o.close()


def header(key, value):
    def edit(spec, pixels, names):
        spec.attribute(key, value)
        return spec, pixels
    return edit


def channel(name, value):
    """The channel set to `value` at pixel (0, 0) only."""
    def edit(spec, pixels, names):
        pixels = pixels.copy()
        pixels[0, 0, names.index(name)] = value
        return spec, pixels
    return edit


def full_size(width, height):
    def edit(spec, pixels, names):
        spec.full_width, spec.full_height = width, height
        return spec, pixels
    return edit


def without(name):
    def edit(spec, pixels, names):
        keep = [i for i, n in enumerate(names) if n != name]
        spec.nchannels, spec.channelformats = len(keep), ()
        spec.channelnames = tuple(names[i] for i in keep)
        return spec, np.ascontiguousarray(pixels[..., keep])
    return edit


def edited(source, target, edit):
    spec, pixels = load(source)
    spec, pixels = edit(spec, pixels, list(spec.channelnames))
    save(target, spec, pixels)


def expect_refusal(case, cmd, says, untouched=None, names="bad.exr", memory_limit=None):
    """Exit 2, one line naming `names` (if not empty) and saying `says`; `untouched`: (path, its
    bytes)."""
    if os.path.exists("merged.exr"):
        os.remove("merged.exr")
    r = run(cmd, memory_limit)
    lines = r.stderr.strip().splitlines()
    problems = []
    if r.returncode != 2:
        problems.append(f"exit {r.returncode}")
    if len(lines) != 1 or names not in lines[0] or says not in lines[0]:
        problems.append(f"stderr {lines!r}, expected one line naming {names} with {says!r}")
    if untouched and open(untouched[0], "rb").read() != untouched[1]:
        problems.append(f"{untouched[0]} was written")
    if os.path.exists("merged.exr"):
        problems.append("merged.exr was written")
    if problems:
        failures.append(f"{case}: {'; '.join(problems)}")


def header_cases(counts, amounts):
    """Hostile values of header numbers: counts must be whole numbers >= 0, amounts finite."""
    cases = []
    for key in counts:
        for value in (NAN, INF, -1.0, 1e30, 4.5):
            cases.append((f"{key} = {value}", header(key, value), f"header's {key} is"))
    for key in amounts:
        for value in (NAN, INF, -1.0):
            cases.append((f"{key} = {value}", header(key, value), f"header's {key} is"))
    return cases


def state_cases():
    """A float NaN, infinity or 1e30 written into a sum's high word; done neither 0 nor 1."""
    cases = []
    for word in ("Rh", "Gh", "Bh", "Ah", "Wh"):
        for value in (NAN, INF, 1e30):
            cases.append((f"tray.{word} = {value}", channel(f"tray.{word}", value),
                          "sums that no render makes"))
    for value in (NAN, 0.5, 2.0, -1.0):
        cases.append((f"tray.done = {value}", channel("tray.done", value), "neither 0 nor 1"))
    return cases


def merge_cases():
    os.chdir(WORK)
    for begin, end in ((0, 4), (4, 8)):
        r = run([RENDER, *PART_JOB, "--sample-range", f"{begin},{end}", "-o", f"p{begin}.exr"])
        assert r.returncode == 0, r.stderr
    names = list(load("p4.exr")[0].channelnames)
    cases = header_cases(["tray:samplesPerPixel", "tray:sampleBegin", "tray:sampleEnd",
                          "tray:pixelsDone", "tray:pixelsTotal", "tray:samplesDone"],
                         ["tray:renderSeconds", "tray:renderCpuSeconds"])
    cases += state_cases()
    cases += [(f"no {n}", without(n), f"no channel {n}") for n in names if n.startswith("tray.")]
    cases.append(("an empty sample range", header("tray:sampleEnd", 4.0), "holds no sample"))
    for case, edit, says in cases:
        edited("p4.exr", "bad.exr", edit)
        for order in (["p0.exr", "bad.exr"], ["bad.exr", "p0.exr"]):
            # Refused in either order: the checks are each part's own, not the first part's.
            expect_refusal(f"merge {' '.join(order)}: {case}",
                           [MERGE, *order, "-o", "merged.exr"], says)
    # Both parts claiming a 200000x200000 image: refused from their windows, in a few MB (before,
    # the merge sized a 160 GB coverage array by the header: out of memory, exit 1, or the OOM
    # killer).
    for source, target in (("p0.exr", "big0.exr"), ("p4.exr", "big4.exr")):
        edited(source, target, full_size(200000, 200000))
    expect_refusal("merge: parts claiming a 200000x200000 image",
                   [MERGE, "big0.exr", "big4.exr", "-o", "merged.exr"], "a part is missing",
                   names="", memory_limit=4 << 30)
    r = run([MERGE, "p0.exr", "p4.exr", "-o", "merged.exr"])
    if r.returncode != 0:
        failures.append(f"the unedited parts do not merge: {r.stderr.strip()}")
    return len(cases) * 2 + 1


def checkpoint(job):
    """A checkpoint of `job`: interrupted (SIGINT) after its first progress line."""
    p = subprocess.Popen([RENDER, *job, "--progress", "plain", "--progress-step", "1",
                          "-o", "checkpoint.exr"], stderr=subprocess.PIPE, text=True, env=ENV)
    for line in p.stderr:
        if line.startswith("progress"):
            p.send_signal(signal.SIGINT)
            break
    p.communicate()
    assert p.returncode == 130, f"the render was not interrupted (exit {p.returncode})"
    spec = load("checkpoint.exr")[0]
    assert spec.getattribute("tray:status") != "complete"


def progress_cases():
    """The progress layer's words: sums as the state layer's, a count, a pending flag."""
    cases = [(f"tray_progress.{w} = {v}", channel(f"tray_progress.{w}", v),
              "in the progress layer sums that no render makes")
             for w in ("Rh", "Wh") for v in (NAN, 1e30)]
    cases += [(f"tray_progress.count = {v}", channel("tray_progress.count", v),
               "sample count that is not one") for v in (NAN, -1.0, 4.5, 1e30)]
    cases += [(f"tray_progress.pending = {v}", channel("tray_progress.pending", v),
               "pending") for v in (NAN, 0.5, 2.0)]
    return cases


def resume_cases(job, adaptive):
    checkpoint(job)
    names = list(load("checkpoint.exr")[0].channelnames)
    assert adaptive == ("tray_progress.count" in names), names
    cases = header_cases(["tray:pixelsDone"], ["tray:renderSeconds", "tray:renderCpuSeconds"])
    cases += state_cases() + (progress_cases() if adaptive else [])
    for case, edit, says in cases:
        edited("checkpoint.exr", "bad.exr", edit)
        before = open("bad.exr", "rb").read()
        expect_refusal(f"resume{' adaptive' if adaptive else ''}: {case}",
                       [RENDER, *job, "-o", "bad.exr", "--resume"], says, ("bad.exr", before))
    # A data window of 200000x200000 written into the header: refused in one line within the
    # memory limit, by OpenEXR (its offset table runs past the file's end) or by TRay's size
    # check. Before, a checkpoint large enough to open had its pixels sized first: "out of
    # memory while rendering", exit 1.
    forged = bytearray(open("checkpoint.exr", "rb").read())
    at = forged.find(b"dataWindow\0box2i\0") + len(b"dataWindow\0box2i\0") + 4
    forged[at:at + 16] = struct.pack("<4i", 0, 0, 199999, 199999)
    open("bad.exr", "wb").write(forged)
    expect_refusal("resume: a forged 200000x200000 data window",
                   [RENDER, *job, "-o", "bad.exr", "--resume"],
                   "", ("bad.exr", bytes(forged)),
                   memory_limit=4 << 30)
    shutil.copy("checkpoint.exr", "good.exr")
    r = run([RENDER, *job, "-o", "good.exr", "--resume"])
    if r.returncode != 0 or load("good.exr")[0].getattribute("tray:status") != "complete":
        failures.append(f"the unedited checkpoint does not resume: {r.stderr.strip()}")
    return len(cases) + 1


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    count = merge_cases() + resume_cases(CHECKPOINT_JOB, False) + resume_cases(ADAPTIVE_JOB, True)
    print(f"{count} hostile cases")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
