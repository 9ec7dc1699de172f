#!/usr/bin/python3
"""Measures the batch workflow against calling dress-a-mesh directly, on N copies of one row.

usage: workflow/scripts/measure.py [--rows 4] [--repeat 2] [--dress build/bin/dress-a-mesh]
                                   [--data ../shared/data] [--slurm]

Per repetition, on fresh output folders:
  direct 1                   the N dress commands one after another
  engine 1                   snakemake --cores 1 OUT/<id>/report.json...: the N commands as jobs
  engine, nothing to do      the same again: reading the workflow and finding nothing to do
  summary and contact sheet  snakemake --cores 1 on engine 1's folder: only the gathering runs
  direct 2                   the N dress commands two at a time
  engine 2                   snakemake --cores 2: the N rows, summary.csv and the contact sheet
  slurm                      (--slurm) as engine 2 through workflow/profiles/slurm; needs a
                             running cluster (scripts/slurm-local start)
Prints the median wall-clock seconds of each, rows per hour (N / seconds × 3600), and the engine's
overhead measured inside each engine 1 run, where jobs run one at a time: its wall-clock time less
the time its N jobs took (their benchmark.tsv), split into the start of the run (the nothing-to-do
run) and the rest, per job. That does not depend on how busy the machine was during other runs,
as the difference engine 1 - direct 1 does on a shared machine. The row is the MakeHuman
casualsuit on the 11-year-old girl, both in decimetres, quality fast.
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def timed(command, cwd, parallel=1):
    """Wall-clock seconds of the commands (a list of argument lists), `parallel` at a time."""
    started = time.time()
    running = []
    for c in command:
        while len(running) >= parallel:
            running.pop(0).wait()
        running.append(subprocess.Popen(c, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    codes = [p.wait() for p in running]
    if any(codes):
        raise SystemExit("measure.py: a command failed: %s" % command)
    return time.time() - started


def job_seconds(path):
    with open(path) as f:
        return float(f.read().splitlines()[1].split("\t")[0])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rows", type=int, default=4)
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--dress", default=os.path.join(REPO, "build", "bin", "dress-a-mesh"))
    parser.add_argument("--data", default=os.environ.get("DRESSKIT_DATA_DIR") or os.path.join(REPO, "..", "shared", "data"))
    parser.add_argument("--slurm", action="store_true")
    args = parser.parse_args()
    dress, data = os.path.abspath(args.dress), os.path.abspath(args.data)
    body = os.path.join(data, "bodies", "mh_girl_child_11y.obj")
    garment = os.path.join(data, "garments", "mh_female_casualsuit01.obj")
    snakemake = shutil.which("snakemake") or sys.exit("measure.py: snakemake not found")
    snakefile = os.path.join(REPO, "workflow", "Snakefile")

    tmp = tempfile.mkdtemp(prefix="dresskit_measure_")
    manifest = os.path.join(tmp, "manifest.csv")
    ids = ["r%d" % i for i in range(args.rows)]
    with open(manifest, "w") as f:
        f.write("id,body,garments,body_units,garment_units\n")
        for i in ids:
            f.write("%s,%s,%s,dm,dm\n" % (i, body, garment))

    def direct(out):
        return [[dress, "dress", body, garment, "--body-units", "dm", "--garment-units", "dm",
                 "--quality", "fast", "-o", os.path.join(out, i)] for i in ids]

    def engine(out, *options):
        # Options and targets before --config, which takes every word after it.
        return [[snakemake, "-s", snakefile] + list(options) +
                ["--config", "manifest=" + manifest, "out=" + out, "dress=" + dress]]

    seconds = {}
    overhead = []  # per engine 1 run: (seconds outside the jobs, the jobs' seconds, startup seconds)

    loads = []  # the 1-minute load average after each measured case: how busy the machine was

    def record(name, value):
        seconds.setdefault(name, []).append(value)
        loads.append(os.getloadavg()[0])
        print("  %s: %.1f s (load average %.1f)" % (name, value, loads[-1]), file=sys.stderr, flush=True)
        return value

    try:
        for r in range(args.repeat):
            out = lambda name: os.path.join(tmp, "%s-%d" % (name, r))
            record("direct 1", timed(direct(out("direct1")), tmp, 1))
            reports = [os.path.join(out("engine1"), i, "report.json") for i in ids]
            whole = record("engine 1", timed(engine(out("engine1"), "--cores", "1", *reports), tmp))
            jobs = sum(job_seconds(os.path.join(out("engine1"), i, "benchmark.tsv")) for i in ids)
            # The same command again finds nothing to do: what every run costs before its jobs.
            startup = record("engine, nothing to do", timed(engine(out("engine1"), "--cores", "1", *reports), tmp))
            overhead.append((whole - jobs, jobs, startup))
            record("summary and contact sheet", timed(engine(out("engine1"), "--cores", "1"), tmp))
            record("direct 2", timed(direct(out("direct2")), tmp, 2))
            record("engine 2", timed(engine(out("engine2"), "--cores", "2", "--keep-going"), tmp))
            if args.slurm:
                profile = os.path.join(REPO, "workflow", "profiles", "slurm")
                record("slurm", timed(engine(out("slurm"), "--profile", profile), tmp))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    n = args.rows
    median = {name: statistics.median(v) for name, v in seconds.items()}
    print("%d rows, %d repetitions; median wall-clock seconds (each repetition's); %d CPUs, "
          "1-minute load average %.1f to %.1f during the runs" % (n, args.repeat, os.cpu_count(), min(loads), max(loads)))
    for name in seconds:
        rate = "" if name in ("engine, nothing to do", "summary and contact sheet") else \
            "  %4.0f rows/h" % (n / median[name] * 3600)
        print("  %-26s %6.1f s%s  (%s)" % (name, median[name], rate, ", ".join("%.1f" % v for v in seconds[name])))
    for outside, jobs, startup in overhead:
        print("  engine 1: jobs %.1f s, engine %.2f s outside them: %.2f s at the start, %.2f s per job (%.1f %%); "
              "all of it %.1f %% of the jobs' time" % (jobs, outside, startup, (outside - startup) / n,
                                                      100 * (outside - startup) / jobs, 100 * outside / jobs))
    per_job = statistics.median((o - s) / n for o, _, s in overhead)
    share = statistics.median((o - s) / j for o, j, s in overhead)
    total = statistics.median(o / j for o, j, _ in overhead)
    print("engine overhead (median): %.2f s per job (%.1f %% of a job), %.1f %% with the start of the run "
          "spread over %d rows" % (per_job, 100 * share, 100 * total, n))


if __name__ == "__main__":
    main()
