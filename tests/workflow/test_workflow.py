#!/usr/bin/env python3
"""Runs the batch workflow (workflow/Snakefile) for real on the shared data and checks its results.

usage: test_workflow.py local|bad_input|slurm --dress BINARY --source REPO --data DEFAULT_DATA_DIR

  local      three rows through the local profile: reports, summary.csv and contact sheet checked;
             one result deleted and the run repeated: only that row is redone; a third run does nothing
  bad_input  a manifest with an unknown file, a duplicate id, a row missing cells, an unusable id
             and a row whose dress fails, beside a good row; a manifest whose header lacks a column;
             a manifest that does not exist
  slurm      a one-node cluster started with scripts/slurm-local (unless one runs already), three
             rows submitted through workflow/profiles/slurm (one failing), then the failing row
             fixed and the run repeated; the cluster is stopped again if this test started it

Data: DRESSKIT_DATA_DIR if set, else --data. Exit 0 passed, 1 failed, 77 skipped (no data outside
CI, no Snakemake outside CI, Slurm not installed or unable to start). Runs without USER or LOGNAME
in the environment: the workflow must not need them.
"""
import argparse
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SKIP = 77
BODY = "bodies/mh_girl_child_11y.obj"
GARMENT = "garments/mh_female_casualsuit01.obj"
RUN_TIMEOUT = 180  # seconds for one snakemake run; the few runs and cluster start/stop stay within ctest's 900


class Failed(Exception):
    pass


class Skipped(Exception):
    pass


def skip(message):
    raise Skipped(message)


def check(condition, message):
    if not condition:
        raise Failed(message)


def in_ci():
    return os.environ.get("CI") == "true"


def environment():
    env = dict(os.environ)
    for name in ("USER", "LOGNAME"):
        env.pop(name, None)
    return env


class Runner:
    def __init__(self, args, tmp):
        self.args, self.tmp = args, tmp
        self.snakemake = shutil.which("snakemake")
        self.snakefile = os.path.join(args.source, "workflow", "Snakefile")
        self.count = 0

    def manifest(self, name, lines):
        path = os.path.join(self.tmp, name)
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")
        return path

    def run(self, manifest, out, profile="local", env=None):
        """Runs snakemake; returns (exit code, its output). Output is kept in a numbered log."""
        self.count += 1
        command = [self.snakemake, "-s", self.snakefile,
                   "--profile", os.path.join(self.args.source, "workflow", "profiles", profile),
                   "--config", "manifest=" + manifest, "out=" + out, "dress=" + self.args.dress]
        log = os.path.join(self.tmp, "snakemake-%d.log" % self.count)
        print("$ " + " ".join(command), flush=True)
        started = time.time()
        # In a process group of its own, so that a run past its time is interrupted whole (Snakemake then
        # cancels its Slurm jobs) and, failing that, killed whole.
        p = subprocess.Popen(command, cwd=self.tmp, env=env or environment(), stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True, preexec_fn=os.setsid)
        try:
            stdout, _ = p.communicate(timeout=RUN_TIMEOUT)
        except BaseException as e:  # past its time, or this test ended by a signal
            os.killpg(p.pid, signal.SIGINT)
            try:
                stdout, _ = p.communicate(timeout=60)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                stdout, _ = p.communicate()
            if not isinstance(e, subprocess.TimeoutExpired):
                raise
            raise Failed("snakemake did not finish within %d s; the end of its output:\n%s" % (
                RUN_TIMEOUT, stdout[-4000:]))
        r = subprocess.CompletedProcess(command, p.returncode, stdout)
        with open(log, "w") as f:
            f.write(r.stdout)
        print("  exit code %d after %.1f s (output in %s)" % (r.returncode, time.time() - started, log), flush=True)
        return r.returncode, r.stdout


def data_row(data, row_id, body_units="dm", relative_to=None):
    body, garment = os.path.join(data, BODY), os.path.join(data, GARMENT)
    if relative_to:
        body, garment = os.path.relpath(body, relative_to), os.path.relpath(garment, relative_to)
    return "%s,%s,%s,%s,dm" % (row_id, body, garment, body_units)


def summary(out):
    path = os.path.join(out, "summary.csv")
    check(os.path.isfile(path), "no %s" % path)
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def png_size(path):
    check(os.path.isfile(path), "no %s" % path)
    with open(path, "rb") as f:
        head = f.read(24)
    check(head[:8] == b"\x89PNG\r\n\x1a\n", "%s is not a PNG" % path)
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def jobs_run(output):
    """Row ids of the dress jobs a snakemake run started, from its output."""
    ids, in_dress = [], False
    for line in output.splitlines():
        if re.match(r"^(local)?rule \w+:", line):
            in_dress = line.startswith("rule dress:")
        m = re.match(r"^\s+wildcards: id=(\S+)", line)
        if m and in_dress:
            ids.append(m.group(1))
    return sorted(ids)


def check_ok_row(out, line, row_id):
    report_path = os.path.join(out, row_id, "report.json")
    check(os.path.isfile(report_path), "row %s: no report.json" % row_id)
    with open(report_path) as f:
        report = json.load(f)
    check(line["status"] == "ok", "row %s: status %r, expected ok (reason: %s)" % (row_id, line["status"], line["reason"]))
    check(len(report["garments"]) == 1, "row %s: %d garments in the report" % (row_id, len(report["garments"])))
    garment = report["garments"][0]
    for kind in ("placed", "dressed"):
        path = os.path.join(out, row_id, garment["outputs"][kind])
        check(os.path.isfile(path), "row %s: no %s" % (row_id, path))
    check(os.path.isfile(os.path.join(out, row_id, "dressed.glb")), "row %s: no dressed.glb" % row_id)
    # The summary holds the report's figures.
    check(abs(float(line["seconds"]) - report["seconds"]) < 0.01,
          "row %s: summary seconds %s, report %s" % (row_id, line["seconds"], report["seconds"]))
    stages = {s["name"]: s for s in report["stages"]}
    for name in ("load", "segmentation", "placement", "settle", "write"):
        check(line["seconds_" + name] != "" and abs(float(line["seconds_" + name]) - stages[name]["seconds"]) < 0.01,
              "row %s: seconds_%s %r, report %s" % (row_id, name, line["seconds_" + name], stages[name]["seconds"]))
    check(int(line["vertices_inside_dressed"]) == garment["vertices_inside_body_2mm"]["dressed"],
          "row %s: vertices_inside_dressed %s" % (row_id, line["vertices_inside_dressed"]))
    check(int(line["crossings_dressed"]) == garment["crossings"]["dressed"],
          "row %s: crossings_dressed %s" % (row_id, line["crossings_dressed"]))
    check(abs(float(line["max_strain"]) - garment["max_strain"]) < 1e-3,
          "row %s: max_strain %s, report %s" % (row_id, line["max_strain"], garment["max_strain"]))
    wearer = garment["wearer"]
    check(line["wearer_rms_mm_max"] != "" and abs(float(line["wearer_rms_mm_max"]) - wearer["rms_mm"]) < 0.01,
          "row %s: wearer_rms_mm_max %r, report %s" % (row_id, line["wearer_rms_mm_max"], wearer["rms_mm"]))
    check(line["job_seconds"] != "" and float(line["job_seconds"]) >= float(line["seconds"]) - 0.5,
          "row %s: job_seconds %r" % (row_id, line["job_seconds"]))


def test_local(runner, data):
    tmp = runner.tmp
    out = os.path.join(tmp, "out")
    # Row b names its files relative to the manifest's folder.
    manifest = runner.manifest("three.csv", ["id,body,garments,body_units,garment_units",
                                             data_row(data, "a"), data_row(data, "b", relative_to=tmp),
                                             data_row(data, "c")])
    code, output = runner.run(manifest, out)
    check(code == 0, "first run: exit code %d\n%s" % (code, output[-3000:]))
    check(jobs_run(output) == ["a", "b", "c"], "first run dressed %s" % jobs_run(output))
    lines = summary(out)
    check([l["id"] for l in lines] == ["a", "b", "c"], "summary ids %s" % [l["id"] for l in lines])
    check([l["line"] for l in lines] == ["2", "3", "4"], "summary lines %s" % [l["line"] for l in lines])
    for line in lines:
        check_ok_row(out, line, line["id"])
    width, height = png_size(os.path.join(out, "contact_sheet.png"))
    check(width >= 3 * 200 and height >= 200, "contact sheet %dx%d: too small for three tiles" % (width, height))
    print("  three rows dressed; reports, summary and contact sheet checked")

    # A deleted result is redone, and nothing else.
    before = {i: os.stat(os.path.join(out, i, "report.json")).st_mtime_ns for i in "ac"}
    shutil.rmtree(os.path.join(out, "b"))
    code, output = runner.run(manifest, out)
    check(code == 0, "second run: exit code %d\n%s" % (code, output[-3000:]))
    check(jobs_run(output) == ["b"], "second run dressed %s, expected only b" % jobs_run(output))
    after = {i: os.stat(os.path.join(out, i, "report.json")).st_mtime_ns for i in "ac"}
    check(before == after, "rows a and c were rewritten: %s -> %s" % (before, after))
    lines = summary(out)
    check([l["status"] for l in lines] == ["ok"] * 3, "summary after the re-run: %s" % [l["status"] for l in lines])
    check_ok_row(out, lines[1], "b")
    print("  b deleted and re-run: only b redone, a and c untouched")

    code, output = runner.run(manifest, out)
    check(code == 0 and jobs_run(output) == [] and "Nothing to be done" in output,
          "third run was to do nothing: exit code %d, dressed %s" % (code, jobs_run(output)))
    print("  third run: nothing to do")


def test_bad_input(runner, data):
    tmp = runner.tmp
    out = os.path.join(tmp, "out")
    missing = os.path.join(data, "garments", "no_such_garment.obj")
    body = os.path.join(data, BODY)
    manifest = runner.manifest("bad.csv", [
        "id,body,garments,body_units,garment_units",
        data_row(data, "a"),                                 # line 2: good
        "b,%s,%s,dm,dm" % (body, missing),                   # line 3: unknown file
        data_row(data, "a"),                                 # line 4: duplicate id
        data_row(data, "d", body_units="m"),                 # line 5: dress fails (a 12.7 m body)
        "e,%s,%s" % (body, os.path.join(data, GARMENT)),     # line 6: missing cells
        data_row(data, "x/y"),                               # line 7: not a folder name
        data_row(data, "a" * 250),                           # line 8: an id too long for a folder
        "n,%s\0,%s,dm,dm" % (body, os.path.join(data, GARMENT)),  # line 9: a NUL byte
    ])
    code, output = runner.run(manifest, out)
    check(code != 0, "a manifest with failing rows: exit code 0\n%s" % output[-3000:])
    expected = {  # line: (id, status, words of the reason)
        "2": ("a", "ok", ""),
        "3": ("b", "failed", "garment file not found: " + missing),
        "4": ("a", "failed", "id a is already used on line 2"),
        "5": ("d", "failed", "12.7 m tall"),
        "6": ("e", "failed", "no value for body_units, garment_units"),
        "7": ("x/y", "failed", "not usable as a folder name"),
        "8": ("a" * 250, "failed", "id is 250 characters long"),
        "9": ("n", "failed", "body holds a NUL byte"),
    }
    lines = {l["line"]: l for l in summary(out)}
    check(sorted(lines) == sorted(expected), "summary lines %s" % sorted(lines))
    for number, (row_id, status, words) in expected.items():
        line = lines[number]
        check(line["id"] == row_id and line["status"] == status,
              "line %s: id %r status %r, expected %s %s" % (number, line["id"], line["status"], row_id, status))
        check(words in line["reason"], "line %s: reason %r lacks %r" % (number, line["reason"], words))
        if status == "failed":
            # The run's output names the row and why.
            pattern = "line %s (id %s): failed: " % (number, row_id)
            check(any(pattern in l and words in l for l in output.splitlines()),
                  "the output does not name line %s and why (%r)\n%s" % (number, words, output[-3000:]))
    check(lines["5"]["exit_code"] == "2", "line 5: exit code %r, expected 2" % lines["5"]["exit_code"])
    check("exit code 2" in output, "the output does not give dress's exit code 2")
    check_ok_row(out, lines["2"], "a")
    check(jobs_run(output) == ["a", "d"], "dressed %s, expected a and d" % jobs_run(output))
    png_size(os.path.join(out, "contact_sheet.png"))
    print("  unknown file, duplicate id, missing cells, unusable id and a failing dress: named, "
          "marked failed; the good row dressed")

    # A header without a required column: every row named, none run, the summary says why.
    out2 = os.path.join(tmp, "out-no-column")
    manifest = runner.manifest("no-column.csv", [
        "id,body,garments,body_units",
        "p,%s,%s,dm" % (body, os.path.join(data, GARMENT)),
        "q,%s,%s,dm" % (body, os.path.join(data, GARMENT))])
    code, output = runner.run(manifest, out2)
    check(code != 0, "a header without garment_units: exit code 0")
    lines = summary(out2)
    check([(l["id"], l["status"]) for l in lines] == [("p", "failed"), ("q", "failed")],
          "summary %s" % [(l["id"], l["status"]) for l in lines])
    for l, number in zip(lines, ("2", "3")):
        check("no column garment_units" in l["reason"], "line %s: reason %r" % (number, l["reason"]))
        check("line %s (id %s): failed: " % (number, l["id"]) in output, "output does not name line %s" % number)
    check(jobs_run(output) == [], "rows were dressed: %s" % jobs_run(output))
    print("  a header without garment_units: both rows named and marked failed, none run")

    # A manifest that is not UTF-8: refused in one line naming the byte, not a traceback.
    latin = os.path.join(tmp, "latin1.csv")
    with open(latin, "wb") as f:
        f.write(b"id,body,garments,body_units,garment_units\nz\xe9,b.obj,g.obj,dm,dm\n")
    code, output = runner.run(latin, os.path.join(tmp, "out-latin1"))
    check(code != 0 and "not UTF-8 text (byte 43: 0xe9)" in output and "Traceback" not in output,
          "a Latin-1 manifest: exit code %d\n%s" % (code, output[-2000:]))
    print("  a manifest that is not UTF-8: refused naming the byte")

    code, output = runner.run(os.path.join(tmp, "absent.csv"), os.path.join(tmp, "out-absent"))
    check(code != 0 and "manifest not found" in output, "a missing manifest: exit code %d\n%s" % (code, output[-2000:]))
    print("  a missing manifest: refused")


def slurm_local(source, command, timeout):
    script = os.path.join(source, "scripts", "slurm-local")
    try:
        r = subprocess.run([script, command], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return 124, "scripts/slurm-local %s did not finish within %d s" % (command, timeout)
    return r.returncode, r.stdout.strip()


def test_slurm(runner, data):
    needed = ["slurmctld", "slurmd", "sbatch", "squeue", "scontrol", "munged"]
    absent = [c for c in needed if not shutil.which(c) and not os.path.exists("/usr/sbin/" + c)]
    if absent:
        skip("Slurm cannot start here: %s not installed (Debian packages slurm-wlm and munge)" % ", ".join(absent))
    if os.geteuid() != 0 and subprocess.run(["sudo", "-n", "true"], capture_output=True).returncode != 0:
        skip("Slurm cannot start here: scripts/slurm-local needs root or sudo without a password")
    source, tmp = runner.args.source, runner.tmp
    running, _ = slurm_local(source, "status", 30)
    started = False
    if running != 0:
        code, message = slurm_local(source, "start", 120)
        if code != 0:
            slurm_local(source, "stop", 60)
            skip("Slurm cannot start here: scripts/slurm-local start said:\n" + message)
        started = True
        print("  " + message.splitlines()[-1])
    else:
        print("  using the one-node cluster already running (left running)")
    try:
        out = os.path.join(tmp, "out")
        rows = ["id,body,garments,body_units,garment_units", data_row(data, "a"), data_row(data, "b"),
                data_row(data, "f", body_units="m")]
        manifest = runner.manifest("slurm.csv", rows)
        code, output = runner.run(manifest, out, profile="slurm")
        check(code != 0, "a failing row on Slurm: exit code 0")
        check(re.search(r"Submitted job \d+ with external jobid '\d+'", output), "no job was submitted to Slurm")
        lines = summary(out)
        check([(l["id"], l["status"]) for l in lines] == [("a", "ok"), ("b", "ok"), ("f", "failed")],
              "summary %s" % [(l["id"], l["status"], l["reason"]) for l in lines])
        check("12.7 m tall" in lines[2]["reason"] and lines[2]["exit_code"] == "2", "row f: %s" % lines[2])
        for line in lines[:2]:
            check_ok_row(out, line, line["id"])
        # Each row ran as a Slurm job asking for the rule's declared resources.
        for row_id in ("a", "b", "f"):
            outs = [n for n in os.listdir(os.path.join(out, row_id)) if re.match(r"slurm-dress-\d+\.out$", n)]
            check(outs, "row %s: no Slurm output file (slurm-dress-<job>.out)" % row_id)
        job = re.search(r"\d+", [n for n in os.listdir(os.path.join(out, "a")) if n.startswith("slurm-dress-")][0]).group(0)
        shown = subprocess.run(["scontrol", "--oneliner", "show", "job", job], capture_output=True, text=True).stdout
        for field in ("JobState=COMPLETED", "NumCPUs=1", "MinMemoryNode=1000M", "TimeLimit=00:15:00"):
            check(field in shown.split(), "Slurm job %s lacks %s: %s" % (job, field, shown))
        print("  three rows submitted to Slurm: two dressed, one failed and named; jobs asked 1 CPU, 1000 MB, 15 min")

        # The failing row fixed: only it runs, then the summary (as a Slurm job too).
        before = {i: os.stat(os.path.join(out, i, "report.json")).st_mtime_ns for i in "ab"}
        rows[3] = data_row(data, "f")
        runner.manifest("slurm.csv", rows)
        code, output = runner.run(manifest, out, profile="slurm")
        check(code == 0, "second run on Slurm: exit code %d\n%s" % (code, output[-3000:]))
        check(jobs_run(output) == ["f"], "second run dressed %s, expected only f" % jobs_run(output))
        after = {i: os.stat(os.path.join(out, i, "report.json")).st_mtime_ns for i in "ab"}
        check(before == after, "rows a and b were rewritten")
        lines = summary(out)
        check([l["status"] for l in lines] == ["ok"] * 3, "summary after the fix: %s" % [l["status"] for l in lines])
        check(any(re.match(r"slurm-summary-\d+\.out$", n) for n in os.listdir(out)), "the summary did not run on Slurm")
        png_size(os.path.join(out, "contact_sheet.png"))
        print("  row f fixed and re-run: only f redone; summary made by a Slurm job")
        left = subprocess.run(["squeue", "--noheader", "--format", "%i %j"], capture_output=True, text=True).stdout
        check(not any(" dresskit-" in " " + l for l in left.splitlines()), "jobs left in the queue: %s" % left)
    finally:
        if started:
            code, message = slurm_local(source, "stop", 90)
            print("  " + (message.splitlines()[-1] if message else "stopped"))
            if code != 0:
                raise Failed("scripts/slurm-local stop failed: " + message)
            code, message = slurm_local(source, "status", 30)
            if code == 0:
                raise Failed("the cluster still runs after scripts/slurm-local stop: " + message)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("case", choices=["local", "bad_input", "slurm"])
    parser.add_argument("--dress", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--data", required=True)
    args = parser.parse_args()
    # ctest ends a test that runs too long with a signal: leave through the cleanup below.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit("terminated"))

    data = os.environ.get("DRESSKIT_DATA_DIR") or args.data
    if not os.path.isdir(data):
        if in_ci():
            print("FAILED: data folder missing under CI: %s" % data)
            return 1
        print("SKIPPED: data folder not found: %s (set DRESSKIT_DATA_DIR)" % data)
        return SKIP
    if not shutil.which("snakemake"):
        if in_ci():
            print("FAILED: snakemake not found under CI (scripts/install-deps installs it)")
            return 1
        print("SKIPPED: snakemake not found (Debian package snakemake; scripts/install-deps installs it)")
        return SKIP
    if not os.access(args.dress, os.X_OK):
        print("FAILED: dress-a-mesh not found: %s" % args.dress)
        return 1

    tmp = tempfile.mkdtemp(prefix="dresskit_workflow_%s_" % args.case)
    runner = Runner(args, tmp)
    try:
        {"local": test_local, "bad_input": test_bad_input, "slurm": test_slurm}[args.case](runner, data)
    except Failed as e:
        print("FAILED: %s\n(files kept in %s)" % (e, tmp))
        return 1
    except Skipped as e:
        shutil.rmtree(tmp, ignore_errors=True)
        print("SKIPPED: %s" % e)
        return SKIP
    shutil.rmtree(tmp, ignore_errors=True)
    print("PASSED: workflow %s" % args.case)
    return 0


if __name__ == "__main__":
    sys.exit(main())
