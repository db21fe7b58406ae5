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
import math
import numbers
import os
import statistics
import time as _time

import numpy as np

from ._cutaway import Error, Scene, live_contexts
from ._cutaway import Renderer as _NativeRenderer

__all__ = ["Error", "Scene", "Renderer", "Image", "load", "from_dict", "live_contexts"]


def load(path):
    """The scene file at `path` (docs/scene-format.md)."""
    path = os.fspath(path)
    if ("\0" if isinstance(path, str) else b"\0") in path:
        raise Error("%r: a file name cannot hold a NUL character" % path)
    return Scene.load(path)


def _json_default(value):
    # NumPy numbers and arrays inside a dict (a transfer function built with NumPy).
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError("%s is not a number, string, list or dict" % type(value).__name__)


def _check_finite(value, place, within=()):
    # JSON has no NaN or infinity: json.dumps would write them, and the parser would then
    # name a line and column of text the user never wrote. `within`: the containers around
    # `value`, so that one holding itself is named rather than recursed into.
    if isinstance(value, (float, np.floating)) and not math.isfinite(value):
        raise Error("<dict>: %s: %r is not a finite number" % (place or "/", float(value)))
    if isinstance(value, (dict, list, tuple)):
        if any(value is outer for outer in within):
            raise Error("<dict>: %s: holds itself (a cycle): JSON cannot write it" % (place or "/"))
        within = within + (value,)
    if isinstance(value, dict):
        for key, item in value.items():
            _check_finite(item, "%s/%s" % (place, key), within)
    elif isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            _check_finite(item, "%s/%d" % (place, i), within)
    elif isinstance(value, np.ndarray) and value.dtype.kind == "f" and not np.isfinite(value).all():
        at = tuple(int(i) for i in np.argwhere(~np.isfinite(value))[0])
        raise Error("<dict>: %s%s: %r is not a finite number"
                    % (place, "".join("/%d" % i for i in at), float(value[at])))


def _dumps(value):
    try:
        _check_finite(value, "")
        return json.dumps(value, default=_json_default, allow_nan=False)
    except RecursionError:
        raise Error("<dict>: nested deeper than Python's recursion limit") from None
    except (TypeError, ValueError) as e:
        raise Error("<dict>: %s" % e) from None


def _affine(place, spacing, origin, affine):
    """The row-major 4×4 voxel-index-to-world matrix as 16 numbers: `affine` itself (NiBabel's
    convention), or the diagonal of `spacing` moved to `origin`."""
    if affine is not None:
        if spacing is not None or origin is not None:
            raise Error("%s: give \"affine\" or \"spacing\" and \"origin\", not both" % place)
        matrix = np.asarray(affine, dtype=float)
        if matrix.shape != (4, 4):
            raise Error("%s: affine must be a 4×4 matrix, got shape %s" % (place, matrix.shape))
        return matrix.ravel().tolist()
    def vector(key, value):
        v = np.asarray(value, dtype=float)
        if v.shape != (3,):
            raise Error("%s: %s must be 3 numbers, got shape %s" % (place, key, v.shape))
        return v

    matrix = np.eye(4)
    if spacing is not None:
        matrix[:3, :3] = np.diag(vector("spacing", spacing))
    if origin is not None:
        matrix[:3, 3] = vector("origin", origin)
    return matrix.ravel().tolist()


def _object_with_arrays(entry, place, meshes):
    # An object entry with "vertices" and "faces" becomes "arrays": its JSON pointer, the
    # arrays going to the native parser under that key.
    if not (isinstance(entry, dict) and ("vertices" in entry or "faces" in entry)):
        return entry
    entry = dict(entry)
    if "vertices" not in entry or "faces" not in entry:
        raise Error("<dict>: %s: an object from arrays needs \"vertices\" and \"faces\"" % place)
    meshes[place] = (entry.pop("vertices"), entry.pop("faces"))
    return dict(entry, arrays=place)


def _volume_with_arrays(entry, place, volumes):
    # A volume entry with "values" (and "spacing", "origin" or "affine") likewise.
    if not (isinstance(entry, dict) and "values" in entry):
        return entry
    entry = dict(entry)
    affine = _affine("<dict>: " + place, entry.pop("spacing", None), entry.pop("origin", None),
                     entry.pop("affine", None))
    volumes[place] = (np.asarray(entry.pop("values")), affine)
    return dict(entry, arrays=place)


def from_dict(scene, base_dir="."):
    """A scene from a dict with the scene file's schema; relative file names resolve
    against `base_dir`. An object entry may give NumPy `vertices` (N, 3) and `faces` (M, 3)
    instead of a file, a volume entry `values` indexed [i, j, k] with `spacing` and `origin`
    or a 4×4 `affine` (docs/python.md)."""
    if not isinstance(scene, dict):
        raise Error("<dict>: expected a dict, got %s" % type(scene).__name__)
    scene, meshes, volumes = dict(scene), {}, {}
    for key, with_arrays, arrays in (("objects", _object_with_arrays, meshes),
                                     ("volumes", _volume_with_arrays, volumes)):
        if isinstance(scene.get(key), list):
            scene[key] = [with_arrays(entry, "/%s/%d" % (key, i), arrays)
                          for i, entry in enumerate(scene[key])]
    return Scene.parse(_dumps(scene), "<dict>", os.fspath(base_dir), meshes, volumes)


def _option_text(value):
    # The --set syntax: true/false, numbers, comma-separated vectors and colours, names.
    # NumPy scalars and 0-d arrays are their Python values.
    if isinstance(value, (np.generic, np.ndarray)) and np.ndim(value) == 0:
        value = value.item()
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple, np.ndarray)):
        return ",".join(repr(float(v)) for v in value)
    return str(value)


def _set(self, path, value):
    """Sets any technique's option by its scene-file path (`cutaway options` lists them)."""
    try:
        text = _option_text(value)
    except (TypeError, ValueError, OverflowError):  # a list of names, a number past a float
        raise Error("%s: expected a number, a name, true/false or a list of numbers, got %r"
                    % (path, value)) from None
    self._set_text(path, text)


def _add_volume(self, name, values, spacing=None, origin=None, affine=None, **entry):
    """A volume from a 3-D array indexed values[i, j, k] (transpose a [z, y, x] array), placed
    by `spacing` and `origin` or a 4×4 `affine` (voxel index to world); every other key of a
    "volumes" entry by its JSON name: transferFunction=[…], role="interest", mode=…"""
    if not isinstance(name, str):
        raise Error("add_volume: the name must be a string")
    place = "add_volume: " + name
    entry = dict(entry, name=name, arrays=name)
    self._add_volume(_dumps(entry), name, np.asarray(values),
                     _affine(place, spacing, origin, affine))


Scene.set = _set
Scene.add_volume = _add_volume


class Image(np.ndarray):
    """An RGBA uint8 frame that a notebook shows as a picture."""

    def __array_wrap__(self, array, context=None, return_scalar=False):
        # What arithmetic and reductions make of a frame is plain data: an ndarray, or a
        # number where the result has no axes.
        plain = np.asarray(array).view(np.ndarray)
        return plain[()] if plain.ndim == 0 else plain

    def _repr_png_(self):
        # Only a whole frame is a picture (a slice or a view of another type shows as an array).
        if self.dtype != np.uint8 or self.ndim != 3 or self.shape[2] != 4:
            return None
        from PIL import Image as PilImage
        out = io.BytesIO()
        PilImage.fromarray(np.ascontiguousarray(self), "RGBA").save(out, format="PNG")
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
        # float("2") would take a string; a bool is an int to Python but no time to a user.
        if isinstance(time, bool) or not isinstance(time, numbers.Real):
            raise Error("render: time: expected seconds as a number, got %s %r"
                        % (type(time).__name__, time))
        try:
            seconds = float(time)
        except OverflowError:  # an int past a float: as far outside the range as it gets
            seconds = math.inf
        self._aovs = None
        return self._native.render(seconds).view(Image)

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
        if isinstance(frames, bool) or not isinstance(frames, numbers.Integral) or frames < 1:
            raise Error("bench: frames: expected a whole number at least 1, got %r" % (frames,))
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
