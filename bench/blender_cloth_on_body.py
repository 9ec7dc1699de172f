"""Blender's built-in cloth dropped onto a human body's head, as an independent baseline.

Builds the scene from scratch in dresskit's Y-up coordinates and converts them to Blender's Z-up
ones ((x, y, z)_dresskit = (x, z, -y)_blender): the GarmentCode mean body (default
DATA/bodies/gc_mean_all.obj: metres, Y up, feet at y = 0, head top at y = 1.72, 47,500 triangles;
DATA is the environment variable DRESSKIT_DATA_DIR if set, else ../shared/data beside the
repository, i.e. <repo>/../shared/data, as for dresskit's tests; fabrics from
DATA/fabrics/fabrics.json), read here line by line ('v' and 'f', polygons fanned into triangles) so that
vertex order and axes are exact, as a collision object with Blender's default collision settings;
a horizontal square grid (default 0.8 m, 60x60 vertices) centred at dresskit (0, 1.87, 0.04),
15 cm above the head top, of total mass areal density x area (density from fabrics.json, default
camel-ponte-roma 0.284 kg/m^2, so 0.18176 kg, 5.049e-5 kg per vertex); the cloth modifier with
Blender's default settings except the vertex mass; frames 1..49 (2 s at 24 fps) or --seconds.
Steps the frames one by one and measures wall-clock and process-CPU seconds per simulated frame
(frames 2..end; the metrics are not timed), structural strain (grid edges) against the flat grid
every frame, and at the last frame and every 6th frame the cloth vertices inside the body and the
deepest one. The inside test does not use Blender's collision: a BVH tree of the body; a vertex in
the body's bounding box is inside when at least 2 of 3 rays in fixed generic directions cross the
body an odd number of times (hits counted by repeated ray casts, each restarted 1e-6 m past the
last hit); its depth is its distance to the nearest body point. At the last frame it also counts
the cloth's self-intersections (edge-triangle pairs that do not share a vertex, among pairs of
overlapping triangles).

With --check OBJ it simulates nothing: it reads a cloth written by dresskit (dresskit's Y-up axes,
metres, 'v' lines then triangular 'f' lines; vertex (i, j) of the grid is index j*N + i with
N = --resolution, the order of the rest grid built here) and takes the same end-of-run measures
with the same independent checks: vertices inside the body deeper than 2 mm and the deepest,
self-intersections (triangles from the OBJ's faces), max and mean structural strain over the grid's
axis-aligned edges (rest length size/(N-1); every such edge must be an edge of the OBJ's faces),
mean drop (--center's y minus the final mean y) and lowest y.

usage: blender -b --factory-startup --threads 1 -P bench/blender_cloth_on_body.py -- \
           [--body OBJ] [--body-units M] [--fabric NAME] [--size M] [--resolution N] \
           [--center X Y Z] [--seconds S] [--quality N] [--self-collision] [--air-damping A] \
           [--gravity GZ] --out DIR [--csv FILE --label NAME]
       blender -b --factory-startup -P bench/blender_cloth_on_body.py -- --check CLOTH.obj \
           [--body OBJ] [--body-units M] [--size M] [--resolution N] [--center X Y Z] \
           [--out DIR] [--csv FILE --label NAME]
Writes DIR/blender_report.json and DIR/final.obj (final cloth in dresskit's Y-up axes, 1-based
faces). Pin it, e.g. `taskset -c 1 blender ...`. With --csv, appends the run to FILE as one row
(scripts/run_blender_body runs the default and the matched settings). With --check it prints one
`CHECK ...` line, writes DIR/check_report.json if --out is given, and with --csv appends a row in
the same columns, leaving empty what one final state cannot tell: the per-frame times (filled by
the caller), simulated_seconds, frames and the over-frames maxima (scripts/bench_head_drop checks
dresskit's result this way). Needs Debian's blender
package (3.4.1 on bookworm); not used by the build or the tests.

Caveats: as in bench/blender_cloth_on_sphere.py, Blender's air drag (-0.01 * air_damping * v per
vertex) does not scale with mass, so with Blender's default air_damping 1.0 and 5e-5 kg per vertex
the cloth barely falls in 2 s and may never reach the head; and Blender applies 0.001 * gravity per
frame^2, i.e. 0.576 g at 24 fps. Options matching dresskit's defaults (air_damping 0.1 1/s,
g = 9.81 m/s^2) for the default cloth (vertex mass m = 0.284 * 0.64 / 3600 kg):
    --air-damping 0.000021 --gravity -17.03    (0.1 * m / (0.01 * 24);  -9.81 / (0.001 * 24^2))
Other fabrics, sizes or resolutions change m and so the matched air damping. Strain is measured on
the grid edges only (no shear). The inside test assumes a closed body (gc_mean_all is: every edge
has two triangles); a cloth vertex resting on the body within Blender's collision distance
(0.015 m by default) is outside, so "inside deeper than 2 mm" counts real penetrations. With
--self-collision, Blender's default self distance (0.015 m) exceeds the default grid's spacing
(0.8 / 59 = 0.0136 m), so neighbours beyond the springs repel from the first frame.
"""
import argparse
import json
import os
import sys
import time

import bpy
import numpy as np
from mathutils import Vector
from mathutils.bvhtree import BVHTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_common import (add_cloth, add_grid, grid_fields, lengths, mesh_arrays, new_scene,  # noqa: E402
                            print_result, quads_to_tris, run_fields, run_frames, self_intersection_fields,
                            self_intersections, settings_fields, settings_text, strain, write_obj)

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.environ.get("DRESSKIT_DATA_DIR") or os.path.normpath(os.path.join(REPO, "..", "shared", "data"))
FPS = 24
FRAME_START = 1
INSIDE_EVERY = 6            # inside test every 6th frame (and the last)
INSIDE_DEPTH = 0.002        # m, "inside" for the counts
RAY_EPS = 1e-6              # m, step past a hit
# Fixed generic (not axis-aligned, not symmetric) directions for the parity rays, dresskit axes.
RAY_DIRS = ((0.5377, 0.8339, -0.1243), (-0.7071, 0.1492, 0.6912), (0.2315, -0.6129, -0.7555))


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_cloth_on_body.py")
    p.add_argument("--body", default=os.path.join(DATA, "bodies", "gc_mean_all.obj"))
    p.add_argument("--body-units", type=float, default=1.0, help="metres per OBJ unit (default 1)")
    p.add_argument("--fabric", default="camel-ponte-roma", help="name in fabrics.json")
    p.add_argument("--fabrics", default=os.path.join(DATA, "fabrics", "fabrics.json"))
    p.add_argument("--size", type=float, default=0.8, help="cloth side in m")
    p.add_argument("--resolution", type=int, default=60, help="cloth vertices per side")
    p.add_argument("--center", type=float, nargs=3, default=(0.0, 1.87, 0.04),
                   help="cloth centre in dresskit axes (Y up), m")
    p.add_argument("--seconds", type=float, default=2.0, help="simulated time (default 2 s = 48 frames)")
    p.add_argument("--self-collision", action="store_true")
    p.add_argument("--quality", type=int, default=None, help="cloth steps per frame (Blender default 5)")
    p.add_argument("--air-damping", type=float, default=None, help="Blender air viscosity (default 1.0)")
    p.add_argument("--gravity", type=float, default=None, help="scene gravity z in m/s^2 (default -9.81)")
    p.add_argument("--check", default=None, metavar="OBJ",
                   help="measure this cloth OBJ written by dresskit instead of simulating")
    p.add_argument("--out", default=None, help="output directory (required unless --check)")
    p.add_argument("--csv", default=None, help="append the run as one row to this CSV")
    p.add_argument("--label", default="Blender", help="the row's setting name (with --csv)")
    args = p.parse_args(argv)
    if args.out is None and args.check is None:
        p.error("--out is required (unless --check)")
    if args.resolution < 2:
        p.error("--resolution must be at least 2")
    return args


def to_blender(p):
    """dresskit (x, y, z), Y up -> Blender (x, -z, y), Z up."""
    p = np.asarray(p, dtype=float)
    return np.stack([p[..., 0], -p[..., 2], p[..., 1]], axis=-1)


def to_dresskit(p):
    """Blender (x, y, z) -> dresskit (x, z, -y)."""
    p = np.asarray(p, dtype=float)
    return np.stack([p[..., 0], p[..., 2], -p[..., 1]], axis=-1)


def read_obj(path, units):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            s = line.split()
            if not s:
                continue
            if s[0] == "v":
                verts.append([float(x) for x in s[1:4]])
            elif s[0] == "f":
                idx = []
                for tok in s[1:]:
                    i = int(tok.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return np.array(verts) * units, np.array(tris, dtype=np.int64)


def fabric_density(path, name):
    with open(path) as f:
        data = json.load(f)
    for fab in data["fabrics"]:
        if fab["name"] == name:
            return float(fab["areal_density_kg_per_m2"])
    raise SystemExit("fabric %r not in %s" % (name, path))


def add_body(verts_dk, tris):
    vb = to_blender(verts_dk)
    me = bpy.data.meshes.new("Body")
    me.from_pydata([tuple(v) for v in vb], [], [tuple(int(i) for i in t) for t in tris])
    me.update()
    ob = bpy.data.objects.new("Body", me)
    bpy.context.scene.collection.objects.link(ob)
    assert len(me.vertices) == len(vb) and len(me.polygons) == len(tris)
    ob.modifiers.new("Collision", "COLLISION")
    return ob, vb


def crossings(tree, origin, direction):
    n, o = 0, Vector(origin)
    for _ in range(10000):
        loc, _, _, _ = tree.ray_cast(o, direction)
        if loc is None:
            return n
        n += 1
        o = loc + direction * RAY_EPS
    raise RuntimeError("ray from %s never left the body" % (tuple(origin),))


def inside_depths(tree, lo, hi, co):
    """Depths (m) of the cloth vertices inside the body (Blender coordinates)."""
    dirs = [Vector(tuple(to_blender(d))).normalized() for d in RAY_DIRS]
    cand = np.nonzero(np.all((co >= lo) & (co <= hi), axis=1))[0]
    depths = []
    for i in cand:
        p = tuple(co[i])
        odd = sum(crossings(tree, p, d) % 2 for d in dirs)
        if odd >= 2:
            depths.append(tree.find_nearest(Vector(p))[3])
    return np.array(depths), len(cand)


CSV_HEADER = ("setting,blender_settings,cpu_seconds_per_frame,wall_seconds_per_frame,"
              "simulated_seconds,frames,final_max_strain,max_strain_all_frames,inside_2mm_end,"
              "deepest_inside_mm_end,max_inside_2mm_over_frames,self_crossings_end,"
              "mean_drop_m,lowest_y_m\n")


def csv_quote(s):
    return '"%s"' % str(s).replace('"', '""')


def append_csv(path, row):
    new_file = not os.path.exists(path) or os.path.getsize(path) == 0
    with open(path, "a") as f:
        if new_file:
            f.write(CSV_HEADER)
        f.write(row)


def grid_edges(n):
    """Axis-aligned edges of an n x n grid, vertex (i, j) = j*n + i."""
    idx = np.arange(n * n).reshape(n, n)            # [j, i]
    along_i = np.stack([idx[:, :-1].ravel(), idx[:, 1:].ravel()], axis=1)
    along_j = np.stack([idx[:-1, :].ravel(), idx[1:, :].ravel()], axis=1)
    return np.concatenate([along_i, along_j])


def check(args):
    """Measures a dresskit cloth OBJ (end of run) with the same independent checks as a simulation."""
    t0 = time.perf_counter()
    body_dk, body_tris = read_obj(args.body, args.body_units)
    body_b = to_blender(body_dk)
    body_tree = BVHTree.FromPolygons([tuple(v) for v in body_b], body_tris.tolist(), all_triangles=True)
    lo, hi = body_b.min(axis=0), body_b.max(axis=0)

    cloth_dk, tris = read_obj(args.check, 1.0)
    n_side = args.resolution
    n = n_side * n_side
    if len(cloth_dk) != n:
        raise SystemExit("%s: %d vertices, expected %d x %d = %d (--resolution)"
                         % (args.check, len(cloth_dk), n_side, n_side, n))
    if len(tris) == 0:
        raise SystemExit("%s: no faces" % args.check)
    if tris.min() < 0 or tris.max() >= n:
        raise SystemExit("%s: a face index is out of range" % args.check)
    if not np.all(np.isfinite(cloth_dk)):
        raise SystemExit("%s: non-finite vertex coordinates" % args.check)
    edges = grid_edges(n_side)
    face_edges = set()
    for t in tris:
        for k in range(3):
            a, b = int(t[k]), int(t[(k + 1) % 3])
            face_edges.add((min(a, b), max(a, b)))
    missing = sum((int(a), int(b)) not in face_edges for a, b in edges)
    if missing:
        raise SystemExit("%s: %d of the %d grid edges (vertex (i, j) = j*%d + i) are not edges of its "
                         "faces: wrong --resolution or vertex order" % (args.check, missing, len(edges), n_side))

    co = to_blender(cloth_dk)   # same axes, rays and body tree as a simulation's checks
    rest_len = args.size / (n_side - 1)
    e_max, e_mean, e_min = strain(co, edges, rest_len)
    depths, n_cand = inside_depths(body_tree, lo, hi, co)
    tri_pairs, edge_tri = self_intersections(co, tris)
    start_y = float(args.center[1])
    drop = start_y - float(cloth_dk[:, 1].mean())
    lowest = float(cloth_dk[:, 1].min())
    inside_2mm = int((depths > INSIDE_DEPTH).sum())
    deepest = float(depths.max()) if len(depths) else 0.0
    report = {
        "check": os.path.abspath(args.check),
        "blender_version": bpy.app.version_string,
        "body": {"path": os.path.abspath(args.body), "units_m": args.body_units,
                 "vertices": len(body_b), "triangles": len(body_tris)},
        "cloth_size_m": args.size, "resolution": n_side, "cloth_center_dresskit": list(args.center),
        "vertices": n, "triangles": len(tris), "grid_edges": len(edges), "rest_edge_m": rest_len,
        "final_structural_strain_max": e_max, "final_structural_strain_mean": e_mean,
        "final_structural_strain_min": e_min,
        "final_vertices_in_body_bbox": n_cand, "final_vertices_inside_body": int(len(depths)),
        "final_vertices_inside_body_2mm": inside_2mm, "final_deepest_inside_m": deepest,
        "start_mean_y": start_y, "final_mean_y": float(cloth_dk[:, 1].mean()),
        "final_mean_drop": drop, "final_lowest_y": lowest,
        "final_self_intersecting_triangle_pairs": tri_pairs,
        "final_self_intersecting_edge_triangle_pairs": edge_tri,
        "check_wall_s": time.perf_counter() - t0,
    }
    if args.out:
        os.makedirs(args.out, exist_ok=True)
        with open(os.path.join(args.out, "check_report.json"), "w") as f:
            json.dump(report, f, indent=1)
    if args.csv:
        append_csv(args.csv, '%s,%s,,,,,%.4f,,%d,%.1f,,%d,%.3f,%.3f\n' % (
            csv_quote(args.label), csv_quote("check of %s" % os.path.abspath(args.check)),
            e_max, inside_2mm, 1e3 * deepest, edge_tri, drop, lowest))
    print("CHECK %s: final max strain %.4f (mean %.4f), inside >2 mm %d (inside %d), deepest %.1f mm, "
          "self crossings %d, mean drop %.3f m, lowest y %.3f m" % (
              args.check, e_max, e_mean, inside_2mm, len(depths), 1e3 * deepest, edge_tri, drop, lowest))


def main():
    args = parse_args()
    if args.check:
        check(args)
        return
    os.makedirs(args.out, exist_ok=True)
    load_start = os.getloadavg()
    frame_end = FRAME_START + int(round(args.seconds * FPS))
    scene = new_scene(FPS, FRAME_START, frame_end)

    body_dk, body_tris = read_obj(args.body, args.body_units)
    body, body_b = add_body(body_dk, body_tris)
    body_tree = BVHTree.FromPolygons([tuple(v) for v in body_b], body_tris.tolist(), all_triangles=True)
    lo, hi = body_b.min(axis=0), body_b.max(axis=0)

    n_side = args.resolution
    center_b = to_blender(args.center)
    cloth, subdiv = add_grid(n_side, args.size, center_b)
    density = fabric_density(args.fabrics, args.fabric)
    total_mass = density * args.size * args.size
    n = len(cloth.data.vertices)
    mod = add_cloth(cloth, scene, total_mass / n, FRAME_START, frame_end, quality=args.quality,
                    air_damping=args.air_damping, gravity=args.gravity, self_collision=args.self_collision)
    cs, cc = mod.settings, mod.collision_settings

    rest, edges, quads = mesh_arrays(cloth.data)
    rest_e = lengths(rest, edges)

    def measure(f, co, wall_s, cpu_s):
        e_max, e_mean, e_min = strain(co, edges, rest_e)
        fm = {"frame": f, "wall_s": wall_s, "cpu_s": cpu_s, "structural_strain_max": e_max,
              "structural_strain_mean": e_mean, "structural_strain_min": e_min,
              "mean_y": float(co[:, 2].mean()), "lowest_y": float(co[:, 2].min())}
        if (f - FRAME_START) % INSIDE_EVERY == 0 or f == frame_end:
            depths, n_cand = inside_depths(body_tree, lo, hi, co)
            fm.update(in_bbox=n_cand, inside=int(len(depths)),
                      inside_2mm=int((depths > INSIDE_DEPTH).sum()),
                      deepest_inside=float(depths.max()) if len(depths) else 0.0)
        return fm

    per_frame, co, timing = run_frames(scene, cloth, FRAME_START, frame_end, measure)
    n_sim = frame_end - FRAME_START
    final = per_frame[-1]
    start_y = per_frame[0]["mean_y"]
    drop = float(start_y - co[:, 2].mean())
    isect = self_intersection_fields(co, quads_to_tris(quads))
    edge_tri = isect["final_self_intersecting_edge_triangle_pairs"]
    write_obj(os.path.join(args.out, "final.obj"), co, quads)
    tested = [p for p in per_frame if "inside" in p]

    report = {
        **run_fields(scene, load_start),
        "body": {"path": os.path.abspath(args.body), "units_m": args.body_units,
                 "vertices": len(body_b), "triangles": len(body_tris),
                 "bbox_min_dresskit": to_dresskit(lo).tolist(), "bbox_max_dresskit": to_dresskit(hi).tolist()},
        "fabric": args.fabric, "areal_density_kg_per_m2": density,
        "cloth_size_m": args.size, "cloth_center_dresskit": list(args.center),
        "quality": cs.quality, "self_collision": cc.use_self_collision,
        "frames": [FRAME_START, frame_end], "simulated_frames": n_sim, "simulated_seconds": n_sim / FPS,
        "fps": FPS,
        **grid_fields(cs, n, edges, quads, subdiv),
        **timing,
        "final_structural_strain_max": final["structural_strain_max"],
        "final_structural_strain_mean": final["structural_strain_mean"],
        "final_structural_strain_min": final["structural_strain_min"],
        "max_structural_strain_all_frames": max(p["structural_strain_max"] for p in per_frame),
        "final_vertices_inside_body": final["inside"],
        "final_vertices_inside_body_2mm": final["inside_2mm"],
        "final_deepest_inside_m": final["deepest_inside"],
        "max_inside_2mm_over_tested_frames": max(p["inside_2mm"] for p in tested),
        "deepest_inside_over_tested_frames_m": max(p["deepest_inside"] for p in tested),
        "inside_tested_frames": [p["frame"] for p in tested],
        "start_mean_y": start_y, "final_mean_drop": drop, "final_lowest_y": final["lowest_y"],
        **isect,
        **settings_fields(mod, body),
        "gravity": list(scene.gravity),
        "per_frame": per_frame,
    }
    with open(os.path.join(args.out, "blender_report.json"), "w") as f:
        json.dump(report, f, indent=1)
    if args.csv:
        settings = "%s, %s" % (args.fabric, settings_text(mod, args.quality, args.air_damping, args.gravity))
        append_csv(args.csv, '%s,%s,%.4f,%.4f,%.3f,%d,%.4f,%.4f,%d,%.1f,%d,%d,%.3f,%.3f\n' % (
            csv_quote(args.label), csv_quote(settings), report["seconds_per_frame_cpu"],
            report["seconds_per_frame_wall"], n_sim / FPS, n_sim, report["final_structural_strain_max"],
            report["max_structural_strain_all_frames"], report["final_vertices_inside_body_2mm"],
            1e3 * report["final_deepest_inside_m"], report["max_inside_2mm_over_tested_frames"],
            edge_tri, drop, report["final_lowest_y"]))
    print_result(args.out, report, "final max strain %.4f (all frames %.4f), "
                 "inside >2 mm %d (max over frames %d), deepest %.1f mm, self crossings %d, "
                 "mean drop %.3f m, lowest y %.3f m", (
                     report["final_structural_strain_max"], report["max_structural_strain_all_frames"],
                     report["final_vertices_inside_body_2mm"], report["max_inside_2mm_over_tested_frames"],
                     1e3 * report["final_deepest_inside_m"], edge_tri, drop, report["final_lowest_y"]))


if __name__ == "__main__":
    main()
