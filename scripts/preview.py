#!/usr/bin/python3
"""Renders meshes written by dresskit (binary PLY with label colours, or OBJ) to a PNG: front and side
views, flat shaded, coloured by part label when the file has colours.

usage: scripts/preview.py OUT.png MESH.ply [MESH.ply ...]
Needs Debian's python3-matplotlib (a development aid; the build and tests do not use it).
"""
import struct
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

TYPES = {"double": "d", "float": "f", "uchar": "B", "int": "i", "uint": "I"}


def fan(idx):
    """A polygon's vertex indices as the triangles (idx[0], idx[k], idx[k + 1])."""
    return [(idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1)]


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    props, nv, nf, element = [], 0, 0, None
    for line in header:
        w = line.split()
        if w[0] == "element":
            element = w[1]
            if element == "vertex":
                nv = int(w[2])
            elif element == "face":
                nf = int(w[2])
        elif w[0] == "property" and element == "vertex":
            props.append((w[2], TYPES[w[1]]))
    fmt = "<" + "".join(t for _, t in props)
    size = struct.calcsize(fmt)
    rows = [struct.unpack_from(fmt, data, end + i * size) for i in range(nv)]
    names = [n for n, _ in props]
    verts = np.array([[r[names.index(a)] for a in "xyz"] for r in rows])
    colours = None
    if "red" in names:
        colours = np.array([[r[names.index(c)] for c in ("red", "green", "blue")] for r in rows]) / 255
    pos, faces = end + nv * size, []
    for _ in range(nf):
        n = data[pos]
        idx = struct.unpack_from("<%di" % n, data, pos + 1)
        pos += 1 + 4 * n
        faces += fan(idx)
    return verts, np.array(faces), colours


def read_obj(path):
    verts, faces = [], []
    for line in open(path):
        w = line.split()
        if w[:1] == ["v"]:
            verts.append([float(x) for x in w[1:4]])
        elif w[:1] == ["f"]:
            faces += fan([int(x.split("/")[0]) - 1 for x in w[1:]])
    return np.array(verts), np.array(faces), None


def main():
    out, paths = sys.argv[1], sys.argv[2:]
    meshes = [read_ply(p) if p.endswith(".ply") else read_obj(p) for p in paths]
    fig = plt.figure(figsize=(8, 6))
    light = np.array([0.3, 0.5, 1.0])
    light /= np.linalg.norm(light)
    # One collection for all meshes, so that their triangles are depth-sorted together. A mesh
    # without colours gets one of its own (a garment over a body), not grey.
    palette = np.array([[0.80, 0.36, 0.36], [0.36, 0.55, 0.80], [0.45, 0.70, 0.40], [0.85, 0.70, 0.30]])
    plain = 0
    tris_all, base_all = [], []
    for verts, faces, colours in meshes:
        # matplotlib's z is up: show dresskit's (x, y, z) as (x, -z, y).
        v = verts[:, [0, 2, 1]] * np.array([1, -1, 1])
        tris_all.append(v[faces])
        if colours is not None:
            base_all.append(colours[faces].mean(axis=1))
        else:
            base_all.append(np.tile(palette[plain % len(palette)], (len(faces), 1)))
            plain += 1
    tris, base = np.concatenate(tris_all), np.concatenate(base_all)
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True) + 1e-30
    shade = 0.35 + 0.65 * np.abs(n @ np.array([light[0], -light[2], light[1]]))
    for view, (elev, azim) in enumerate([(10, -90), (10, 0)]):
        ax = fig.add_subplot(1, 2, view + 1, projection="3d")
        ax.add_collection3d(Poly3DCollection(tris, facecolors=base * shade[:, None], linewidths=0))
        allv = np.vstack([m[0] for m in meshes])[:, [0, 2, 1]] * np.array([1, -1, 1])
        c, r = allv.mean(axis=0), (allv.max(axis=0) - allv.min(axis=0)).max() / 2
        ax.set_xlim(c[0] - r, c[0] + r)
        ax.set_ylim(c[1] - r, c[1] + r)
        ax.set_zlim(c[2] - r, c[2] + r)
        ax.view_init(elev=elev, azim=azim)
        ax.set_axis_off()
        ax.set_box_aspect((1, 1, 1), zoom=1.6)
    plt.tight_layout()
    plt.savefig(out, dpi=90)


if __name__ == "__main__":
    main()
