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
import time

import bpy
import numpy as np
from mathutils.bvhtree import BVHTree

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


def cli_threads():
    argv = sys.argv[:sys.argv.index("--")] if "--" in sys.argv else sys.argv
    for i, a in enumerate(argv[:-1]):
        if a in ("--threads", "-t"):
            return int(argv[i + 1])
    return None


def clear_scene():
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for me in list(bpy.data.meshes):
        bpy.data.meshes.remove(me)


def add_grid():
    # Blender 3.x: x_subdivisions is the number of vertices per side minus one (older versions: the
    # number of vertices). Try both and assert the vertex count.
    for subdiv in (GRID_N - 1, GRID_N):
        bpy.ops.mesh.primitive_grid_add(x_subdivisions=subdiv, y_subdivisions=subdiv, size=GRID_SIZE,
                                        location=(0.0, 0.0, CLOTH_Z))
        ob = bpy.context.active_object
        if len(ob.data.vertices) == GRID_N * GRID_N:
            break
        bpy.data.objects.remove(ob, do_unlink=True)
    else:
        raise RuntimeError("could not make a %dx%d grid" % (GRID_N, GRID_N))
    me = ob.data
    assert len(me.vertices) == GRID_N * GRID_N, len(me.vertices)
    assert len(me.edges) == 2 * GRID_N * (GRID_N - 1), len(me.edges)
    assert len(me.polygons) == (GRID_N - 1) ** 2 and all(len(p.vertices) == 4 for p in me.polygons)
    assert abs(ob.dimensions.x - GRID_SIZE) < 1e-6 and abs(ob.dimensions.y - GRID_SIZE) < 1e-6
    ob.name = "Cloth"
    return ob, subdiv


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


def world_coords(ob, depsgraph):
    ob_eval = ob.evaluated_get(depsgraph)
    me = ob_eval.to_mesh()
    co = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", co)
    ob_eval.to_mesh_clear()
    co = co.reshape(-1, 3)
    m = np.array(ob.matrix_world)
    return co @ m[:3, :3].T + m[:3, 3]


def strain(co, pairs, rest):
    s = np.linalg.norm(co[pairs[:, 0]] - co[pairs[:, 1]], axis=1) / rest - 1.0
    return float(s.max()), float(s.mean()), float(s.min())


def frame_metrics(co, edges, rest_e, diags, rest_d):
    r = np.linalg.norm(co, axis=1)
    e_max, e_mean, e_min = strain(co, edges, rest_e)
    d_max, d_mean, d_min = strain(co, diags, rest_d)
    return {"structural_strain_max": e_max, "structural_strain_mean": e_mean, "structural_strain_min": e_min,
            "shear_strain_max": d_max, "shear_strain_mean": d_mean, "shear_strain_min": d_min,
            "closest_distance_to_sphere": float(r.min() - SPHERE_R),
            "vertices_inside_sphere": int((r < SPHERE_R).sum()),
            "min_z": float(co[:, 2].min()), "min_height_above_floor": float(co[:, 2].min() - FLOOR_Z)}


def seg_tri(p, q, a, b, c, eps=1e-12):
    """Does segment pq cross triangle abc (Moller-Trumbore, parameter in [0, 1])?"""
    d = q - p
    e1, e2 = b - a, c - a
    h = np.cross(d, e2)
    det = e1.dot(h)
    if abs(det) < eps:
        return False
    f = 1.0 / det
    s = p - a
    u = f * s.dot(h)
    if u < 0.0 or u > 1.0:
        return False
    qv = np.cross(s, e1)
    v = f * d.dot(qv)
    if v < 0.0 or u + v > 1.0:
        return False
    t = f * e2.dot(qv)
    return 0.0 <= t <= 1.0


def self_intersections(co, quads):
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    tree = BVHTree.FromPolygons([tuple(v) for v in co], tris.tolist(), all_triangles=True, epsilon=0.0)
    tri_pairs = set()
    for i, j in tree.overlap(tree):
        if i == j or set(tris[i]) & set(tris[j]):
            continue
        tri_pairs.add((min(i, j), max(i, j)))
    edge_tri = set()
    for i, j in tri_pairs:
        for a, b in ((i, j), (j, i)):
            ta, tb = tris[a], tris[b]
            for k in range(3):
                e = tuple(sorted((int(ta[k]), int(ta[(k + 1) % 3]))))
                if seg_tri(co[e[0]], co[e[1]], co[tb[0]], co[tb[1]], co[tb[2]]):
                    edge_tri.add((e, int(b)))
    return len(tri_pairs), len(edge_tri)


def write_obj(path, co, quads):
    with open(path, "w") as f:
        f.write("# Blender %s cloth, final frame, dresskit axes (Y up)\n" % bpy.app.version_string)
        for x, y, z in co:
            f.write("v %.7f %.7f %.7f\n" % (x, z, -y))
        for q in quads:
            f.write("f %d %d %d %d\n" % tuple(int(v) + 1 for v in q))


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    load_start = os.getloadavg()
    clear_scene()
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = FPS, 1.0
    scene.frame_start, scene.frame_end = FRAME_START, FRAME_END

    cloth, subdiv = add_grid()
    sphere, floor = add_colliders()
    mod = cloth.modifiers.new("Cloth", "CLOTH")
    cs, cc = mod.settings, mod.collision_settings
    n = len(cloth.data.vertices)
    cs.mass = args.vertex_mass
    if args.air_damping is not None:
        cs.air_damping = args.air_damping
    if args.gravity is not None:
        scene.gravity = (0.0, 0.0, args.gravity)
    if args.quality is not None:
        cs.quality = args.quality
    cc.use_self_collision = args.self_collision
    if args.self_distance is not None:
        cc.self_distance_min = args.self_distance
    mod.point_cache.frame_start, mod.point_cache.frame_end = FRAME_START, FRAME_END

    me = cloth.data
    rest = np.empty(n * 3)
    me.vertices.foreach_get("co", rest)
    rest = rest.reshape(-1, 3)
    edges = np.empty(len(me.edges) * 2, dtype=np.int64)
    me.edges.foreach_get("vertices", edges)
    edges = edges.reshape(-1, 2)
    quads = np.empty(len(me.polygons) * 4, dtype=np.int64)
    me.polygons.foreach_get("vertices", quads)
    quads = quads.reshape(-1, 4)
    diags = np.concatenate([quads[:, [0, 2]], quads[:, [1, 3]]])
    rest_e = np.linalg.norm(rest[edges[:, 0]] - rest[edges[:, 1]], axis=1)
    rest_d = np.linalg.norm(rest[diags[:, 0]] - rest[diags[:, 1]], axis=1)

    depsgraph = bpy.context.evaluated_depsgraph_get()
    per_frame = []
    sim_wall = sim_cpu = 0.0
    first_wall = first_cpu = 0.0
    metrics_wall = 0.0
    for f in range(FRAME_START, FRAME_END + 1):
        w0, c0 = time.perf_counter(), time.process_time()
        scene.frame_set(f)
        co = world_coords(cloth, depsgraph)   # forces the evaluated mesh, included in the timing
        dw, dc = time.perf_counter() - w0, time.process_time() - c0
        if f == FRAME_START:
            first_wall, first_cpu = dw, dc
        else:
            sim_wall += dw
            sim_cpu += dc
        m0 = time.perf_counter()
        fm = frame_metrics(co, edges, rest_e, diags, rest_d)
        fm.update(frame=f, wall_s=dw, cpu_s=dc)
        per_frame.append(fm)
        metrics_wall += time.perf_counter() - m0

    n_sim = FRAME_END - FRAME_START
    drop = float(CLOTH_Z - co[:, 2].mean())
    t0 = time.perf_counter()
    tri_pairs, edge_tri = self_intersections(co, quads)
    isect_wall = time.perf_counter() - t0
    write_obj(os.path.join(args.out, "final.obj"), co, quads)
    final = per_frame[-1]
    late = [p for p in per_frame if p["frame"] > FRAME_END - FPS // 2]

    def late_mean(key):
        return sum(p[key] for p in late) / len(late)

    sc = sphere.collision
    report = {
        "blender_version": bpy.app.version_string,
        "threads_cli": cli_threads(),
        "render_threads": scene.render.threads,   # what Blender's thread pool reports (honours --threads)
        "cpu_affinity": sorted(os.sched_getaffinity(0)),
        "loadavg_start": load_start, "loadavg_end": os.getloadavg(),
        "quality": cs.quality, "self_collision": cc.use_self_collision,
        "frames": [FRAME_START, FRAME_END], "simulated_frames": n_sim, "fps": FPS,
        "grid": {"vertices": n, "edges": len(edges), "quads": len(quads), "x_subdivisions_used": subdiv},
        "vertex_mass": cs.mass, "total_mass": cs.mass * n,
        "total_wall_s": sim_wall, "total_cpu_s": sim_cpu,
        "seconds_per_frame_wall": sim_wall / n_sim, "seconds_per_frame_cpu": sim_cpu / n_sim,
        "first_frame_wall_s": first_wall, "first_frame_cpu_s": first_cpu,
        "metrics_wall_s_untimed": metrics_wall,
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
        "final_self_intersecting_triangle_pairs": tri_pairs,
        "final_self_intersecting_edge_triangle_pairs": edge_tri,
        "self_intersection_check_wall_s": isect_wall,
        "cloth_settings": {k: getattr(cs, k) for k in (
            "quality", "mass", "air_damping", "tension_stiffness", "compression_stiffness",
            "shear_stiffness", "bending_stiffness", "tension_damping", "compression_damping",
            "shear_damping", "bending_damping", "bending_model", "time_scale", "use_internal_springs",
            "use_pressure", "use_dynamic_mesh", "use_sewing_springs")},
        "collision_settings": {k: getattr(cc, k) for k in (
            "use_collision", "collision_quality", "distance_min", "impulse_clamp", "use_self_collision",
            "self_distance_min", "self_friction", "self_impulse_clamp", "friction")},
        "collider_settings": {k: getattr(sc, k) for k in (
            "thickness_outer", "thickness_inner", "damping", "cloth_friction", "use_culling")},
        "sphere_mesh": {"segments": 64, "rings": 32, "vertices": len(sphere.data.vertices)},
        "gravity": list(scene.gravity),
        "per_frame": per_frame,
    }
    with open(os.path.join(args.out, "blender_report.json"), "w") as f:
        json.dump(report, f, indent=1)
    if args.csv:
        settings = "vertex mass %g kg" % cs.mass
        if args.air_damping is not None:
            settings += ", air damping %g" % cs.air_damping
        if args.gravity is not None:
            settings += ", gravity %g" % args.gravity
        if cc.use_self_collision:
            settings += ", self collision (distance %g)" % cc.self_distance_min
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
    print("RESULT %s: %.4f s/frame wall, %.4f s/frame cpu, final max strain %.4f (shear %.4f), "
          "last 0.5 s mean of the per-frame max %.4f (shear %.4f), "
          "closest to sphere %.5f m, inside %d, self-isect tri pairs %d, mean drop %.3f m" % (
              args.out, report["seconds_per_frame_wall"], report["seconds_per_frame_cpu"],
              report["final_structural_strain_max"], report["final_shear_strain_max"],
              report["late_mean_structural_strain_max"], report["late_mean_shear_strain_max"],
              report["final_closest_distance_to_sphere"], report["final_vertices_inside_sphere"],
              tri_pairs, drop))


if __name__ == "__main__":
    main()
