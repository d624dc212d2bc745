#!/usr/bin/env python3
"""tray-farm on a real one-machine Slurm cluster (tools/slurm-local.sh): a 2-frame x 4-part job
merged bit for bit against single-machine renders, a part killed mid-way and resumed, a part
that fails and is retried, a cancelled job, and bad input refused before anything is submitted.
The failing part is a wrapper tray-render given with --bin, not a hook in tray-farm's scripts.
Each test writes into a folder of its own under $TMPDIR, removed after the run unless the test
failed. Exit 77 (ctest: skipped) only where Slurm cannot start, with the reason.

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
MERGE = os.path.join(BIN, "tray-merge")
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


def failing_bin(folder, task, calls):
    """A --bin folder whose tray-render fails array task `task` on its first attempt
    (TRAY_FARM_ATTEMPT 0), as a crashed machine would, and otherwise execs the real one (SIGTERM
    still reaches the renderer); every call appends "TASK ATTEMPT" to `calls`."""
    os.makedirs(folder)
    wrapper = os.path.join(folder, "tray-render")
    with open(wrapper, "w") as f:
        f.write("""#!/bin/sh
echo "$SLURM_ARRAY_TASK_ID ${TRAY_FARM_ATTEMPT:-unset}" >>'%s'
if [ "$SLURM_ARRAY_TASK_ID" = %d ] && [ "${TRAY_FARM_ATTEMPT:-0}" = 0 ]; then
  echo "test wrapper: part $SLURM_ARRAY_TASK_ID fails on its first attempt" >&2; exit 1
fi
exec '%s' "$@"
""" % (calls, task, RENDER))
    os.chmod(wrapper, 0o755)
    os.symlink(MERGE, os.path.join(folder, "tray-merge"))
    return folder


class FarmOnSlurm(unittest.TestCase):
    folders = []  # (test id, folder): removed after the run unless that test failed

    def setUp(self):
        self.dir = os.path.join(tempfile.gettempdir(), "FarmOnSlurm." + self._testMethodName)
        shutil.rmtree(self.dir, ignore_errors=True)  # kept by an earlier failed run
        os.makedirs(self.dir)
        self.folders.append((self.id(), self.dir))

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
        calls = os.path.join(self.dir, "calls.txt")
        fake = failing_bin(os.path.join(self.dir, "bin"), 1, calls)
        folder = self.submit(ANIMATED, ["--frames", "1-1", "--split", "samples:2", "--retries",
                                        "1", "--bin", fake] + JOB)
        self.wait_merged(folder, 1)
        parts = [r for r in records(folder) if r["kind"] == "parts"]
        self.assertEqual([p["tasks"] for p in parts], [[0, 1], [1]])  # only the failed one again
        # The wrapper ran every part: part 1 failed once, then its retry (attempt 1) rendered.
        self.assertEqual(sorted(text(calls).splitlines()), ["0 0", "1 0", "1 1"])
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
            (["--frames", "0-100000000"], None, "more than 100000"),  # was unbounded memory
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
    """Starts the one-machine cluster; returns (stop_after, cluster_folder_to_remove_after,
    reason_if_it_cannot_start). The folder (config, munge key, state, logs) is removed after a
    passing run only if this test created it: a cluster someone else set up keeps its own."""
    if os.geteuid() != 0:
        return False, None, "the one-machine Slurm cluster runs its daemons as root; run as root"
    if not shutil.which("apt-get") and not shutil.which("slurmctld"):
        return False, None, "no Slurm and no apt-get to install it"
    conf = run([SLURM_LOCAL, "env"]).stdout.strip().split("=", 1)[1]
    folder = os.path.dirname(conf)
    created = not os.path.exists(folder)
    was_up = run([SLURM_LOCAL, "status"]).returncode == 0
    r = run([SLURM_LOCAL, "start"])
    if r.returncode != 0:
        return False, None, "tools/slurm-local.sh start failed: " + r.stderr.strip()[-300:]
    os.environ["SLURM_CONF"] = conf
    return not was_up, folder if created else None, None


if __name__ == "__main__":
    stop_after, cluster_folder, reason = start_cluster()
    if reason:
        print("SKIPPED: Slurm cannot start here: " + reason)
        sys.exit(77)
    try:
        result = unittest.main(argv=[sys.argv[0]] + sys.argv[3:], exit=False, verbosity=2).result
    finally:
        if stop_after:
            run([SLURM_LOCAL, "stop"])
    if stop_after and cluster_folder and result.wasSuccessful():
        shutil.rmtree(cluster_folder, ignore_errors=True)
    failed = {test.id() for test, _ in result.failures + result.errors}
    for test_id, folder in FarmOnSlurm.folders:
        if test_id in failed:
            print("test files kept in " + folder)
        else:
            shutil.rmtree(folder, ignore_errors=True)
    sys.exit(0 if result.wasSuccessful() else 1)
