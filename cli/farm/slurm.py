"""The Slurm command-line clients tray-farm drives (sbatch, squeue, scontrol, scancel): no
accounting database, no library, so any Slurm installation that runs jobs serves."""

import shutil
import subprocess


class SlurmError(Exception):
    """A Slurm client is missing or failed; the message is one line for the user."""


def _run(args, timeout=60):
    if not shutil.which(args[0]):
        raise SlurmError("%s not found: install Slurm's clients (Debian: slurm-client), or try "
                         "a one-machine cluster with tools/slurm-local.sh start" % args[0])
    try:
        return subprocess.run(args, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise SlurmError("%s did not answer in %d s: is slurmctld reachable?" % (args[0], timeout))


def _one_line(text):
    return " ".join(text.split())


def check_controller():
    """Raises SlurmError unless sbatch exists and the controller answers."""
    if not shutil.which("sbatch"):
        _run(["sbatch"])  # raises the "not found" message
    r = _run(["scontrol", "ping"], timeout=30)
    if r.returncode != 0 or " is UP" not in r.stdout:
        reply = _one_line(r.stdout + r.stderr) or "no reply"
        raise SlurmError("the Slurm controller does not answer (scontrol ping: %s); is slurmctld "
                         "running and SLURM_CONF set? (tools/slurm-local.sh env)" % reply)


def sbatch(script, options, script_args=()):
    """Submits `script` with sbatch `options`; returns the job id."""
    r = _run(["sbatch", "--parsable"] + list(options) + [script] + list(script_args))
    if r.returncode != 0:
        raise SlurmError("sbatch refused the job: " + _one_line(r.stderr or r.stdout))
    return r.stdout.strip().split(";")[0]


def queued(job_ids):
    """{"ID" or "ID_TASK": state} of the jobs and array tasks still known to the queue
    (PENDING, RUNNING, ...). A job that has ended is not in it."""
    if not job_ids:
        return {}
    r = _run(["squeue", "-h", "-r", "-o", "%i %T", "-j", ",".join(job_ids)])
    states = {}
    for line in r.stdout.splitlines():
        fields = line.split()
        if len(fields) == 2:
            states[fields[0]] = fields[1]
    return states


def cancel(job_ids):
    """Cancels the jobs (scancel: SIGTERM, then SIGKILL after the cluster's KillWait)."""
    if job_ids:
        r = _run(["scancel"] + list(job_ids))
        if r.returncode != 0 and "Invalid job id" not in r.stderr:
            raise SlurmError("scancel failed: " + _one_line(r.stderr))
