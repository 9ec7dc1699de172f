"""Gathers a batch's results: summary.csv (one line per manifest row) and contact_sheet.png.

A row is `ok` when its report.json exists, `failed` when it could not run (the manifest's reason)
or its dress run failed (the error line and exit code from its log), and `not run` when the run
stopped before it. Each result is drawn once into <id>/preview.png (front and side view of the
dressed body from dressed.glb), redrawn when its report is newer; the contact sheet tiles them.
"""
import csv
import json
import os
import re
import struct
import textwrap

STAGES = ["load", "clean", "units", "segmentation", "layers", "placement", "thickness", "settle", "write"]
COLUMNS = (
    ["line", "id", "status", "reason", "exit_code", "quality", "garments", "seconds"]
    + ["seconds_" + s for s in STAGES]
    + ["job_seconds", "max_rss_mb", "settle_steps", "settle_stopped_reason",
       "vertices_inside_placed", "vertices_inside_dressed", "max_strain",
       "crossings_authored", "crossings_fitted", "crossings_placed", "crossings_dressed",
       "crossings_between_layers", "layer_gap_p5_mm_min", "layer_gap_median_mm_min",
       "wearer_rms_mm_max", "carry_move_mm_max", "body_height_m", "folder"]
)
EXIT_LINE = re.compile(r"^workflow: dress-a-mesh exited with code (-?\d+)")

TILE_W, TILE_H, DPI = 280, 300, 100


def row_folder(out, row_id):
    return os.path.join(out, row_id)


def log_path(out, row_id):
    return os.path.join(out, row_id, "dress.log")


def _num(value, digits):
    return "" if value is None else round(float(value), digits)


def _failure(out, row):
    """(reason, exit code) of a valid row without a report, or None when it has not run."""
    log = log_path(out, row.id)
    if not os.path.exists(log):
        return None
    with open(log, errors="replace") as f:
        lines = [l.rstrip("\n") for l in f]
    code, message = "", ""
    for l in lines:
        m = EXIT_LINE.match(l)
        if m:
            code = int(m.group(1))
        elif l.startswith("dress-a-mesh: "):
            message = l
    if code == "" and not message:
        # The job ended without the workflow's last line: killed (time or memory limit,
        # cancelled) or still running elsewhere.
        return ("the job ended without a result (see %s)" % log, "")
    return (message or "dress-a-mesh failed (see %s)" % log, code)


def _benchmark(out, row_id):
    path = os.path.join(out, row_id, "benchmark.tsv")
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f, delimiter="\t"))
        return float(rows[-1]["s"]), float(rows[-1]["max_rss"])
    except (OSError, KeyError, ValueError, IndexError):
        return None, None


def summarize(out, row, report):
    line = {c: "" for c in COLUMNS}
    line.update(line=row.line, id=row.id, quality=row.quality,
                garments=len(row.garments) if row.garments else "", folder=row.id if report else "")
    if report is None:
        return line
    line["status"] = "ok"
    line["seconds"] = _num(report.get("seconds"), 3)
    for stage in report.get("stages", []):
        key = "seconds_" + stage.get("name", "")
        if key in line:
            line[key] = _num(stage.get("seconds"), 3)
    line["job_seconds"], rss = _benchmark(out, row.id)
    line["job_seconds"] = _num(line["job_seconds"], 3)
    line["max_rss_mb"] = _num(rss, 1)
    settle = report.get("settle") or {}
    line["settle_steps"] = settle.get("steps", "")
    line["settle_stopped_reason"] = settle.get("stopped_reason", "")
    garments = report.get("garments", [])
    inside = [g.get("vertices_inside_body_2mm") or {} for g in garments]
    crossings = [g.get("crossings") or {} for g in garments]
    for when in ("placed", "dressed"):
        line["vertices_inside_" + when] = sum(int(i.get(when) or 0) for i in inside)
    for when in ("authored", "fitted", "placed", "dressed"):
        line["crossings_" + when] = sum(int(c.get(when) or 0) for c in crossings)
    strains = [g["max_strain"] for g in garments if g.get("max_strain") is not None]
    line["max_strain"] = _num(max(strains), 4) if strains else ""
    wearers = [g["wearer"] for g in garments if g.get("wearer")]
    rms = [w["rms_mm"] for w in wearers if w.get("rms_mm") is not None]
    moves = [w["carry_move_p95_mm"] for w in wearers if w.get("carry_move_p95_mm") is not None]
    line["wearer_rms_mm_max"] = _num(max(rms), 2) if rms else ""
    line["carry_move_mm_max"] = _num(max(moves), 1) if moves else ""
    layers = report.get("layers") or {}
    line["crossings_between_layers"] = layers.get("crossings_between", "")
    gaps = layers.get("gaps") or []
    for key in ("p5_mm", "median_mm"):
        values = [g[key] for g in gaps if g.get(key) is not None]
        line["layer_gap_%s_min" % key] = _num(min(values), 2) if values else ""
    line["body_height_m"] = _num((report.get("body") or {}).get("height_m"), 3)
    return line


def _report(out, row):
    if row.reason:
        return None
    try:
        with open(os.path.join(out, row.id, "report.json")) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def write_summary(out, rows):
    """Writes out/summary.csv; returns its lines (dicts) in manifest order."""
    lines = []
    for row in rows:
        report = _report(out, row)
        line = summarize(out, row, report)
        if report is None:
            if row.reason:
                line.update(status="failed", reason=row.reason)
            else:
                failure = _failure(out, row)
                if failure is None:
                    line.update(status="not run", reason="the run stopped before this row")
                else:
                    line.update(status="failed", reason=failure[0], exit_code=failure[1])
        lines.append(line)
    path = os.path.join(out, "summary.csv")
    os.makedirs(out, exist_ok=True)
    with open(path + ".tmp", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(lines)
    os.replace(path + ".tmp", path)
    return lines


# --- contact sheet -------------------------------------------------------------------------

_COMPONENTS = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
_WIDTHS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def read_glb(path):
    """[(name, vertices (n×3), triangles (m×3))] of the meshes in a binary glTF file, in metres."""
    import numpy as np

    data = open(path, "rb").read()
    magic, _, _ = struct.unpack_from("<4sII", data, 0)
    if magic != b"glTF":
        raise ValueError("%s: not a binary glTF file" % path)
    json_length, _ = struct.unpack_from("<II", data, 12)
    doc = json.loads(data[20:20 + json_length])
    bin_start = 20 + json_length + 8
    views = doc.get("bufferViews", [])

    def accessor(index):
        a = doc["accessors"][index]
        view = views[a["bufferView"]]
        fmt = _COMPONENTS[a["componentType"]]
        width = _WIDTHS[a["type"]]
        start = bin_start + view.get("byteOffset", 0) + a.get("byteOffset", 0)
        count = a["count"] * width
        array = np.frombuffer(data, dtype=np.dtype("<" + fmt), count=count, offset=start)
        return array.reshape(a["count"], width) if width > 1 else array

    meshes = []
    for node in doc.get("nodes", []):
        if "mesh" not in node:
            continue
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            if prim.get("mode", 4) != 4:
                continue
            verts = accessor(prim["attributes"]["POSITION"]).astype(float)
            if "matrix" in node:
                m = np.array(node["matrix"], dtype=float).reshape(4, 4).T
                verts = verts @ m[:3, :3].T + m[:3, 3]
            tris = accessor(prim["indices"]).astype(np.int64).reshape(-1, 3) if "indices" in prim \
                else np.arange(len(verts)).reshape(-1, 3)
            meshes.append((node.get("name", ""), verts, tris))
    return meshes


def _draw_views(fig, meshes):
    import numpy as np
    from matplotlib.collections import PolyCollection

    palette = np.array([[0.84, 0.38, 0.34], [0.30, 0.50, 0.78], [0.42, 0.66, 0.36],
                        [0.86, 0.68, 0.26], [0.58, 0.42, 0.70]])
    skin = np.array([0.86, 0.80, 0.74])
    light = np.array([0.35, 0.45, 1.0])
    light /= np.linalg.norm(light)
    tris, colours, bias = [], [], []
    garment = 0
    for name, verts, faces in meshes:
        base = skin if name == "body" else palette[garment % len(palette)]
        # Garments lie millimetres over the body and over each other (inside to outside in the
        # file): sorting by centroid alone would let the larger triangles beneath cover them, so
        # each layer is sorted as if a little nearer than the one under it.
        bias.append(np.full(len(faces), 0.0 if name == "body" else 0.02 * (1 + garment)))
        if name != "body":
            garment += 1
        tris.append(verts[faces])
        colours.append(np.repeat(base[None, :], len(faces), axis=0))
    if not tris:
        return
    tris = np.concatenate(tris)
    colours = np.concatenate(colours)
    bias = np.concatenate(bias)
    lo, hi = tris.reshape(-1, 3).min(axis=0), tris.reshape(-1, 3).max(axis=0)
    centre = (lo + hi) / 2
    # Front view from +z (x to the right) and side view from +x, the body's left (-z to the right);
    # triangles drawn far to near. Both at one scale that fits the height and the widths.
    width, height = 0.5 * TILE_W, 0.88 * TILE_H
    half_h = 1.03 * max((hi[1] - lo[1]) / 2, (hi[0] - lo[0]) / 2 * height / width,
                        (hi[2] - lo[2]) / 2 * height / width)
    half_w = half_h * width / height
    for i, (h_axis, h_sign, depth_axis) in enumerate([(0, 1, 2), (2, -1, 0)]):
        ax = fig.add_axes([i * 0.5, 0.0, 0.5, 0.88])
        ax.set_axis_off()
        ax.set_xlim(-half_w, half_w)
        ax.set_ylim(-half_h, half_h)
        order = np.argsort(tris[:, :, depth_axis].mean(axis=1) + bias)  # far first
        t = tris[order]
        n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
        n /= np.linalg.norm(n, axis=1, keepdims=True) + 1e-30
        l = light if depth_axis == 2 else np.array([light[2], light[1], light[0]])
        shade = 0.35 + 0.65 * np.abs(n @ l)
        c = np.clip(colours[order] * shade[:, None], 0, 1)
        xy = np.stack([(t[:, :, h_axis] - centre[h_axis]) * h_sign, t[:, :, 1] - centre[1]], axis=2)
        ax.add_collection(PolyCollection(xy, facecolors=c, edgecolors="none", antialiased=False))


def _figure():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(TILE_W / DPI, TILE_H / DPI), dpi=DPI)
    fig.patch.set_facecolor("white")
    return plt, fig


def _to_array(plt, fig):
    import numpy as np

    fig.canvas.draw()
    image = np.asarray(fig.canvas.buffer_rgba())[:, :, :3].copy()
    plt.close(fig)
    return image


def render_preview(glb, title, path):
    plt, fig = _figure()
    _draw_views(fig, read_glb(glb))
    fig.text(0.5, 0.97, title, ha="center", va="top", fontsize=7)
    image = _to_array(plt, fig)
    plt.imsave(path + ".tmp.png", image)
    os.replace(path + ".tmp.png", path)
    return image


def _text_tile(title, body, colour):
    plt, fig = _figure()
    fig.text(0.5, 0.97, title, ha="center", va="top", fontsize=7)
    wrapped = "\n".join(textwrap.wrap(body, 38)[:12])
    fig.text(0.5, 0.5, wrapped, ha="center", va="center", fontsize=6, color=colour)
    return _to_array(plt, fig)


def write_contact_sheet(out, lines, columns=None):
    import math

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    tiles = []
    for line in lines:
        title = "%s (line %s)  %s" % (line["id"] or "no id", line["line"], line["status"])
        if line["status"] == "ok":
            folder = row_folder(out, line["id"])
            glb, preview = os.path.join(folder, "dressed.glb"), os.path.join(folder, "preview.png")
            title += "  %.1f s" % float(line["seconds"] or 0)
            try:
                if os.path.exists(preview) and os.path.getmtime(preview) >= os.path.getmtime(
                        os.path.join(folder, "report.json")):
                    image = (plt.imread(preview)[:, :, :3] * 255).astype(np.uint8)
                else:
                    image = render_preview(glb, title, preview)
            except (OSError, ValueError, KeyError, IndexError) as e:
                image = _text_tile(title, "no picture: %s" % e, "black")
        else:
            image = _text_tile(title, line["reason"], "firebrick")
        if image.shape[:2] != (TILE_H, TILE_W):
            padded = np.full((TILE_H, TILE_W, 3), 255, np.uint8)
            h, w = min(TILE_H, image.shape[0]), min(TILE_W, image.shape[1])
            padded[:h, :w] = image[:h, :w]
            image = padded
        tiles.append(image)
    # One line up to 6 rows, else about square; tiles shrink (every k-th pixel) so that the sheet
    # stays under about 50 megapixels.
    count = max(1, len(tiles))
    columns = columns or (count if count <= 6 else math.ceil(math.sqrt(count * TILE_H / TILE_W)))
    step = max(1, math.ceil(math.sqrt(count * TILE_W * TILE_H / 50e6)))
    tile_h, tile_w = len(range(0, TILE_H, step)), len(range(0, TILE_W, step))
    rows = math.ceil(count / columns)
    sheet = np.full((rows * tile_h, columns * tile_w, 3), 255, np.uint8)
    for i, tile in enumerate(tiles):
        r, c = divmod(i, columns)
        sheet[r * tile_h:(r + 1) * tile_h, c * tile_w:(c + 1) * tile_w] = tile[::step, ::step]
    path = os.path.join(out, "contact_sheet.png")
    plt.imsave(path + ".tmp.png", sheet)
    os.replace(path + ".tmp.png", path)


def gather(out, rows):
    lines = write_summary(out, rows)
    write_contact_sheet(out, lines)
    return lines


def read_summary(out):
    with open(os.path.join(out, "summary.csv"), newline="") as f:
        return list(csv.DictReader(f))


def tally(lines):
    """'5 rows: 3 ok, 2 failed' (and 'not run' when some are)."""
    counts = {}
    for line in lines:
        counts[line["status"]] = counts.get(line["status"], 0) + 1
    parts = ["%d %s" % (counts[s], s) for s in ("ok", "failed", "not run") if s in counts]
    return "%d row%s: %s" % (len(lines), "" if len(lines) == 1 else "s", ", ".join(parts))
