"""What bench/blender_cloth_on_sphere.py and bench/blender_cloth_on_body.py share: the scene, the cloth
grid and its modifier, the timed frame loop, the strain and self-intersection measures, the final OBJ
and the report's common fields. Runs inside Blender (imports bpy); the scripts put this folder on
sys.path before importing it.
"""
import os
import sys
import time

import bpy
import numpy as np
from mathutils.bvhtree import BVHTree

# Settings copied into the report as they are after the run.
CLOTH_SETTINGS = (
    "quality", "mass", "air_damping", "tension_stiffness", "compression_stiffness",
    "shear_stiffness", "bending_stiffness", "tension_damping", "compression_damping",
    "shear_damping", "bending_damping", "bending_model", "time_scale", "use_internal_springs",
    "use_pressure", "use_dynamic_mesh", "use_sewing_springs")
COLLISION_SETTINGS = (
    "use_collision", "collision_quality", "distance_min", "impulse_clamp", "use_self_collision",
    "self_distance_min", "self_friction", "self_impulse_clamp", "friction")
COLLIDER_SETTINGS = ("thickness_outer", "thickness_inner", "damping", "cloth_friction", "use_culling")


def cli_threads():
    """The value of Blender's own --threads (or -t) option, before "--"; None when not given."""
    argv = sys.argv[:sys.argv.index("--")] if "--" in sys.argv else sys.argv
    for i, a in enumerate(argv[:-1]):
        if a in ("--threads", "-t"):
            return int(argv[i + 1])
    return None


def clear_scene():
    """Removes every object and mesh of the startup scene."""
    for ob in list(bpy.data.objects):
        bpy.data.objects.remove(ob, do_unlink=True)
    for me in list(bpy.data.meshes):
        bpy.data.meshes.remove(me)


def new_scene(fps, frame_start, frame_end):
    """Clears the scene and sets its frame rate and frame range; returns the scene."""
    clear_scene()
    scene = bpy.context.scene
    scene.render.fps, scene.render.fps_base = fps, 1.0
    scene.frame_start, scene.frame_end = frame_start, frame_end
    return scene


def add_grid(n, size, location):
    """A square grid named "Cloth" of n x n vertices and side size (m) centred at location (Blender
    axes); returns the object and the x_subdivisions that made it."""
    # Blender 3.x: x_subdivisions is the number of vertices per side minus one (older versions: the
    # number of vertices). Try both and assert the vertex count.
    for subdiv in (n - 1, n):
        bpy.ops.mesh.primitive_grid_add(x_subdivisions=subdiv, y_subdivisions=subdiv, size=size,
                                        location=tuple(location))
        ob = bpy.context.active_object
        if len(ob.data.vertices) == n * n:
            break
        bpy.data.objects.remove(ob, do_unlink=True)
    else:
        raise RuntimeError("could not make a %dx%d grid" % (n, n))
    me = ob.data
    assert len(me.vertices) == n * n, len(me.vertices)
    assert len(me.edges) == 2 * n * (n - 1), len(me.edges)
    assert len(me.polygons) == (n - 1) ** 2 and all(len(p.vertices) == 4 for p in me.polygons)
    assert abs(ob.dimensions.x - size) < 1e-6 and abs(ob.dimensions.y - size) < 1e-6
    ob.name = "Cloth"
    return ob, subdiv


def add_cloth(cloth, scene, mass, frame_start, frame_end, quality=None, air_damping=None, gravity=None,
              self_collision=False, self_distance=None):
    """Adds the cloth modifier with Blender's defaults except the vertex mass (kg) and what is not
    None (gravity is the scene's z); returns the modifier."""
    mod = cloth.modifiers.new("Cloth", "CLOTH")
    cs, cc = mod.settings, mod.collision_settings
    cs.mass = mass
    if air_damping is not None:
        cs.air_damping = air_damping
    if gravity is not None:
        scene.gravity = (0.0, 0.0, gravity)
    if quality is not None:
        cs.quality = quality
    cc.use_self_collision = self_collision
    if self_distance is not None:
        cc.self_distance_min = self_distance
    mod.point_cache.frame_start, mod.point_cache.frame_end = frame_start, frame_end
    return mod


def mesh_arrays(me):
    """A quad mesh's vertex coordinates (local), edges and quads as numpy arrays."""
    rest = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", rest)
    rest = rest.reshape(-1, 3)
    edges = np.empty(len(me.edges) * 2, dtype=np.int64)
    me.edges.foreach_get("vertices", edges)
    edges = edges.reshape(-1, 2)
    quads = np.empty(len(me.polygons) * 4, dtype=np.int64)
    me.polygons.foreach_get("vertices", quads)
    quads = quads.reshape(-1, 4)
    return rest, edges, quads


def world_coords(ob, depsgraph):
    """The evaluated (simulated) vertex coordinates of ob in world space."""
    ob_eval = ob.evaluated_get(depsgraph)
    me = ob_eval.to_mesh()
    co = np.empty(len(me.vertices) * 3)
    me.vertices.foreach_get("co", co)
    ob_eval.to_mesh_clear()
    co = co.reshape(-1, 3)
    m = np.array(ob.matrix_world)
    return co @ m[:3, :3].T + m[:3, 3]


def lengths(co, pairs):
    """Lengths of the segments between the vertex pairs."""
    return np.linalg.norm(co[pairs[:, 0]] - co[pairs[:, 1]], axis=1)


def strain(co, pairs, rest):
    """(max, mean, min) of length / rest length - 1 over the vertex pairs."""
    s = lengths(co, pairs) / rest - 1.0
    return float(s.max()), float(s.mean()), float(s.min())


def run_frames(scene, cloth, frame_start, frame_end, measure):
    """Steps the frames one by one, timing each frame's step with the evaluation of the cloth's
    coordinates; measure(f, co, wall_s, cpu_s) returns the frame's entry of per_frame and is not
    timed. Returns per_frame, the last frame's coordinates and the report's timing fields (the
    per-frame times over frames frame_start + 1 .. frame_end)."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    per_frame = []
    sim_wall = sim_cpu = 0.0
    first_wall = first_cpu = 0.0
    metrics_wall = 0.0
    for f in range(frame_start, frame_end + 1):
        w0, c0 = time.perf_counter(), time.process_time()
        scene.frame_set(f)
        co = world_coords(cloth, depsgraph)   # forces the evaluated mesh, included in the timing
        dw, dc = time.perf_counter() - w0, time.process_time() - c0
        if f == frame_start:
            first_wall, first_cpu = dw, dc
        else:
            sim_wall += dw
            sim_cpu += dc
        m0 = time.perf_counter()
        per_frame.append(measure(f, co, dw, dc))
        metrics_wall += time.perf_counter() - m0
    n_sim = frame_end - frame_start
    timing = {"total_wall_s": sim_wall, "total_cpu_s": sim_cpu,
              "seconds_per_frame_wall": sim_wall / n_sim, "seconds_per_frame_cpu": sim_cpu / n_sim,
              "first_frame_wall_s": first_wall, "first_frame_cpu_s": first_cpu,
              "metrics_wall_s_untimed": metrics_wall}
    return per_frame, co, timing


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


def quads_to_tris(quads):
    """Each quad (a, b, c, d) as the triangles (a, b, c) and (a, c, d)."""
    return np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])


def self_intersections(co, tris, adjacent=True):
    """(triangle pairs sharing no vertex whose boxes overlap, edge-triangle crossings): an edge of one
    triangle of an overlapping pair crossing the other triangle, the edge sharing no vertex with it
    (the triangles may share one); each (edge, triangle) counted once. With adjacent=False the
    crossings are looked for only between triangles that share no vertex."""
    tree = BVHTree.FromPolygons([tuple(v) for v in co], tris.tolist(), all_triangles=True, epsilon=0.0)
    tri_pairs, edge_tri = set(), set()
    for i, j in tree.overlap(tree):
        if i == j:
            continue
        if not set(tris[i]) & set(tris[j]):
            tri_pairs.add((min(i, j), max(i, j)))
        elif not adjacent:
            continue
        for a, b in ((i, j), (j, i)):
            ta, tb = tris[a], tris[b]
            sb = set(int(v) for v in tb)
            for k in range(3):
                e = tuple(sorted((int(ta[k]), int(ta[(k + 1) % 3]))))
                if e[0] in sb or e[1] in sb or (e, int(b)) in edge_tri:
                    continue
                if seg_tri(co[e[0]], co[e[1]], co[tb[0]], co[tb[1]], co[tb[2]]):
                    edge_tri.add((e, int(b)))
    return len(tri_pairs), len(edge_tri)


def self_intersection_fields(co, tris, adjacent=True):
    """The report's self-intersection fields (see self_intersections) and the check's wall time."""
    t0 = time.perf_counter()
    tri_pairs, edge_tri = self_intersections(co, tris, adjacent)
    return {"final_self_intersecting_triangle_pairs": tri_pairs,
            "final_self_intersecting_edge_triangle_pairs": edge_tri,
            "self_intersection_check_wall_s": time.perf_counter() - t0}


def write_obj(path, co, quads):
    """Writes the cloth (Blender coordinates) as an OBJ in dresskit's axes, (x, z, -y), 1-based faces."""
    with open(path, "w") as f:
        f.write("# Blender %s cloth, final frame, dresskit axes (Y up)\n" % bpy.app.version_string)
        for x, y, z in co:
            f.write("v %.7f %.7f %.7f\n" % (x, z, -y))
        for q in quads:
            f.write("f %d %d %d %d\n" % tuple(int(v) + 1 for v in q))


def run_fields(scene, load_start):
    """The report's first fields: Blender's version, threads, CPU affinity and load averages."""
    return {"blender_version": bpy.app.version_string,
            "threads_cli": cli_threads(),
            "render_threads": scene.render.threads,   # what Blender's thread pool reports (honours --threads)
            "cpu_affinity": sorted(os.sched_getaffinity(0)),
            "loadavg_start": load_start, "loadavg_end": os.getloadavg()}


def grid_fields(cs, n, edges, quads, subdiv):
    """The report's fields on the cloth grid and its mass."""
    return {"grid": {"vertices": n, "edges": len(edges), "quads": len(quads), "x_subdivisions_used": subdiv},
            "vertex_mass": cs.mass, "total_mass": cs.mass * n}


def settings_fields(mod, collider):
    """The report's cloth, collision and collider settings as they are after the run."""
    cs, cc, sc = mod.settings, mod.collision_settings, collider.collision
    return {"cloth_settings": {k: getattr(cs, k) for k in CLOTH_SETTINGS},
            "collision_settings": {k: getattr(cc, k) for k in COLLISION_SETTINGS},
            "collider_settings": {k: getattr(sc, k) for k in COLLIDER_SETTINGS}}


def settings_text(mod, quality=None, air_damping=None, gravity=None):
    """The CSV's description of the settings: the vertex mass, then the quality, air damping and
    gravity where given (not None) and the self-collision distance where self-collision is on."""
    cs, cc = mod.settings, mod.collision_settings
    text = "vertex mass %g kg" % cs.mass
    if quality is not None:
        text += ", quality %d" % cs.quality
    if air_damping is not None:
        text += ", air damping %g" % cs.air_damping
    if gravity is not None:
        text += ", gravity %g" % gravity
    if cc.use_self_collision:
        text += ", self collision (distance %g)" % cc.self_distance_min
    return text


def print_result(out, report, details, values):
    """Prints the run's RESULT line: out, the wall and CPU seconds per frame, then details % values."""
    print("RESULT %s: %.4f s/frame wall, %.4f s/frame cpu, %s" % (
        out, report["seconds_per_frame_wall"], report["seconds_per_frame_cpu"], details % values))
