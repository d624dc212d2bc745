"""A farm job on disk: its folder (job.json, the batch scripts, parts, logs, state) and its plan,
frames x parts, each part one tray-render --region or --sample-range run (docs/farm.md)."""

import json
import os
import re
import shlex
import time

from exr_header import part_state

SPEC_FILE = "job.json"
# What makes two submissions the same job: parts rendered for one are parts of the other.
IDENTITY = ("scene", "scene_stamp", "frames", "split", "render_args", "output")


class JobError(Exception):
    """Bad input for a job; the message is one line for the user."""


# Frames one job may hold: each is a part set, a merge and their records (a job's plan is built
# in memory, and a Slurm array is far smaller: MaxArraySize defaults to 1001).
MAX_FRAMES = 100000


def parse_frames(text):
    """'A-B' or 'A' (0 <= A <= B, at most MAX_FRAMES frames) as [A, B]."""
    m = re.fullmatch(r"(\d+)(?:-(\d+))?", text or "")
    if not m:
        raise JobError("--frames %s: expected FIRST-LAST (e.g. 1-48) or one frame" % text)
    first, last = int(m.group(1)), int(m.group(2) or m.group(1))
    if first > last:
        raise JobError("--frames %s: the first frame is after the last" % text)
    if last - first + 1 > MAX_FRAMES:
        raise JobError("--frames %s: %d frames, more than %d in one job: submit the range in "
                       "several jobs" % (text, last - first + 1, MAX_FRAMES))
    return [first, last]


def parse_split(text):
    """'regions:N' or 'samples:N' (N >= 1) as (kind, N)."""
    m = re.fullmatch(r"(regions|samples):(\d+)", text or "")
    if not m or int(m.group(2)) < 1:
        raise JobError("--split %s: expected regions:N or samples:N with N >= 1" % text)
    return m.group(1), int(m.group(2))


def render_option(args, name):
    """The value of `--name V` or `--name=V` among tray-render's arguments, or None."""
    for i, a in enumerate(args):
        if a == name and i + 1 < len(args):
            return args[i + 1]
        if a.startswith(name + "="):
            return a[len(name) + 1:]
    return None


def band_edges(height, n):
    """Row edges of n bands: at multiples of 8 where every band keeps a row, so that noise-driven
    adaptive sampling (which decides per 8x8 block, docs/adaptive-sampling.md) renders each band
    as the whole image would; else as even as can be."""
    rows = [min(height, 8 * round(height * k / (8 * n))) for k in range(n + 1)]
    rows[-1] = height
    if all(a < b for a, b in zip(rows, rows[1:])):
        return rows
    return [height * k // n for k in range(n + 1)]


def part_options(split, render_args):
    """tray-render's options for each part: bands of rows (whole rows keep each part's EXR
    scanlines contiguous for the merge) or consecutive sample ranges."""
    kind, n = parse_split(split)
    if kind == "regions":
        size = render_option(render_args, "--resolution")
        m = re.fullmatch(r"(\d+)x(\d+)", size or "")
        if not m:
            raise JobError("--split %s needs the image size: give --resolution WxH" % split)
        width, height = int(m.group(1)), int(m.group(2))
        if n > height:
            raise JobError("--split %s: more regions than the %d rows of the image"
                           % (split, height))
        rows = band_edges(height, n)
        return [["--region", "0,%d,%d,%d" % (rows[k], width, rows[k + 1])] for k in range(n)]
    spp = render_option(render_args, "--spp")
    if spp is None or not spp.isdigit():
        raise JobError("--split %s needs the samples per pixel: give --spp N" % split)
    if n > int(spp):
        raise JobError("--split %s: more ranges than the %s samples per pixel" % (split, spp))
    bounds = [int(spp) * k // n for k in range(n + 1)]
    return [["--sample-range", "%d,%d" % (bounds[k], bounds[k + 1])] for k in range(n)]


def frame_path(pattern, frame):
    """`pattern` with its '####' or '%0Nd' replaced by the zero-padded frame (as tray-render)."""
    m = re.search(r"#+", pattern)
    if m:
        return pattern[:m.start()] + str(frame).zfill(len(m.group(0))) + pattern[m.end():]
    m = re.search(r"%(0?)(\d*)d", pattern)
    if m:
        return pattern[:m.start()] + str(frame).zfill(int(m.group(2) or 1)) + pattern[m.end():]
    return pattern


def has_frame_pattern(path):
    return re.search(r"#+|%0?\d*d", path) is not None


class FarmJob:
    """The job in folder `folder`; `spec` is job.json's content."""

    def __init__(self, folder, spec):
        self.folder = os.path.abspath(folder)
        self.spec = spec
        frames = spec["frames"]
        self.frames = list(range(frames[0], frames[1] + 1)) if frames else [None]
        self.options = part_options(spec["split"], spec["render_args"])

    @staticmethod
    def load(folder):
        path = os.path.join(folder, SPEC_FILE)
        try:
            with open(path) as f:
                return FarmJob(folder, json.load(f))
        except OSError:
            raise JobError("%s: not a tray-farm job folder (no %s)" % (folder, SPEC_FILE))
        except (ValueError, KeyError) as e:
            raise JobError("%s: unreadable (%s)" % (path, e))

    def path(self, *names):
        return os.path.join(self.folder, *names)

    # The plan: task i renders part i % P of frame i // P.
    def task_count(self):
        return len(self.frames) * len(self.options)

    def tasks_of_frame(self, frame_index):
        p = len(self.options)
        return list(range(frame_index * p, (frame_index + 1) * p))

    def part_file(self, task):
        frame = self.frames[task // len(self.options)]
        name = "p%03d" % (task % len(self.options))
        return self.path("parts", name + (".exr" if frame is None else ".%06d.exr" % frame))

    def output_file(self, frame_index):
        frame = self.frames[frame_index]
        return self.spec["output"] if frame is None else frame_path(self.spec["output"], frame)

    def part_states(self):
        return [part_state(self.part_file(t)) for t in range(self.task_count())]

    # What happened, appended by submit, resume and the merge steps (one JSON object a line).
    def record(self, **entry):
        entry["time"] = time.time()
        with open(self.path("state", "slurm.jsonl"), "a") as f:
            f.write(json.dumps(entry) + "\n")

    def records(self):
        try:
            with open(self.path("state", "slurm.jsonl")) as f:
                return [json.loads(line) for line in f if line.strip()]
        except OSError:
            return []

    def slurm_task_ids(self):
        """The Slurm id ("JOB_TASK") of each task's latest submission (None if never)."""
        ids = [None] * self.task_count()
        for r in self.records():
            if r["kind"] == "parts":
                for t in r["tasks"]:
                    ids[t] = "%s_%d" % (r["id"], t)
        return ids

    def marker(self, name):
        return self.path("state", name)

    def part_script(self):
        """The array task script: task i execs tray-render for part i (SIGTERM reaches it)."""
        q = shlex.quote
        tasks = range(self.task_count())
        frames = " ".join(str(self.frames[t // len(self.options)]) for t in tasks)
        opts = " ".join(q(self.options[t % len(self.options)][0]) for t in range(self.task_count()))
        vals = " ".join(q(self.options[t % len(self.options)][1]) for t in range(self.task_count()))
        outs = []
        for t in range(self.task_count()):
            out = self.part_file(t)
            if self.frames[0] is not None:
                out = re.sub(r"\.\d{6}\.exr$", ".######.exr", out)
            outs.append(q(out))
        renderer = q(os.path.join(self.spec["bin"], "tray-render"))
        args = " ".join(q(a) for a in [self.spec["scene"]] + self.spec["render_args"])
        frame_arg = '--frames "${FRAMES[i]}"' if self.frames[0] is not None else ""
        return f"""#!/bin/bash
# tray-farm: Slurm array task i renders part i of the job in {self.folder}
# (frame FRAMES[i], {self.spec["split"]}), written by `tray-farm submit`; read or adapt it.
# exec: scancel and time limits deliver SIGTERM to tray-render itself, which writes the part so
# far (exit 143); --resume continues it, or any checkpoint, when the task runs again.
# TRAY_FARM_ATTEMPT in the environment: 0 on a part's first run, N on its Nth retry.
set -u
FRAMES=({frames})
PART_OPT=({opts})
PART_VAL=({vals})
OUTPUT=({" ".join(outs)})
i=$SLURM_ARRAY_TASK_ID
exec {renderer} {args} {frame_arg} "${{PART_OPT[i]}}" "${{PART_VAL[i]}}" \\
  -o "${{OUTPUT[i]}}" --checkpoint {self.spec["checkpoint"]} --resume --progress plain
"""

    def merge_script(self, farm_program):
        """The per-frame merge job: checks the parts, retries failed ones, runs tray-merge."""
        q = shlex.quote
        return f"""#!/bin/bash
# tray-farm: merges frame index $1 of the job in {self.folder} once its parts have ended
# (dependency afterany: it always runs, so a failed part never leaves it pending); parts that
# are not complete are resubmitted up to {self.spec["retries"]} times, then it fails.
exec python3 {q(farm_program)} merge-step {q(self.folder)} "$1"
"""
