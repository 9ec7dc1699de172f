#!/usr/bin/python3
"""Open3D's point-to-plane ICP on the same known-transform pairs as dresskit's ICP (a bench aid).

Writes the pairs with `bench_alignment --export DIR` first, then runs Open3D (Debian's python3-open3d)
with the same correspondence-distance schedule and iteration budget, and prints time and error ratios.

usage: OMP_NUM_THREADS=1 scripts/bench_open3d_icp.py DIR   (DIR: pair files and dresskit.csv written by
       build/bin/bench_alignment --only export --export DIR; one thread, as dresskit runs on one core)
"""
import csv
import glob
import math
import os
import sys
import time

import numpy as np
import open3d as o3d


def rotation_error_deg(estimated, truth):
    a = estimated[:3, :3] / np.cbrt(np.linalg.det(estimated[:3, :3]))
    d = a @ truth[:3, :3].T
    return math.degrees(math.acos(max(-1.0, min(1.0, (np.trace(d) - 1) / 2))))


def main(folder):
    reg = o3d.pipelines.registration
    rows = {r["pair"]: r for r in csv.DictReader(open(os.path.join(folder, "dresskit.csv")))}
    out = []
    for path in sorted(glob.glob(os.path.join(folder, "pair_*.txt"))):
        name = os.path.basename(path)[:-4]
        lines = open(path).read().split("\n")
        truth = np.array([float(x) for x in lines[0].split()]).reshape(4, 4)
        centre = np.array([float(x) for x in lines[1].split()])
        diagonal = float(lines[2])
        source = np.loadtxt(os.path.join(folder, name + "_source.xyz"))
        target = np.loadtxt(os.path.join(folder, name + "_target.xyzn"))
        src = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(source))
        tgt = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(target[:, :3]))
        tgt.normals = o3d.utility.Vector3dVector(target[:, 3:])
        start = time.perf_counter()
        transform = np.eye(4)
        # Same schedule as dresskit's defaults: centred start, 3 stages, 40 iterations each.
        for fraction in (0.2, 0.06, 0.02):
            result = reg.registration_icp(src, tgt, fraction * diagonal, transform,
                                          reg.TransformationEstimationPointToPlane(),
                                          reg.ICPConvergenceCriteria(1e-6, 1e-6, 40))
            transform = result.transformation
        seconds = time.perf_counter() - start
        c = np.append(centre, 1.0)
        rot = rotation_error_deg(transform, truth)
        trans = np.linalg.norm((transform @ c - truth @ c)[:3]) / diagonal * 100
        d = rows[name]
        out.append((name, d["angle"], rot, trans, seconds, float(d["rotation_deg"]), float(d["translation_percent"]),
                    float(d["seconds"])))
    print("| pair | θ [°] | Open3D rot. err. [°] | dresskit rot. err. [°] | Open3D transl. [%] | dresskit transl. [%] | "
          "Open3D [ms] | dresskit [ms] | time ratio dresskit/Open3D |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n, a, r, t, s, dr, dt, ds in out:
        print("| %s | %s | %.3f | %.3f | %.3f | %.3f | %.1f | %.1f | %.2f |" % (n, a, r, dr, t, dt, s * 1e3, ds * 1e3, ds / s))
    ok_o = sum(1 for o in out if o[2] < 0.5 and o[3] < 0.5)
    ok_d = sum(1 for o in out if o[5] < 0.5 and o[6] < 0.5)
    med = lambda xs: float(np.median(xs))
    print("\nsuccess (rot < 0.5°, transl < 0.5%%): Open3D %d/%d, dresskit %d/%d" % (ok_o, len(out), ok_d, len(out)))
    print("median rotation error ratio dresskit/Open3D: %.2f; median time ratio dresskit/Open3D: %.2f"
          % (med([o[5] / max(o[2], 1e-9) for o in out]), med([o[7] / o[4] for o in out])))
    total_o, total_d = sum(o[4] for o in out), sum(o[7] for o in out)
    print("total time over the %d pairs: Open3D %.0f ms, dresskit %.0f ms (ratio %.2f)"
          % (len(out), total_o * 1e3, total_d * 1e3, total_d / total_o))


if __name__ == "__main__":
    main(sys.argv[1])
