#!/usr/bin/python3
"""Prints a Slurm job's state for Snakemake: running, success or failed.

usage: status.py JOBID

Asks squeue (which lists finished jobs for MinJobAge, 300 s by default), then scontrol, then sacct
where accounting is set up. Works on any Slurm: no accounting database needed, no environment
variables read. A controller that does not answer is reported as running (asked again later); a job
no command knows any more is reported failed, as its result cannot be confirmed.
"""
import subprocess
import sys

RUNNING = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "REQUEUE_HOLD",
           "REQUEUE_FED", "RESIZING", "SIGNALING", "STAGE_OUT", "STOPPED", "RESV_DEL_HOLD", "POWER_UP_NODE"}
SUCCESS = {"COMPLETED"}


def ask(args):
    """(answered, output): answered is False when the command failed for a reason other than an
    unknown job id."""
    try:
        r = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return False, ""
    if r.returncode != 0:
        return "Invalid job id" in r.stderr, ""
    return True, r.stdout.strip()


def verdict(state):
    state = state.split()[0].rstrip("+") if state.split() else ""
    if state in SUCCESS:
        return "success"
    if state in RUNNING:
        return "running"
    return "failed"  # FAILED, CANCELLED, TIMEOUT, OUT_OF_MEMORY, NODE_FAIL, BOOT_FAIL, DEADLINE, PREEMPTED


def main(argv):
    if len(argv) != 2:
        raise SystemExit("usage: status.py JOBID")
    job = argv[1].split(";")[0].strip()
    answered_any = False

    answered, out = ask(["squeue", "--noheader", "--jobs", job, "--states", "all", "--format", "%T"])
    answered_any |= answered
    if out:
        return verdict(out.splitlines()[0])

    answered, out = ask(["scontrol", "--oneliner", "show", "job", job])
    answered_any |= answered
    for field in out.split():
        if field.startswith("JobState="):
            return verdict(field[len("JobState="):])

    answered, out = ask(["sacct", "--noheader", "--parsable2", "--jobs", job, "--format", "State", "--allocations"])
    if out:
        return verdict(out.splitlines()[0])

    if not answered_any:
        print("status.py: Slurm did not answer about job %s; asking again later" % job, file=sys.stderr)
        return "running"
    print("status.py: Slurm no longer knows job %s (older than its MinJobAge, no accounting)" % job,
          file=sys.stderr)
    return "failed"


if __name__ == "__main__":
    print(main(sys.argv))
