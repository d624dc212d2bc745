#!/usr/bin/env python3
"""tray-farm on a real one-machine Slurm cluster (tools/slurm-local.sh): a 2-frame x 4-part job
merged bit for bit against single-machine renders, a part killed mid-way and resumed, a part
that fails and is retried, a cancelled job, and bad input refused before anything is submitted.
Exit 77 (ctest: skipped) only where Slurm cannot start, with the reason.

Usage: farm_slurm_test.py SOURCE_DIR BIN_DIR [unittest arguments]"""

import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

SOURCE, BIN = (os.path.abspath(a) for a in sys.argv[1:3])
FARM = os.path.join(BIN, "tray-farm")
RENDER = os.path.join(BIN, "tray-render")
SLURM_LOCAL = os.path.join(SOURCE, "tools", "slurm-local.sh")
ANIMATED = os.path.join(SOURCE, "..", "shared", "gltf-features", "BoxAnimated.glb")
CORNELL = os.path.join(SOURCE, "..", "shared", "reference", "cornell-box.gltf")
# Small: each part renders in well under a second; --fps 2 makes frames 1 and 2 differ.
JOB = ["--integrator", "path", "--spp", "4", "--resolution", "48x32", "--fps", "2", "--seed", "3"]
# Slow enough to be stopped mid-way: one thread, more samples (a part: about 2.5 CPU seconds).
SLOW = ["--integrator", "path", "--spp", "1536", "--resolution", "64x48", "--threads", "1"]


def run(args, **kw):
    return subprocess.run(args, capture_output=True, text=True, **kw)


def wait_for(condition, seconds, what):
    deadline = time.time() + seconds
    while time.time() < deadline:
        if condition():
            return
        time.sleep(0.2)
    raise AssertionError("timed out after %d s waiting for %s" % (seconds, what))


def text(path):
    with open(path) as f:
        return f.read()


def records(folder):
    with open(os.path.join(folder, "state", "slurm.jsonl")) as f:
        return [json.loads(line) for line in f]


def queue_empty(folder):
    ids = ",".join(r["id"] for r in records(folder))
    return run(["squeue", "-h", "-r", "-j", ids]).stdout.strip() == ""


def same_pixels(a, b):
    r = run(["idiff", "-fail", "0", "-warn", "0", a, b])
    return r.returncode == 0, r.stdout[-400:]


class FarmOnSlurm(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="farm-slurm-", dir=os.environ.get("TEST_TMPDIR"))

    def tearDown(self):
        shutil.rmtree(self.dir, ignore_errors=True)

    def farm(self, *args, expect=0):
        r = run([FARM] + list(args))
        self.assertEqual(r.returncode, expect, r.stdout + r.stderr)
        return r

    def submit(self, scene, extra, output="out.####.exr", **kw):
        folder = os.path.join(self.dir, "job")
        self.farm("submit", scene, "-o", os.path.join(self.dir, output), "--job-dir", folder,
                  "--checkpoint", "1", *extra, **kw)
        return folder

    def wait_merged(self, folder, frames, seconds=120):
        wait_for(lambda: all(os.path.exists(os.path.join(folder, "state", "merged-%d" % f))
                             for f in range(frames)) and queue_empty(folder), seconds, "the merges")

    def test_two_frames_four_regions_merge_bit_for_bit(self):
        started = time.time()
        folder = self.submit(ANIMATED, ["--frames", "1-2", "--split", "regions:4"] + JOB)
        self.wait_merged(folder, 2)
        farm_seconds = time.time() - started
        started = time.time()
        ref = os.path.join(self.dir, "ref.####.exr")
        r = run([RENDER, ANIMATED, "--frames", "1-2", "-o", ref, "-q"] + JOB)
        self.assertEqual(r.returncode, 0, r.stderr)
        one_process = time.time() - started
        for frame in ("0001", "0002"):
            ok, diff = same_pixels(ref.replace("####", frame),
                                   os.path.join(self.dir, "out.%s.exr" % frame))
            self.assertTrue(ok, diff)
        self.assertFalse(same_pixels(os.path.join(self.dir, "out.0001.exr"),
                                     os.path.join(self.dir, "out.0002.exr"))[0])
        status = self.farm("status", folder).stdout
        self.assertEqual(status.count(": merged:"), 2, status)
        print("2 frames x 4 parts: %.1f s on the one-machine cluster, %.1f s in one process"
              % (farm_seconds, one_process))

    def test_killed_part_resumes_to_the_same_image(self):
        folder = self.submit(CORNELL, ["--split", "regions:2", "--retries", "0"] + SLOW,
                             output="out.exr")
        task = "%s_0" % records(folder)[0]["id"]
        log = os.path.join(folder, "logs", "part-0-%s.log" % task.split("_")[0])

        def rendering():  # its first progress line: the renderer's handlers are in place
            return os.path.exists(log) and "progress " in text(log)
        wait_for(rendering, 60, "part 0 to render")
        run(["scancel", task])  # SIGTERM to tray-render: the part so far is written
        wait_for(lambda: os.path.exists(os.path.join(folder, "state", "failed-0")), 60,
                 "the merge to give up")
        status = self.farm("status", folder).stdout
        self.assertIn("part 0: failed (file: partial", status)
        self.assertIn("interrupted (SIGTERM)", text(log))
        self.farm("resume", folder)
        self.wait_merged(folder, 1)
        ref = os.path.join(self.dir, "ref.exr")
        all_threads = SLOW[:-1] + ["0"]  # threads never change pixels
        self.assertEqual(run([RENDER, CORNELL, "-o", ref, "-q"] + all_threads).returncode, 0)
        ok, diff = same_pixels(ref, os.path.join(self.dir, "out.exr"))
        self.assertTrue(ok, diff)

    def test_failed_part_is_retried(self):
        folder = self.submit(ANIMATED, ["--frames", "1-1", "--split", "samples:2", "--retries",
                                        "1", "--test-fail", "1"] + JOB)
        self.wait_merged(folder, 1)
        parts = [r for r in records(folder) if r["kind"] == "parts"]
        self.assertEqual([p["tasks"] for p in parts], [[0, 1], [1]])  # only the failed one again
        self.assertEqual(text(os.path.join(folder, "state", "attempts-0")), "1")
        self.assertTrue(os.path.exists(os.path.join(self.dir, "out.0001.exr")))

    def test_cancelled_job_stops_and_submits_nothing_more(self):
        folder = self.submit(CORNELL, ["--split", "regions:2"] + SLOW, output="out.exr")
        wait_for(lambda: "RUNNING" in run(["squeue", "-h", "-r", "-o", "%T"]).stdout, 60,
                 "a running part")
        self.farm("cancel", folder)
        before = len(records(folder))
        wait_for(lambda: queue_empty(folder), 60, "the cancelled jobs to leave the queue")
        time.sleep(1)
        self.assertEqual(len(records(folder)), before, "a merge step submitted more work")
        self.assertTrue(queue_empty(folder))
        self.assertFalse(os.path.exists(os.path.join(self.dir, "out.exr")))
        self.assertIn("cancelled", self.farm("status", folder).stdout)

    def test_bad_input_is_one_line_and_submits_nothing(self):
        out = os.path.join(self.dir, "x.####.exr")
        env_no_slurm = dict(os.environ, PATH="/nonexistent")
        unreachable = os.path.join(self.dir, "slurm.conf")
        with open(os.environ["SLURM_CONF"]) as f:
            conf = re.sub(r"SlurmctldHost=.*", "SlurmctldHost=localhost\nSlurmctldPort=9", f.read())
        with open(unreachable, "w") as f:
            f.write(conf + "MessageTimeout=2\n")
        cases = [
            (["--frames", "3-1"], None, "--frames"),
            (["--frames", "a-b"], None, "--frames"),
            (["--frames", "1-2", "--split", "tiles:4"], None, "--split"),
            (["--frames", "1-2", "--split", "regions:4", "--spp", "4"], None, "--resolution"),
            (["--frames", "1-2"] + JOB, env_no_slurm, "not found"),
            (["--frames", "1-2"] + JOB, dict(os.environ, SLURM_CONF=unreachable), "controller"),
        ]
        for extra, env, says in cases:
            r = run([sys.executable, FARM, "submit", ANIMATED, "-o", out, "--job-dir",
                     os.path.join(self.dir, "bad")] + extra, env=env)
            self.assertNotEqual(r.returncode, 0, extra)
            self.assertIn(says, r.stderr, extra)
            self.assertEqual(r.stderr.count("\n"), 1, r.stderr)
            self.assertFalse(os.path.exists(os.path.join(self.dir, "bad", "state")), extra)
        # A job folder holding another job's parts.
        folder = os.path.join(self.dir, "job")
        self.farm("submit", ANIMATED, "-o", out, "--job-dir", folder, "--frames", "1-1", *JOB)
        self.wait_merged(folder, 1)
        before = len(records(folder))
        r = self.farm("submit", ANIMATED, "-o", out, "--job-dir", folder, "--frames", "1-1",
                      *(JOB[:-1] + ["4"]), expect=2)
        self.assertIn("another job (render_args differ)", r.stderr)
        self.assertEqual(len(records(folder)), before)


def start_cluster():
    """Starts the one-machine cluster; returns (stop_after, reason_if_it_cannot_start)."""
    if os.geteuid() != 0:
        return False, "the one-machine Slurm cluster runs its daemons as root; run as root"
    if not shutil.which("apt-get") and not shutil.which("slurmctld"):
        return False, "no Slurm and no apt-get to install it"
    was_up = run([SLURM_LOCAL, "status"]).returncode == 0
    r = run([SLURM_LOCAL, "start"])
    if r.returncode != 0:
        return False, "tools/slurm-local.sh start failed: " + r.stderr.strip()[-300:]
    env = run([SLURM_LOCAL, "env"]).stdout.strip()
    os.environ["SLURM_CONF"] = env.split("=", 1)[1]
    return not was_up, None


if __name__ == "__main__":
    stop_after, reason = start_cluster()
    if reason:
        print("SKIPPED: Slurm cannot start here: " + reason)
        sys.exit(77)
    try:
        result = unittest.main(argv=[sys.argv[0]] + sys.argv[3:], exit=False, verbosity=2).result
    finally:
        if stop_after:
            run([SLURM_LOCAL, "stop"])
    sys.exit(0 if result.wasSuccessful() else 1)
