#!/usr/bin/python3
"""Cutaway figures from Python: the engine's adaptive cutaway (Burns08), the MRI head opened
by a box cut, and the engine's view depth AOV in false colour.

    PYTHONPATH=build/release/python examples/python/cutaway_figures.py [OUT_DIR] [--size WxH]

Writes engine-cutaway.png, mri-head-box-cut.png and engine-view-depth.png to OUT_DIR (default
the current folder). In a notebook, `renderer.render()` shows itself instead.
"""
import argparse
import json
import os

import numpy as np
from PIL import Image

import cutaway

EXAMPLES = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def example(name, size):
    # The bundled scene file as a dict, at the asked size; its relative files resolve
    # against examples/.
    with open(os.path.join(EXAMPLES, name + ".json")) as f:
        scene = json.load(f)
    if size:
        scene["resolution"] = list(size)
    return cutaway.from_dict(scene, base_dir=EXAMPLES)


def false_colour(depth):
    # Near blue to far yellow over the covered pixels; the background (0) white.
    covered = depth > 0
    t = np.zeros_like(depth)
    if covered.any():
        near, far = depth[covered].min(), depth[covered].max()
        t[covered] = (depth[covered] - near) / max(far - near, 1e-9)
    rgb = np.stack([0.15 + 0.8 * t, 0.25 + 0.6 * t, 0.85 - 0.7 * t], axis=-1)
    rgb[~covered] = 1.0
    return (rgb * 255).round().astype(np.uint8)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", nargs="?", default=".")
    p.add_argument("--size", help="WxH instead of the scenes' own")
    args = p.parse_args()
    size = tuple(int(v) for v in args.size.split("x")) if args.size else None
    os.makedirs(args.out, exist_ok=True)

    engine = cutaway.Renderer(example("engine-cutaway", size))
    Image.fromarray(engine.render()).save(os.path.join(args.out, "engine-cutaway.png"))
    depth = engine.aov("viewDepth")
    Image.fromarray(false_colour(depth)).save(os.path.join(args.out, "engine-view-depth.png"))

    head = cutaway.Renderer(example("mri-head-box-cut", size))
    Image.fromarray(head.render()).save(os.path.join(args.out, "mri-head-box-cut.png"))
    print("wrote engine-cutaway.png, engine-view-depth.png and mri-head-box-cut.png to %s (%s)"
          % (args.out, engine.device))


if __name__ == "__main__":
    main()
