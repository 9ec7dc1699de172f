#!/usr/bin/env python3
"""Peak memory and time of `info`, `clean` and `segment` on a body of a million triangles or more,
and of `dress` given a garment beyond its size bound.

Splits every triangle of a shared body into k² (k = 5 on gc_mean_all: 1,187,500 triangles; edge
points shared, so the result is as closed as the body), writes it as OBJ in a temporary folder and
runs each command once under /usr/bin/time, reading its wall time and peak resident memory. The
garment (k = 8 on the man's casualsuit02: about 270,000 triangles) is dressed on the shared man.

  bench/large_mesh.py OUT.csv [--body PATH] [--k 5] [--garment PATH] [--garment-k 8]
                      [--tool build/bin/dress-a-mesh]
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time


def read_obj(path):
    V, F = [], []
    with open(path) as f:
        for line in f:
            if line.startswith('v '):
                V.append(tuple(float(x) for x in line.split()[1:4]))
            elif line.startswith('f '):
                idx = [int(w.split('/')[0]) - 1 for w in line.split()[1:]]
                for a in range(1, len(idx) - 1):
                    F.append((idx[0], idx[a], idx[a + 1]))
    return V, F


def subdivide(V, F, k):
    """Each triangle into k² by its barycentric grid; points on an edge are shared by both sides."""
    V = list(V)
    edge_points = {}

    def point(a, b, i):  # the i-th of the k−1 inner points from a to b
        key = (a, b, i) if a < b else (b, a, k - i)
        p = edge_points.get(key)
        if p is None:
            pa, pb = V[a], V[b]
            t = i / k
            V.append(tuple(pa[c] + t * (pb[c] - pa[c]) for c in range(3)))
            p = edge_points[key] = len(V) - 1
        return p

    out = []
    for a, b, c in F:
        pa, pb, pc = V[a], V[b], V[c]
        grid = {}
        for i in range(k + 1):          # along a→b
            for j in range(k + 1 - i):  # along a→c
                if i == 0 and j == 0:
                    g = a
                elif i == k:
                    g = b
                elif j == k:
                    g = c
                elif j == 0:
                    g = point(a, b, i)
                elif i == 0:
                    g = point(a, c, j)
                elif i + j == k:
                    g = point(b, c, j)
                else:
                    wa, wb, wc = (k - i - j) / k, i / k, j / k
                    V.append(tuple(wa * pa[d] + wb * pb[d] + wc * pc[d] for d in range(3)))
                    g = len(V) - 1
                grid[i, j] = g
        for i in range(k):
            for j in range(k - i):
                out.append((grid[i, j], grid[i + 1, j], grid[i, j + 1]))
                if i + j < k - 1:
                    out.append((grid[i + 1, j], grid[i + 1, j + 1], grid[i, j + 1]))
    return V, out


def write_obj(path, V, F):
    with open(path, 'w') as f:
        f.write(''.join('v %.7f %.7f %.7f\n' % p for p in V))
        f.write(''.join('f %d %d %d\n' % (a + 1, b + 1, c + 1) for a, b, c in F))


def timed(cmd):
    """Runs cmd under /usr/bin/time; returns (exit code, wall seconds, peak RSS in MB)."""
    with tempfile.NamedTemporaryFile('r', suffix='.time') as t:
        p = subprocess.run(['/usr/bin/time', '-f', '%e %M', '-o', t.name] + cmd,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        wall, kb = t.read().split()[-2:]
    if p.returncode != 0:
        sys.stderr.write(p.stderr)
    return p.returncode, float(wall), int(kb) / 1024.0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('csv')
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    data = os.environ.get('DRESSKIT_DATA_DIR', os.path.join(root, '..', 'shared', 'data'))
    ap.add_argument('--body', default=os.path.join(data, 'bodies', 'gc_mean_all.obj'))
    ap.add_argument('--k', type=int, default=5)
    ap.add_argument('--garment', default=os.path.join(data, 'garments', 'mh_male_casualsuit02.obj'))
    ap.add_argument('--garment-k', type=int, default=8)
    ap.add_argument('--garment-body', default=os.path.join(data, 'bodies', 'mh_man_young_average.obj'))
    ap.add_argument('--tool', default=os.path.join(root, 'build', 'bin', 'dress-a-mesh'))
    args = ap.parse_args()
    GV, GF = subdivide(*read_obj(args.garment), args.garment_k)
    V, F = read_obj(args.body)
    t0 = time.time()
    V, F = subdivide(V, F, args.k)
    with tempfile.TemporaryDirectory() as tmp:
        body = os.path.join(tmp, 'body.obj')
        write_obj(body, V, F)
        print('%s split %d × %d: %d vertices, %d triangles (%.1f s)' %
              (os.path.basename(args.body), args.k, args.k, len(V), len(F), time.time() - t0))
        garment = os.path.join(tmp, 'garment.obj')
        write_obj(garment, GV, GF)
        print('%s split %d × %d: %d vertices, %d triangles' %
              (os.path.basename(args.garment), args.garment_k, args.garment_k, len(GV), len(GF)))
        runs = [('info', [args.tool, 'info', body], F, V),
                ('clean', [args.tool, 'clean', body, '-o', os.path.join(tmp, 'clean.obj')], F, V),
                ('segment', [args.tool, 'segment', body, '-o', os.path.join(tmp, 'segment')], F, V),
                ('dress (garment)', [args.tool, 'dress', args.garment_body, garment, '--units', 'dm',
                                     '-o', os.path.join(tmp, 'dress')], GF, GV)]
        rows = []
        for name, cmd, faces, vertices in runs:
            code, wall, mb = timed(cmd)
            rows.append({'command': name, 'triangles': len(faces), 'vertices': len(vertices), 'exit_code': code,
                         'wall_seconds': wall, 'peak_rss_mb': round(mb, 1)})
            print('%-8s exit %d  %7.1f s  %8.1f MB' % (name, code, wall, mb))
    os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
    with open(args.csv, 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


if __name__ == '__main__':
    main()
