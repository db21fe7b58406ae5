#!/usr/bin/python3
"""Cutaway figures from Python: the engine's adaptive cutaway (Burns08), the abdominal CT
(a NumPy array) opened by a contextual cutaway around an ultrasound plane (Burns11 §7.1), and
a matplotlib figure of both with the engine's view depth AOV.

    PYTHONPATH=build/release/python examples/python/cutaway_figures.py [OUT_DIR] [--size WxH]

Writes engine-cutaway.png, ct-stent-contextual.png and cutaway-figures.png (the matplotlib
figure) to OUT_DIR (default the current folder). In a notebook, `renderer.render()` shows
itself instead.
"""
import argparse
import json
import os

import matplotlib
import numpy as np
from PIL import Image

import cutaway

matplotlib.use("Agg")  # files, no window
import matplotlib.pyplot as plt  # noqa: E402 (after the backend is chosen)

EXAMPLES = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# A real abdominal CT with a stented aorta (int16 Hounsfield units), from python3-imageio.
STENT = "/usr/lib/python3/dist-packages/imageio/resources/images/stent.npz"


def example(name, size):
    # The bundled scene file as a dict, at the asked size.
    with open(os.path.join(EXAMPLES, name + ".json")) as f:
        scene = json.load(f)
    if size:
        scene["resolution"] = list(size)
    return scene


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", nargs="?", default=".")
    p.add_argument("--size", help="WxH instead of the scenes' own")
    args = p.parse_args()
    size = tuple(int(v) for v in args.size.split("x")) if args.size else None
    os.makedirs(args.out, exist_ok=True)

    engine = cutaway.Renderer(cutaway.from_dict(example("engine-cutaway", size),
                                                base_dir=EXAMPLES))
    engine_image = engine.render()
    Image.fromarray(engine_image).save(os.path.join(args.out, "engine-cutaway.png"))
    depth = engine.aov("viewDepth")

    # The CT scene with its volume from the array instead of the file: the array is indexed
    # [z, y, x], the volume [i, j, k], hence the transpose.
    ct = example("ct-stent-contextual", size)
    volume = ct["volumes"][0]
    del volume["file"]
    volume["values"] = np.load(STENT)["arr_0"].T
    ct_renderer = cutaway.Renderer(cutaway.from_dict(ct, base_dir=EXAMPLES))
    ct_image = ct_renderer.render()
    Image.fromarray(ct_image).save(os.path.join(args.out, "ct-stent-contextual.png"))

    figure, axes = plt.subplots(1, 3, figsize=(12, 4.2), width_ratios=[1.2, 0.8, 1.35])
    axes[0].imshow(engine_image)
    axes[0].set_title("adaptive cutaway (Burns08)")
    axes[1].imshow(ct_image)
    axes[1].set_title("contextual cutaway of a CT")
    shown = axes[2].imshow(np.where(depth > 0, depth, np.nan), cmap="viridis")
    axes[2].set_title("engine: view depth AOV")
    figure.colorbar(shown, ax=axes[2], label="distance along the view axis")
    for a in axes:
        a.set_axis_off()
    figure.tight_layout()
    figure.savefig(os.path.join(args.out, "cutaway-figures.png"), dpi=100)
    print("wrote engine-cutaway.png, ct-stent-contextual.png and cutaway-figures.png to %s (%s)"
          % (args.out, engine.device))


if __name__ == "__main__":
    main()
