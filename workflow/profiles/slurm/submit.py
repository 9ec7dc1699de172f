#!/usr/bin/python3
"""Submits one Snakemake job to Slurm and prints its job id.

usage: submit.py [SBATCH_OPTION...] JOBSCRIPT

The job asks for its rule's declared threads (--cpus-per-task), resources.mem_mb (--mem, MB) and
resources.runtime (--time, minutes); resources.slurm_partition and resources.slurm_account, when a
rule or --default-resources sets them, become --partition and --account. Options given before the
jobscript (in the profile's `cluster:` line) go to sbatch as they are and come last, so they win.
Slurm's own output of the job goes beside the rule's log: <log folder>/slurm-<rule>-<job id>.out.
"""
import json
import os
import re
import subprocess
import sys


def properties(jobscript):
    pattern = re.compile(r"# properties = (.*)")
    with open(jobscript) as f:
        for line in f:
            m = pattern.match(line)
            if m:
                return json.loads(m.group(1))
    raise SystemExit("submit.py: %s has no '# properties' line (not a Snakemake jobscript?)" % jobscript)


def main(argv):
    if len(argv) < 2:
        raise SystemExit(__doc__.strip())
    extra, jobscript = argv[1:-1], argv[-1]
    job = properties(jobscript)
    resources = job.get("resources", {})
    rule = job.get("rule") or job.get("groupid") or "job"
    wildcards = job.get("wildcards", {})
    name = "-".join(["dresskit", rule] + [str(v) for v in wildcards.values()])
    logs = job.get("log") or []
    folder = os.path.dirname(logs[0]) if logs else os.path.join(os.getcwd(), "slurm-logs")
    os.makedirs(folder, exist_ok=True)
    args = ["sbatch", "--parsable", "--job-name=" + name,
            "--output=" + os.path.join(folder, "slurm-%s-%%j.out" % rule),
            "--cpus-per-task=%d" % int(job.get("threads", 1))]
    if "mem_mb" in resources:
        args.append("--mem=%d" % int(resources["mem_mb"]))
    if "runtime" in resources:
        args.append("--time=%d" % max(1, int(resources["runtime"])))
    if resources.get("slurm_partition"):
        args.append("--partition=%s" % resources["slurm_partition"])
    if resources.get("slurm_account"):
        args.append("--account=%s" % resources["slurm_account"])
    args += extra + [jobscript]
    try:
        out = subprocess.run(args, check=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             timeout=120)
    except FileNotFoundError:
        raise SystemExit("submit.py: sbatch not found: Slurm's commands are not on this machine")
    except subprocess.CalledProcessError as e:
        raise SystemExit("submit.py: %s failed: %s" % (" ".join(args), e.stderr.strip()))
    except subprocess.TimeoutExpired:
        raise SystemExit("submit.py: sbatch did not answer within 120 s")
    # --parsable prints "jobid" or "jobid;cluster".
    print(out.stdout.strip().split(";")[0])


if __name__ == "__main__":
    main(sys.argv)
