"""cutaway from Python: scenes from files or dicts, frames and AOVs as NumPy arrays.

    import cutaway
    scene = cutaway.load("examples/engine-cutaway.json")
    scene.set("cutters.adaptive.angle", 30)        # any option by its scene-file path
    renderer = cutaway.Renderer(scene)
    image = renderer.render()                      # uint8 (height, width, 4), displays itself
    depth = renderer.aov("viewDepth")              # float32 (height, width)

Errors are cutaway.Error (a RuntimeError) with the CLI's one-line messages. docs/python.md.
"""
import io
import json
import os
import statistics
import time as _time

import numpy as np

from ._cutaway import Error, Scene, live_contexts
from ._cutaway import Renderer as _NativeRenderer

__all__ = ["Error", "Scene", "Renderer", "Image", "load", "from_dict", "live_contexts"]


def load(path):
    """The scene file at `path` (docs/scene-format.md)."""
    return Scene.load(os.fspath(path))


def from_dict(scene, base_dir="."):
    """A scene from a dict with the scene file's schema; relative file names resolve
    against `base_dir`."""
    return Scene.parse(json.dumps(scene), "<dict>", os.fspath(base_dir))


def _option_text(value):
    # The --set syntax: true/false, numbers, comma-separated vectors and colours, names.
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple, np.ndarray)):
        return ",".join(repr(float(v)) for v in value)
    return str(value)


def _set(self, path, value):
    """Sets any technique's option by its scene-file path (`cutaway options` lists them)."""
    self._set_text(path, _option_text(value))


Scene.set = _set


class Image(np.ndarray):
    """An RGBA uint8 frame that a notebook shows as a picture."""

    def _repr_png_(self):
        from PIL import Image as PilImage
        out = io.BytesIO()
        PilImage.fromarray(np.asarray(self), "RGBA").save(out, format="PNG")
        return out.getvalue()


class Renderer:
    """Renders a copy of `scene` on the process's headless OpenGL context (EGL), which is
    made with the first renderer and released with the last."""

    def __init__(self, scene):
        self._native = _NativeRenderer(scene)
        self._aovs = None  # the last frame's, read back once

    def _frame_aovs(self):
        if self._aovs is None:
            self._aovs = self._native.aovs()
        return self._aovs

    @property
    def device(self):
        """The OpenGL renderer string, e.g. llvmpipe."""
        return self._native.device

    def render(self, time=0.0):
        """One frame at `time` seconds: RGBA uint8, shape (height, width, 4), rows top down."""
        self._aovs = None
        return self._native.render(float(time)).view(Image)

    def aovs(self):
        """Every AOV of the last frame by name: float32, (height, width) or (height, width, 3),
        rows top down (the CLI's --aov PFMs, which are stored bottom up)."""
        return {name: array.copy() for name, array in self._frame_aovs().items()}

    def aov(self, name):
        """One AOV of the last frame by name."""
        aovs = self._frame_aovs()
        if name not in aovs:
            raise Error("no AOV \"%s\" in this frame (it has: %s)" % (name, ", ".join(aovs)))
        return aovs[name].copy()

    def timings(self):
        """The last frame's passes: [{"name", "gpu_ms", "cpu_ms"}]."""
        return self._native.timings()

    def bench(self, frames=10):
        """Renders one warm-up frame and `frames` timed ones; medians per pass and of the
        frame's wall time, in milliseconds, as `cutaway bench` reports them."""
        if frames < 1:
            raise Error("bench: frames must be at least 1")
        self._aovs = None
        self._native.render(0.0)
        walls, passes = [], {}
        for _ in range(frames):
            start = _time.perf_counter()
            self._native.render(0.0)
            walls.append((_time.perf_counter() - start) * 1000.0)
            for t in self._native.timings():
                passes.setdefault(t["name"], []).append(t["gpu_ms"])
        return {"device": self.device, "frames": frames,
                "frame_ms": {"median": statistics.median(walls), "min": min(walls),
                             "max": max(walls)},
                "passes_gpu_ms": {k: statistics.median(v) for k, v in passes.items()}}
