#!/usr/bin/python3
"""Error against K: how many rotatable square lights an environment needs.

For one frame of a scene, the ground truth once, then the RSL renderer with
K = 4 … 200 lights fitted to the same environment map: the relative L2 error
of the vertex colours and of the image against the truth, the fit's own error
(the map rebuilt from its lights) and the shading time. Prints a Markdown
table; with matplotlib, also plots it (docs/PYTHON.md shows the result).

  /usr/bin/python3 python/examples/error_vs_k.py [SCENE] [--environment MAP ...] [--plot FILE.png]
(PYTHONPATH: the folder of the built or installed module.)
"""
import argparse
import os
import time

import rsl

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("scene", nargs="?", default="demos/compare/scene.json")
parser.add_argument("--time", type=float, default=0.0)
parser.add_argument("--environment", nargs="+", help="maps to light the scene with in turn (default: its own)")
parser.add_argument("--lights", type=int, nargs="+", default=[4, 6, 10, 20, 30, 50, 100, 200])
parser.add_argument("--plot", help="write the plot here (needs matplotlib)")
parser.add_argument("--images", help="write the images of the first map: truth and three K, side by side (matplotlib)")
args = parser.parse_args()


def sweep(scene):
    """Rows (K, vertex error, image error, image H1 error, fit error, shading ms) for one scene,
    and the truth's image and those of three K."""
    renderer = rsl.Renderer(scene, lights=args.lights[0])  # fields from the scene's cache (baked once)
    renderer.set_time(args.time)
    start = time.perf_counter()
    truth = renderer.truth()
    truth_seconds = time.perf_counter() - start
    truth_image = renderer.form_image(truth)
    rows, images = [], {"truth": truth_image}
    shown = {args.lights[0], args.lights[len(args.lights) // 2], args.lights[-1]}
    for k in args.lights:
        fit = rsl.fit_environment(scene.environment_file, k, resolution=scene.environment_resolution)
        renderer.set_environment_lights(fit["centers"], fit["half_diagonals"], fit["radiance"])
        renderer.shade()  # the first frame after new lights sizes its buffers
        start = time.perf_counter()
        colors = renderer.shade()
        shade_ms = 1e3 * (time.perf_counter() - start)
        vertices = rsl.compare(colors, truth)
        rendered = renderer.form_image(colors)
        if k in shown:
            images[f"K = {k}"] = rendered
        image = rsl.compare_images(rendered, truth_image)
        rows.append((k, vertices["relative_l2"], image["relative_l2"], image["relative_h1"], fit["relative_l2"], shade_ms))
    return rows, truth_seconds, images


matplotlib = None
results, first_images = {}, None
for environment in args.environment or [None]:
    scene = rsl.Scene.load(args.scene)
    if environment:
        scene.set_environment(environment, scene.environment_resolution)
    name = os.path.basename(scene.environment_file)
    rows, truth_seconds, images = sweep(scene)
    results[name] = rows
    first_images = first_images or (name, images)
    print(f"scene {scene.name}: {scene.vertex_count} vertices, t = {args.time} s, environment {name} at "
          f"6×{scene.environment_resolution}²; truth {truth_seconds:.2f} s")
    print()
    print("| K | vertex rel. L2 | image rel. L2 | image rel. H1 | fit rel. L2 (map) | shading (ms) |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    for k, v, i, h, f, ms in rows:
        print(f"| {k} | {v:.4f} | {i:.4f} | {h:.4f} | {f:.4f} | {ms:.1f} |")
    print()

if args.plot or args.images:
    try:
        import matplotlib
    except ImportError:
        matplotlib = None
        print("(no matplotlib: the tables above are the result)")
if matplotlib and args.plot:
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 4.2), dpi=100)
    for (name, rows), color in zip(results.items(), ["tab:blue", "tab:orange", "tab:green", "tab:red"]):
        ks = [r[0] for r in rows]
        ax.loglog(ks, [r[1] for r in rows], "o-", color=color, label=f"{name}: vertices vs truth")
        ax.loglog(ks, [r[2] for r in rows], "s:", color=color, label=f"{name}: image vs truth")
        ax.loglog(ks, [r[4] for r in rows], "^--", color=color, alpha=0.5, label=f"{name}: map rebuilt from its lights")
    ax.set_xlabel("K (rotatable square lights)")
    ax.set_ylabel("relative L2 error")
    ax.set_title(f"{scene.name}: error against K")
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.02, 0.5))
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.plot)
    print(f"plot: {args.plot}")
if matplotlib and args.images:
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    name, images = first_images
    # Premultiplied RGB; one exposure for all, from the truth's 99th percentile; gamma 2.2.
    scale = 0.9 / np.percentile(images["truth"][..., :3], 99)
    fig, axes = plt.subplots(1, len(images), figsize=(3.2 * len(images), 2.7), dpi=100)
    for ax, (label, image) in zip(axes, images.items()):
        ax.imshow(np.clip(image[..., :3] * scale, 0, 1) ** (1 / 2.2))
        ax.set_title(f"{name}: {label}", fontsize=9)
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(args.images)
    print(f"images: {args.images}")
