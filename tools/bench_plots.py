#!/usr/bin/env python3
"""The plots of `shadowcert bench` (docs/bench.md#the-plots), drawn from bench.json alone.

    python3 tools/bench_plots.py DIR/bench.json DIR/plots

Writes PNG files and DIR/plots/index.json (a list of {"file", "title", "caption"}, in order),
which report.html reads. `shadowcert bench` runs this script itself when a python3 with
matplotlib is found (Debian: python3-matplotlib); the Agg backend needs no display.

  time_vs_error_SUITE[_K].png   per scene: frame ms against hard-error pixels, one point per run
                                (method and parameter), coloured by family, the Pareto front
                                (no run both faster and with fewer errors) drawn and labelled
  contour_vs_eps.png            analytic suite: contour error (max distance to the conic) against
                                smooth's eps, one line per caster, discrete and accurate dotted
  contour_vs_tessellation.png   analytic suite: contour error against the caster's triangles, one
                                line per method and eps
  soft_error_vs_ms[_K].png      per scene with a soft reference: mean soft-shadow error against
                                frame ms, the shadow-map family and cpu (the exact hard shadow)
  precision_recall.png          edge maps (issue 14): precision against recall per run and scene
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402

FAMILY_COLOURS = {"stencil": "#1f77b4", "silhouette": "#2ca02c", "shadowmap": "#d62728", "edges": "#9467bd",
                  "ray_traced": "#8c564b"}
PER_FIGURE = 12  # scenes per figure of small multiples


def frame_ms(run):
    return run["time"]["frame_ms"]["median"]


def pareto(points):
    """The points (x, y, ...) that no other point beats in both x and y (smaller is better), by x."""
    front = []
    best_y = math.inf
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if p[1] < best_y:
            front.append(p)
            best_y = p[1]
    return front


def add_families(families, points):
    for p in points:
        if p[3] not in families:
            families.append(p[3])


def scene_title(scene):
    return f"{scene['suite']}/{scene['name']}"


def small_multiples(count):
    cols = min(4, max(1, count))
    rows = (count + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.4 * rows), squeeze=False)
    for ax in axes.flat[count:]:
        ax.set_visible(False)
    return fig, list(axes.flat)


def family_legend(fig, families):
    handles = [plt.Line2D([], [], marker="o", linestyle="", color=FAMILY_COLOURS[f], label=f) for f in families]
    handles.append(plt.Line2D([], [], color="black", linewidth=1, label="Pareto front"))
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), frameon=False)


def scatter_with_front(ax, points, y_label, y_log):
    """points: (x, y, id, family)."""
    for x, y, _, family in points:
        ax.plot(x, y, "o", color=FAMILY_COLOURS.get(family, "gray"), markersize=4, alpha=0.8)
    front = pareto(points)
    ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="black", linewidth=1)
    for x, y, run_id, _ in front:
        ax.annotate(run_id, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
    log_axis(ax, [p[0] for p in points])
    top = max([p[1] for p in points] + [0])
    if y_log:
        ax.set_yscale("symlog", linthresh=1.0)
        ax.set_ylim(-0.05, max(10.0, 2.0 * top))
    else:
        ax.set_ylim(0, max(1e-3, 1.1 * top))
    ax.set_xlabel("frame ms (median)")
    ax.set_ylabel(y_label)
    ax.grid(True, which="both", linewidth=0.3, alpha=0.5)


def log_axis(ax, xs):
    """A log x axis over whole decades (labels at powers of ten only, never crowded)."""
    ax.set_xscale("log")
    if xs:
        lo, hi = min(xs), max(xs)
        ax.set_xlim(10 ** math.floor(math.log10(lo)), 10 ** math.ceil(math.log10(hi) + 1e-9))
    ax.xaxis.set_minor_formatter(ticker.NullFormatter())


def chunks(items, size):
    return [items[i:i + size] for i in range(0, len(items), size)] or [[]]


def save(fig, out_dir, name, title, caption, index):
    fig.savefig(os.path.join(out_dir, name), dpi=90)
    plt.close(fig)
    index.append({"file": name, "title": title, "caption": caption})


def time_vs_error(bench, out_dir, index):
    suites = []
    for scene in bench["scenes"]:
        if scene["skipped"] is None and scene["runs"] and scene["suite"] not in suites:
            suites.append(scene["suite"])
    for suite in suites:
        scenes = [s for s in bench["scenes"] if s["suite"] == suite and s["skipped"] is None and s["runs"]]
        parts = chunks(scenes, PER_FIGURE)
        for k, part in enumerate(parts):
            fig, axes = small_multiples(len(part))
            families = []
            for ax, scene in zip(axes, part):
                points = [(max(frame_ms(r), 1e-3), r["error"]["hard_errors"], r["id"], r["family"]) for r in scene["runs"]
                          if r["error"]["hard_errors"] is not None]  # edge maps have no lit mask
                add_families(families, points)
                scatter_with_front(ax, points, "hard-error pixels", True)
                ax.set_title(scene_title(scene), fontsize=9)
            family_legend(fig, families)
            fig.tight_layout(rect=(0, 0.05, 1, 1))
            suffix = f"_{k + 1}" if len(parts) > 1 else ""
            save(fig, out_dir, f"time_vs_error_{suite}{suffix}.png",
                 f"Time against error, {suite}" + (f" ({k + 1}/{len(parts)})" if len(parts) > 1 else ""),
                 "per scene, every run: median frame ms against pixels disagreeing with the exact image "
                 "(hard errors; symlog axis), coloured by family; the line is the Pareto front, its runs labelled",
                 index)


def analytic_runs(bench):
    """{light: [(scene, run), ...]} for the analytic suite's silhouette runs with a contour error."""
    out = {}
    for scene in bench["scenes"]:
        if scene["suite"] != "analytic" or scene["skipped"] is not None:
            continue
        light = scene["name"].rsplit("-", 1)[-1]
        for run in scene["runs"]:
            if run["family"] == "silhouette" and run["error"]["contour"] is not None:
                out.setdefault(light, []).append((scene, run))
    return out


def contour_axes(ax, light, xlabel):
    """Log-log axes of a contour-error panel of the analytic suite under `light`."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("contour error, max (world units)")
    ax.set_title(f"analytic suite, {light} light", fontsize=10)
    ax.grid(True, which="both", linewidth=0.3, alpha=0.5)
    ax.legend(fontsize=7)


def contour_plots(bench, out_dir, index):
    by_light = analytic_runs(bench)
    if not by_light:
        return
    lights = list(by_light)
    colours = plt.get_cmap("viridis")
    # Against eps.
    fig, axes = plt.subplots(1, len(lights), figsize=(6 * len(lights), 4.2), squeeze=False)
    for ax, light in zip(axes[0], lights):
        shapes = []
        for scene, _ in by_light[light]:
            if scene["name"] not in shapes:
                shapes.append(scene["name"])
        for i, shape in enumerate(shapes):
            colour = colours(i / max(1, len(shapes) - 1))
            smooth = sorted((r["parameter"]["epsilon"], r["error"]["contour"]["max"])
                            for s, r in by_light[light] if s["name"] == shape and r["method"] == "smooth")
            if smooth:
                ax.plot([e for e, _ in smooth], [max(m, 1e-6) for _, m in smooth], "o-", color=colour,
                        label=shape.rsplit("-", 1)[0], markersize=3)
            for s, r in by_light[light]:
                if s["name"] == shape and r["method"] == "discrete":
                    ax.axhline(max(r["error"]["contour"]["max"], 1e-6), color=colour, linestyle=":", linewidth=0.8)
        contour_axes(ax, light, "smooth's eps (world units)")
        ax.invert_xaxis()
    fig.tight_layout()
    save(fig, out_dir, "contour_vs_eps.png", "Contour error against eps",
         "smooth's largest distance from the analytic conic on the floor as eps falls, one line per caster "
         "(viridis from coarse to fine); dotted: discrete at the same tessellation", index)
    # Against tessellation.
    fig, axes = plt.subplots(1, len(lights), figsize=(6 * len(lights), 4.2), squeeze=False)
    for ax, light in zip(axes[0], lights):
        ids = []
        for _, r in by_light[light]:
            if r["id"] not in ids:
                ids.append(r["id"])
        for i, run_id in enumerate(ids):
            points = sorted((s["triangles"], r["error"]["contour"]["max"]) for s, r in by_light[light]
                            if r["id"] == run_id and s["name"].startswith("sphere"))
            if points:
                ax.plot([t for t, _ in points], [max(m, 1e-6) for _, m in points], marker="o", markersize=3,
                        color=colours(i / max(1, len(ids) - 1)), label=run_id,
                        linestyle="--" if run_id in ("discrete", "accurate") else "-")
        contour_axes(ax, light, "triangles of the scene (uv spheres 8x4 to 256x128, and the floor)")
    fig.tight_layout()
    save(fig, out_dir, "contour_vs_tessellation.png", "Contour error against tessellation",
         "the largest distance from the analytic conic for every silhouette run as the sphere gets finer "
         "(dashed: discrete and accurate)", index)


def soft_plots(bench, out_dir, index):
    scenes = [s for s in bench["scenes"] if s["skipped"] is None and s.get("soft_reference") is not None
              and any(r["error"]["soft"] is not None and (r["family"] == "shadowmap" or r["id"] == "cpu")
                      for r in s["runs"])]
    if not scenes:
        return
    parts = chunks(scenes, PER_FIGURE)
    for k, part in enumerate(parts):
        fig, axes = small_multiples(len(part))
        families = []
        for ax, scene in zip(axes, part):
            points = [(max(frame_ms(r), 1e-3), r["error"]["soft"]["mean_error"], r["id"], r["family"])
                      for r in scene["runs"]
                      if r["error"]["soft"] is not None and (r["family"] == "shadowmap" or r["id"] == "cpu")]
            add_families(families, points)
            scatter_with_front(ax, points, "mean |light error|", False)
            ax.set_title(scene_title(scene), fontsize=9)
        family_legend(fig, families)
        fig.tight_layout(rect=(0, 0.05, 1, 1))
        suffix = f"_{k + 1}" if len(parts) > 1 else ""
        save(fig, out_dir, f"soft_error_vs_ms{suffix}.png",
             "Soft-shadow error against ms" + (f" ({k + 1}/{len(parts)})" if len(parts) > 1 else ""),
             "per scene with a soft reference: the mean |light - exact soft light| of cpu (the exact hard shadow) and "
             "the shadow-map family against median frame ms; the line is the Pareto front", index)


def precision_recall(bench, out_dir, index):
    points = [(r["error"]["edges"]["recall"], r["error"]["edges"]["precision"], r["id"], scene_title(s))
              for s in bench["scenes"] if s["skipped"] is None for r in s["runs"]
              if r["error"].get("edges") is not None]
    if not points:
        return
    fig, ax = plt.subplots(figsize=(6, 5))
    ids = sorted({p[2] for p in points})
    colours = plt.get_cmap("viridis")
    for i, run_id in enumerate(ids):
        ax.plot([p[0] for p in points if p[2] == run_id], [p[1] for p in points if p[2] == run_id], "o",
                color=colours(i / max(1, len(ids) - 1)), label=run_id, markersize=4)
    ax.set_xlim(0, 1.02)
    ax.set_ylim(0, 1.02)
    ax.set_xlabel("recall")
    ax.set_ylabel("precision")
    ax.grid(True, linewidth=0.3, alpha=0.5)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save(fig, out_dir, "precision_recall.png", "Edge maps: precision against recall",
         "every edge-map run on every scene against the exact edges", index)


def main(argv):
    if len(argv) != 3:
        sys.stderr.write("usage: bench_plots.py BENCH_JSON OUT_DIR\n")
        return 2
    with open(argv[1], encoding="utf-8") as f:
        bench = json.load(f)
    out_dir = argv[2]
    os.makedirs(out_dir, exist_ok=True)
    plt.rcParams.update({"font.size": 8})
    index = []
    time_vs_error(bench, out_dir, index)
    contour_plots(bench, out_dir, index)
    soft_plots(bench, out_dir, index)
    precision_recall(bench, out_dir, index)
    with open(os.path.join(out_dir, "index.json"), "w", encoding="utf-8") as f:
        json.dump(index, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
