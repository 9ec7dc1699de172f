"""Blender's built-in cloth on examples/cloth_on_sphere.json, as an independent baseline.

Builds the scene from scratch (Blender is Z-up, so the cloth is at z = 0.5, the sphere at the origin
and the floor at z = -0.5): a 1 m grid of 64x64 vertices, total mass 0.3 kg; a UV sphere of radius
0.3 (64x32, smooth) and a floor plane, both collision objects; the cloth modifier with Blender's
default settings except vertex mass = 0.3 / 4096 kg; frames 1..49 (2 s at 24 fps). Steps the frames
one by one and measures wall-clock and process-CPU seconds per simulated frame (frames 2..49),
structural strain (grid edges) and shear strain (quad diagonals) against the flat grid, the closest
distance of any vertex to the analytic sphere (|p| - 0.3, negative = inside), the lowest point
against the floor, and at the last frame the cloth's self-intersections (triangle pairs, and
edge-triangle pairs, that do not share a vertex).

usage: blender -b --factory-startup --threads 1 -P bench/blender_cloth_on_sphere.py -- \
           [--self-collision [--self-distance D]] [--quality N] [--vertex-mass KG] [--air-damping A] \
           [--gravity GZ] --out DIR [--csv FILE --label NAME]
Writes DIR/blender_report.json and DIR/final.obj (final cloth in dresskit's Y-up axes:
(x, y, z)_dresskit = (x, z, -y)_blender, 1-based faces). Pin it, e.g. `taskset -c 1 blender ...`.
With --csv, appends the run to FILE as a row of docs/data/blender_cloth_on_sphere.csv (made by
scripts/run_blender_sphere, which runs every setting of that table); crossings_end counts
edge-triangle pairs.
Needs Debian's blender package (3.4.1 on bookworm); not used by the build or the tests.

Caveat: Blender's air drag (-0.01 * air_damping * v per vertex) does not scale with mass, so with
Blender's default air_damping 1.0 and 0.3/4096 kg per vertex the cloth barely falls (about 3 mm in
2 s) and never reaches the sphere. Blender also applies 0.001 * gravity per frame^2, i.e. 0.576 g at
24 fps. Options matching dresskit's scene (air_damping 0.2 1/s, g = 9.81 m/s^2):
    --air-damping 0.000061 --gravity -17.03    (0.2 * m / (0.01 * 24);  -9.81 / (0.001 * 24^2))
Even then the light cloth sinks far slower than free fall until it touches the sphere (0.12 m in the
first 1/3 s instead of 0.55 m): Blender's solver damps it at this mass. With self-collision on, the
default self distance 0.015 m is about one edge (1/63 m) and the cloth blows up before it reaches
the sphere; --self-distance sets it.
"""
import argparse
import json
import os
import sys

import bpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_common import (add_cloth, add_grid, grid_fields, lengths, mesh_arrays,  # noqa: E402
                            new_scene, print_result, quads_to_tris, run_fields, run_frames,
                            self_intersection_fields, settings_fields, settings_text, strain, write_obj)

GRID_N = 64                 # vertices per side
GRID_SIZE = 1.0             # m
CLOTH_Z = 0.5               # m, dresskit's y = 0.5
TOTAL_MASS = 0.3            # kg
SPHERE_R = 0.3              # m
FLOOR_Z = -0.5              # m
FPS = 24
FRAME_START, FRAME_END = 1, 49   # 48 simulated frames = 2 s


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_cloth_on_sphere.py")
    p.add_argument("--self-collision", action="store_true")
    p.add_argument("--self-distance", type=float, default=None,
                   help="self-collision distance in m (Blender default 0.015)")
    p.add_argument("--quality", type=int, default=None, help="cloth steps per frame (Blender default 5)")
    p.add_argument("--vertex-mass", type=float, default=TOTAL_MASS / (GRID_N * GRID_N),
                   help="kg per vertex (Blender's mass is per vertex; its own default is 0.3)")
    p.add_argument("--air-damping", type=float, default=None, help="Blender air viscosity (default 1.0)")
    p.add_argument("--gravity", type=float, default=None, help="scene gravity z in m/s^2 (default -9.81)")
    p.add_argument("--out", required=True)
    p.add_argument("--csv", default=None,
                   help="append the run as a row of docs/data/blender_cloth_on_sphere.csv's format")
    p.add_argument("--label", default="Blender", help="the row's setting name (with --csv)")
    return p.parse_args(argv)


def add_colliders():
    bpy.ops.mesh.primitive_uv_sphere_add(segments=64, ring_count=32, radius=SPHERE_R, location=(0, 0, 0))
    sphere = bpy.context.active_object
    sphere.name = "Sphere"
    bpy.ops.object.shade_smooth()
    sphere.modifiers.new("Collision", "COLLISION")
    bpy.ops.mesh.primitive_plane_add(size=4.0, location=(0, 0, FLOOR_Z))
    floor = bpy.context.active_object
    floor.name = "Floor"
    floor.modifiers.new("Collision", "COLLISION")
    return sphere, floor


def frame_metrics(co, edges, rest_e, diags, rest_d):
    r = np.linalg.norm(co, axis=1)
    e_max, e_mean, e_min = strain(co, edges, rest_e)
    d_max, d_mean, d_min = strain(co, diags, rest_d)
    return {"structural_strain_max": e_max, "structural_strain_mean": e_mean, "structural_strain_min": e_min,
            "shear_strain_max": d_max, "shear_strain_mean": d_mean, "shear_strain_min": d_min,
            "closest_distance_to_sphere": float(r.min() - SPHERE_R),
            "vertices_inside_sphere": int((r < SPHERE_R).sum()),
            "min_z": float(co[:, 2].min()), "min_height_above_floor": float(co[:, 2].min() - FLOOR_Z)}


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    load_start = os.getloadavg()
    scene = new_scene(FPS, FRAME_START, FRAME_END)

    cloth, subdiv = add_grid(GRID_N, GRID_SIZE, (0.0, 0.0, CLOTH_Z))
    sphere, floor = add_colliders()
    n = len(cloth.data.vertices)
    mod = add_cloth(cloth, scene, args.vertex_mass, FRAME_START, FRAME_END, quality=args.quality,
                    air_damping=args.air_damping, gravity=args.gravity, self_collision=args.self_collision,
                    self_distance=args.self_distance)
    cs, cc = mod.settings, mod.collision_settings

    rest, edges, quads = mesh_arrays(cloth.data)
    diags = np.concatenate([quads[:, [0, 2]], quads[:, [1, 3]]])
    rest_e = lengths(rest, edges)
    rest_d = lengths(rest, diags)

    def measure(f, co, wall_s, cpu_s):
        fm = frame_metrics(co, edges, rest_e, diags, rest_d)
        fm.update(frame=f, wall_s=wall_s, cpu_s=cpu_s)
        return fm

    per_frame, co, timing = run_frames(scene, cloth, FRAME_START, FRAME_END, measure)
    n_sim = FRAME_END - FRAME_START
    drop = float(CLOTH_Z - co[:, 2].mean())
    isect = self_intersection_fields(co, quads_to_tris(quads), adjacent=False)
    tri_pairs = isect["final_self_intersecting_triangle_pairs"]
    edge_tri = isect["final_self_intersecting_edge_triangle_pairs"]
    write_obj(os.path.join(args.out, "final.obj"), co, quads)
    final = per_frame[-1]
    late = [p for p in per_frame if p["frame"] > FRAME_END - FPS // 2]

    def late_mean(key):
        return sum(p[key] for p in late) / len(late)

    report = {
        **run_fields(scene, load_start),
        "quality": cs.quality, "self_collision": cc.use_self_collision,
        "frames": [FRAME_START, FRAME_END], "simulated_frames": n_sim, "fps": FPS,
        **grid_fields(cs, n, edges, quads, subdiv),
        **timing,
        "final_structural_strain_max": final["structural_strain_max"],
        "final_structural_strain_mean": final["structural_strain_mean"],
        "final_structural_strain_min": final["structural_strain_min"],
        "final_shear_strain_max": final["shear_strain_max"],
        "final_shear_strain_mean": final["shear_strain_mean"],
        "max_structural_strain_all_frames": max(p["structural_strain_max"] for p in per_frame),
        "max_shear_strain_all_frames": max(p["shear_strain_max"] for p in per_frame),
        "max_strain_all_frames": max(max(p["structural_strain_max"], p["shear_strain_max"])
                                     for p in per_frame),
        # The last 0.5 s (frames 38..49, 12 frames): the cloth still flaps, so one frame's largest
        # strain is a sample of a moving quantity; the mean and the worst of the per-frame largest
        # strains over these frames are steadier (dresskit's bench_cloth_sphere reports the same).
        "late_mean_structural_strain_max": late_mean("structural_strain_max"),
        "late_mean_shear_strain_max": late_mean("shear_strain_max"),
        "late_worst_structural_strain_max": max(p["structural_strain_max"] for p in late),
        "late_worst_shear_strain_max": max(p["shear_strain_max"] for p in late),
        "final_closest_distance_to_sphere": final["closest_distance_to_sphere"],
        "closest_distance_to_sphere_all_frames": min(p["closest_distance_to_sphere"] for p in per_frame),
        "final_vertices_inside_sphere": final["vertices_inside_sphere"],
        "max_vertices_inside_sphere_all_frames": max(p["vertices_inside_sphere"] for p in per_frame),
        "final_mean_drop": drop, "final_min_z": final["min_z"],
        "final_min_height_above_floor": final["min_height_above_floor"],
        "min_height_above_floor_all_frames": min(p["min_height_above_floor"] for p in per_frame),
        **isect,
        **settings_fields(mod, sphere),
        "sphere_mesh": {"segments": 64, "rings": 32, "vertices": len(sphere.data.vertices)},
        "gravity": list(scene.gravity),
        "per_frame": per_frame,
    }
    with open(os.path.join(args.out, "blender_report.json"), "w") as f:
        json.dump(report, f, indent=1)
    if args.csv:
        settings = settings_text(mod, air_damping=args.air_damping, gravity=args.gravity)
        new_file = not os.path.exists(args.csv)
        with open(args.csv, "a") as f:
            if new_file:
                f.write("fabric,setting,blender_settings,cpu_seconds_per_frame,wall_seconds_per_frame,"
                        "max_strain,mean_strain,max_shear_strain,max_strain_all_frames,closest_mm,"
                        "mean_drop_m,crossings_end,late_mean_max_strain,late_mean_max_shear_strain,"
                        "late_worst_max_strain,late_worst_max_shear_strain\n")
            f.write('Blender default,"%s","%s",%.4f,%.4f,%.4f,%.5f,%.4f,%.4f,%.1f,%.3f,%d,%.4f,%.4f,%.4f,%.4f\n' % (
                args.label, settings, report["seconds_per_frame_cpu"], report["seconds_per_frame_wall"],
                report["final_structural_strain_max"], report["final_structural_strain_mean"],
                report["final_shear_strain_max"], report["max_strain_all_frames"],
                1e3 * report["final_closest_distance_to_sphere"], drop, edge_tri,
                report["late_mean_structural_strain_max"], report["late_mean_shear_strain_max"],
                report["late_worst_structural_strain_max"], report["late_worst_shear_strain_max"]))
    print_result(args.out, report, "final max strain %.4f (shear %.4f), "
                 "last 0.5 s mean of the per-frame max %.4f (shear %.4f), "
                 "closest to sphere %.5f m, inside %d, self-isect tri pairs %d, mean drop %.3f m", (
                     report["final_structural_strain_max"], report["final_shear_strain_max"],
                     report["late_mean_structural_strain_max"], report["late_mean_shear_strain_max"],
                     report["final_closest_distance_to_sphere"], report["final_vertices_inside_sphere"],
                     tri_pairs, drop))


if __name__ == "__main__":
    main()
