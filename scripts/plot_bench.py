#!/usr/bin/python3
"""Plots dresskit's benchmark CSVs to PNG (needs Debian's python3-matplotlib; a development aid).

usage: scripts/plot_bench.py stability IN.csv OUT.png
       scripts/plot_bench.py error IN.csv OUT.png
       scripts/plot_bench.py heat IN.csv OUT.png        (bench_heat_error's CSV)
       scripts/plot_bench.py surface IN.csv OUT.png     (dress-a-mesh thickness --plot's temperature.csv)
       scripts/plot_bench.py segmentation IN.csv OUT.png (bench_segmentation --csv)
       scripts/plot_bench.py alignment IN.csv OUT.png   (bench_alignment --only tradeoff --csv)
       scripts/plot_bench.py sphere A.csv,B.csv,... OUT.png (bench_cloth_sphere CSVs and
                                                       docs/data/blender_cloth_on_sphere.csv)
       scripts/plot_bench.py drape IN.csv OUT.png       (bench_drape's CSV: the contact envelope)
       scripts/plot_bench.py dress IN.csv OUT.png       (bench_dress's CSV: error against time)
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def save(fig, out, title=None):
    """Writes the figure to out (90 dpi) after laying it out, with title above its plots if given."""
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=90)


def stability(rows, out):
    integrators = sorted({r["integrator"] for r in rows})
    ks = sorted({float(r["k_per_mass"]) for r in rows})
    dts = sorted({float(r["dt"]) for r in rows})
    fig, axes = plt.subplots(1, len(integrators), figsize=(5 * len(integrators), 4), squeeze=False)
    for ax, name in zip(axes[0], integrators):
        grid = [[0] * len(dts) for _ in ks]
        for r in rows:
            if r["integrator"] == name:
                grid[ks.index(float(r["k_per_mass"]))][dts.index(float(r["dt"]))] = int(r["stable"])
        ax.imshow(grid, origin="lower", cmap="RdYlGn", vmin=0, vmax=1, aspect="auto")
        ax.set_xticks(range(len(dts)), ["1/%d" % round(1 / d) for d in dts])
        ax.set_yticks(range(len(ks)), ["1e%d" % round(__import__("math").log10(k)) for k in ks])
        ax.set_xlabel("time step [s]")
        ax.set_ylabel("stiffness / particle mass [N/m/kg]")
        titles = {"implicit": "implicit Euler", "newton": "Newton (backward Euler)", "symplectic": "symplectic Euler",
                  "projective": "projective dynamics", "projective-bdf2": "projective dynamics, BDF2",
                  "projective-tr_bdf2": "projective dynamics, TR-BDF2",
                  "projective-tr_bdf2-aw": "projective, TR-BDF2, adaptive weights",
                  "projective-midpoint": "projective dynamics, implicit midpoint"}
        ax.set_title("%s: green = stable" % titles.get(name, name))
    save(fig, out)


def error(rows, out):
    """One colour per integrator (and projective variant); for projective dynamics a thin line joins
    the iteration counts at one step size (more iterations: to the right), so that a converging
    setting reads as a line levelling off."""
    fig, ax = plt.subplots(figsize=(10, 6))
    groups = {}
    unstable = set()
    for r in rows:
        if r["stable"] != "1":
            unstable.add(r["integrator"])
            continue
        name = r["integrator"]
        if not name.startswith("projective"):
            name += ", CG tol %s" % r["cg_tolerance"]
        step = r["label"].split(" tol")[0].split(" it ")[0]
        iterations = int(r["label"].split(" it ")[1]) if " it " in r["label"] else 0
        cost = float(r.get("cpu_ms_per_frame") or r["ms_per_frame"])  # CPU time when the CSV has it
        groups.setdefault(name, {}).setdefault(step, []).append((iterations, cost, float(r["relative_error"])))
    colours = plt.get_cmap("tab20")
    for k, (name, steps) in enumerate(sorted(groups.items())):
        colour = colours(k % 20)
        marker = "o" if not name.startswith("projective") else "^"
        first = True
        for step, pts in steps.items():
            pts.sort()
            ax.loglog([p[1] for p in pts], [p[2] for p in pts], "-", marker=marker, color=colour,
                      lw=0.7, ms=3.5, label=name if first else None)
            first = False
    ax.axhline(0.01, color="grey", ls="--", lw=0.8)
    ax.axvline(5.0, color="grey", ls="--", lw=0.8)
    ax.text(5.2, 0.0105, "goal: 1 % at 5 ms", fontsize=8, color="grey")
    ax.set_xlabel("time per 1/60 s frame [ms], one core (CPU time when measured)")
    ax.set_ylabel("RMS position error / cloth size at t = 1 s")
    title = "81x81 hanging cloth: error against run time (projective: a line per step, iterations rising)"
    if unstable:
        title += "\n(unstable at every tested step: %s)" % ", ".join(sorted(unstable))
    ax.set_title(title, fontsize=10)
    ax.set_xlim(1, 1000)
    ax.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.01, 0.5))
    save(fig, out)


def heat(rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    colours = {"explicit": "tab:red", "implicit": "tab:blue", "crank-nicolson": "tab:green"}
    for scheme, colour in colours.items():
        pts = [(float(r["seconds"]) * 1e3, float(r["max_temperature_error_k"]), float(r["thickness_relative_error"]))
               for r in rows if r["scheme"] == scheme]
        axes[0].loglog([p[0] for p in pts], [p[1] for p in pts], "o", ms=3, color=colour, label=scheme)
        axes[1].loglog([p[0] for p in pts], [max(p[2], 1e-9) for p in pts], "o", ms=3, color=colour, label=scheme)
    axes[0].set_ylabel("largest temperature error against erfc [K]")
    axes[1].set_ylabel("thickness error / exact thickness")
    for ax in axes:
        ax.set_xlabel("wall time per solve [ms], one core")
        ax.legend()
    save(fig, out, "1D heat solver, gray-interlock 37 / -10 C, 3600 s: cells 25-800 x steps 10-3200")


def surface(rows, out):
    depths = [float(k[len("T_at_"):-len("_mm")]) for k in rows[0] if k.startswith("T_at_")]
    keys = [k for k in rows[0] if k.startswith("T_at_")]
    times = [float(r["time_s"]) for r in rows]
    grid = [[float(r[k]) for k in keys] for r in rows]
    fig, ax = plt.subplots(figsize=(7, 5))
    mesh = ax.pcolormesh(depths, times, grid, cmap="coolwarm", shading="auto")
    ax.contour(depths, times, grid, levels=8, colors="k", linewidths=0.5)
    ax.set_xlim(0, depths[-1] / 4)
    ax.set_xlabel("depth from the skin [mm]")
    ax.set_ylabel("time [s]")
    fig.colorbar(mesh, label="temperature [C]")
    ax.set_title("T(x, t) through the fabric")
    save(fig, out)


def segmentation(rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    ncvs = sorted({int(r["ncv"]) for r in rows})
    for ncv, colour in zip(ncvs, plt.cm.viridis([i / max(1, len(ncvs) - 1) for i in range(len(ncvs))])):
        pts = [(float(r["seconds_total"]) * 1e3, float(r["eigen_residual"]), 1 - float(r["agreement"]),
                "%g" % float(r["tolerance"])) for r in rows if int(r["ncv"]) == ncv and r["converged"] == "1"]
        axes[0].loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, color=colour, label="ncv %d" % ncv)
        axes[1].semilogy([p[0] for p in pts], [max(p[2], 1e-6) for p in pts], "o-", ms=4, color=colour,
                         label="ncv %d" % ncv)
        for p in pts:
            axes[0].annotate(p[3], (p[0], p[1]), fontsize=6, xytext=(3, 2), textcoords="offset points")
    axes[0].axhline(1e-8, color="grey", ls="--", lw=0.8)
    axes[0].set_ylabel("eigen residual max |Lx - lx| (labels: solver tolerance)")
    axes[1].set_ylabel("1 - label agreement with the reference (floor 1e-6 = identical)")
    for ax in axes:
        ax.axvline(1000, color="grey", ls=":", lw=0.8)
        ax.set_xlabel("segment_mesh wall time [ms], one core")
        ax.legend(fontsize=7)
    save(fig, out, "gc_mean_all (23 752 vertices, 6 parts): error against run time over tolerance and ncv")


def alignment(rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for points in sorted({int(r["source_points"]) for r in rows}):
        pts = sorted((float(r["mean_ms"]), float(r["median_rotation_deg"]), float(r["median_translation_percent"]),
                      int(r["max_iterations"])) for r in rows if int(r["source_points"]) == points)
        label = "%d source points" % points
        axes[0].loglog([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, label=label)
        axes[1].loglog([p[0] for p in pts], [p[2] for p in pts], "o-", ms=4, label=label)
        if points == 2500:
            for p in pts:
                axes[0].annotate("%d it" % p[3], (p[0], p[1]), fontsize=7, xytext=(4, 3), textcoords="offset points")
    axes[0].axhline(0.5, color="grey", ls="--", lw=0.8)
    axes[1].axhline(0.5, color="grey", ls="--", lw=0.8)
    axes[0].set_ylabel("median rotation error [deg]")
    axes[1].set_ylabel("median translation error [% of diagonal]")
    for ax in axes:
        ax.set_xlabel("wall time per registration [ms], one core")
        ax.legend(fontsize=8)
    save(fig, out, "ICP error against run time: MakeHuman body, 20 deg, 0.5% noise, 10% outliers "
                   "(max iterations per stage 1-40)")


def sphere(rows, out):
    fig, axes = plt.subplots(2, 2, figsize=(13, 11))
    markers = {"gray-interlock": "o", "11oz-black-denim": "s", "Blender default": "*"}
    for ax, key, title in ((axes[0][0], "max_strain", "largest structural strain at the end"),
                           (axes[0][1], "max_shear_strain", "largest shear strain at the end"),
                           (axes[1][0], "late_mean_max_strain",
                            "largest structural strain, mean over the last 0.5 s"),
                           (axes[1][1], "late_mean_max_shear_strain",
                            "largest shear strain, mean over the last 0.5 s")):
        for fabric in sorted({r["fabric"] for r in rows}):
            pts = [r for r in rows if r["fabric"] == fabric and "failed" not in r.get("stopped", "")
                   and "the brief" not in r["setting"] and "self-collision" not in r["setting"]
                   and "run 2" not in r["setting"] and "run 3" not in r["setting"]
                   and r.get(key)]
            ax.loglog([float(r["cpu_seconds_per_frame"]) for r in pts], [float(r[key]) for r in pts],
                      markers.get(fabric, "^"), ms=9 if fabric == "Blender default" else 6, label=fabric)
            for r in pts:
                ax.annotate(r["setting"].replace("Blender, ", "Blender ").replace(" (run 1)", ""),
                            (float(r["cpu_seconds_per_frame"]), float(r[key])), fontsize=6,
                            xytext=(4, 2), textcoords="offset points")
        ax.axvline(0.015, color="grey", ls="--", lw=0.8)
        ax.text(0.0152, ax.get_ylim()[0] * 1.1, "goal 0.015 s", fontsize=7, color="grey")
        ax.set_xlabel("CPU seconds per 1/24 s frame, one core")
        ax.set_ylabel(title)
        ax.legend(fontsize=8)
    save(fig, out, "Cloth onto a sphere (64x64, 0.3 kg, 2 s): run time against strain; "
                   "dresskit settings (bench_cloth_sphere) and Blender 3.4.1's cloth")


def drape(rows, out):
    """Cases (rows) × settings (columns): green = held (finished, nothing inside, no crossing,
    strain <= 12 %, fell), red = not; each cell shows the CPU seconds, or why it failed."""
    cases = list(dict.fromkeys(r["case"] for r in rows))
    settings = list(dict.fromkeys(r["setting"] for r in rows))
    grid = [[float("nan")] * len(settings) for _ in cases]
    fig, ax = plt.subplots(figsize=(1.0 + 0.62 * len(settings), 1.2 + 0.5 * len(cases)))
    for r in rows:
        i, j = cases.index(r["case"]), settings.index(r["setting"])
        held = int(r["held"])
        grid[i][j] = held
        if r["stopped"].startswith("failed"):
            text = "blow-up"
        elif not held:
            why = []
            if int(r["inside_2mm"]) > 0:
                why.append("in %s" % r["inside_2mm"])
            if int(r["crossings"]) > 0:
                why.append("x %s" % r["crossings"])
            if float(r["max_strain"]) > 0.12:
                why.append("%.0f%%" % (100 * float(r["max_strain"])))
            text = "\n".join(why) or "no fall"
        else:
            text = "%.1f" % float(r["cpu_seconds"])
        ax.text(j, i, text, ha="center", va="center", fontsize=7)
    ax.imshow(grid, cmap="RdYlGn", vmin=0, vmax=1, aspect="auto", alpha=0.8)
    ax.set_xticks(range(len(settings)), settings, rotation=60, ha="right", fontsize=8)
    ax.set_yticks(range(len(cases)), cases, fontsize=8)
    ax.set_title("Cloth dropped onto real bodies: held (green, CPU s) or not (red, why)", fontsize=10)
    save(fig, out)


def dress(rows, out):
    """Per case with a reference: the mean distance to it (% of body height) against the whole
    run's seconds, one point per quality, and the placed garment (before settling) at the placement's
    time."""
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for case in dict.fromkeys(r["case"] for r in rows):
        points = [r for r in rows if r["case"] == case and r["ok"] == "1" and float(r["dressed_error_pct"]) >= 0]
        if not points:
            continue
        first = points[0]
        placed_at = sum(float(first[k]) for k in ("load_s", "segmentation_s", "placement_s"))
        xs = [placed_at] + [float(r["seconds"]) for r in points]
        ys = [float(first["placed_error_pct"])] + [float(r["dressed_error_pct"]) for r in points]
        ax.plot(xs, ys, "o-", label=case)
        ax.annotate("placed", (xs[0], ys[0]), textcoords="offset points", xytext=(5, 5), fontsize=8)
        for r, x, y in zip(points, xs[1:], ys[1:]):
            ax.annotate(r["quality"], (x, y), textcoords="offset points", xytext=(5, 5), fontsize=8)
    ax.set_xscale("log")
    ax.set_xlabel("whole run [s] (placed: load + segmentation + placement)")
    ax.set_ylabel("mean distance to the reference [% of body height]")
    ax.set_title("dress: error against time per quality")
    ax.legend(fontsize=8)
    save(fig, out)


if __name__ == "__main__":
    kind, src, out = sys.argv[1:4]
    rows = [r for path in src.split(",") for r in csv.DictReader(open(path))]
    {"stability": stability, "error": error, "heat": heat, "surface": surface,
     "segmentation": segmentation, "alignment": alignment, "sphere": sphere, "drape": drape, "dress": dress}[kind](rows, out)
