"""The Python module (python/cutaway) against the CLI on the same scenes: frames and AOVs
equal to what `cutaway render` writes, options by their scene-file paths, errors as
cutaway.Error with the CLI's messages, and the shared context released with the last
renderer. Run by CTest (Python.Module) with PYTHONPATH at the build tree's python/."""
import json
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest
from PIL import Image as PilImage

import cutaway

CLI = os.environ["CUTAWAY_BINARY"]
DATA = os.environ["CUTAWAY_TEST_DATA"]
CUBE = os.path.join(DATA, "meshes", "cube.obj")


def cube_scene(**extra):
    # Two unit cubes ([0, 1]³) centred, the small one of interest inside the big one, cut by
    # the adaptive cutaway.
    scene = {"resolution": [80, 60], "samples": 1,
             "camera": {"eye": [3, 2.5, 4], "target": [0, 0, 0], "fov": 40},
             "objects": [{"name": "outer", "file": CUBE, "role": "context",
                          "transform": {"scale": 1.5, "translate": [-0.75, -0.75, -0.75]}},
                         {"name": "inner", "file": CUBE, "role": "interest",
                          "transform": {"scale": 0.7, "translate": [-0.35, -0.35, -0.35]},
                          "color": [0.9, 0.3, 0.2]}],
             "cutters": {"adaptive": {"angle": 35}}}
    scene.update(extra)
    return scene


def read_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        width, height = map(int, f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    channels = 3 if kind == b"PF" else 1
    image = data.reshape(height, width, channels)[::-1]  # PFM rows run bottom up
    return image[:, :, 0] if channels == 1 else image


def test_frame_and_aovs_equal_the_clis(tmp_path):
    scene_file = tmp_path / "cubes.json"
    scene_file.write_text(json.dumps(cube_scene()))
    subprocess.run([CLI, "render", str(scene_file), "-o", str(tmp_path / "cli.png"),
                    "--aov", str(tmp_path / "aovs")], check=True, capture_output=True)
    renderer = cutaway.Renderer(cutaway.load(scene_file))
    image = renderer.render()
    assert image.shape == (60, 80, 4) and image.dtype == np.uint8
    cli = np.asarray(PilImage.open(tmp_path / "cli.png").convert("RGBA"))
    assert np.array_equal(image, cli)
    aovs = renderer.aovs()
    pfms = {p[:-4] for p in os.listdir(tmp_path / "aovs") if p.endswith(".pfm")}
    assert {"depth", "normal", "position", "objectId", "cutawayDepth"} <= set(aovs)
    assert pfms == set(aovs)
    for name, array in aovs.items():
        assert array.dtype == np.float32
        np.testing.assert_array_equal(array, read_pfm(tmp_path / "aovs" / (name + ".pfm")),
                                      err_msg=name)
    # The AOVs are the frame's: the inner cube is seen through the cut.
    assert (renderer.aov("objectId") == 1).sum() > 50


def test_a_dict_scene_and_options_by_path():
    renderer = cutaway.Renderer(cutaway.from_dict(cube_scene()))
    narrow = renderer.render()
    scene = cutaway.from_dict(cube_scene())
    scene.set("cutters.adaptive.angle", 10)
    scene.set("style.lines.color", [1, 0, 0])
    wide = cutaway.Renderer(scene).render()
    assert not np.array_equal(narrow, wide)
    red = (wide[:, :, 0] == 255) & (wide[:, :, 1] == 0) & (wide[:, :, 2] == 0)
    assert red.sum() > 20  # the feature lines, now red
    assert scene.objects == ["outer", "inner"] and (scene.width, scene.height) == (80, 60)
    assert scene.set_importance("in.*", 0.8) == 1


def test_bad_input_raises_the_clis_messages(tmp_path):
    with pytest.raises(cutaway.Error, match="no-such.json: cannot open scene file"):
        cutaway.load(tmp_path / "no-such.json")
    with pytest.raises(cutaway.Error, match=r"<dict>: /colour: unknown key \"colour\""):
        cutaway.from_dict(dict(cube_scene(), colour=1))
    scene = cutaway.from_dict(cube_scene())
    with pytest.raises(cutaway.Error, match=r"value 95 is outside \[0, 90\]"):
        scene.set("cutters.adaptive.angle", 95)
    with pytest.raises(cutaway.Error, match="no such option"):
        scene.set("cutters.adaptive.angel", 30)
    renderer = cutaway.Renderer(scene)
    renderer.render()
    with pytest.raises(cutaway.Error, match="no AOV \"nope\""):
        renderer.aov("nope")
    assert issubclass(cutaway.Error, RuntimeError)


def test_the_pixel_error_comes_from_the_scene():
    assert cutaway.from_dict(cube_scene()).pixel_error == 0.5
    assert cutaway.from_dict(dict(cube_scene(), pixelError=2)).pixel_error == 2.0
    with pytest.raises(cutaway.Error, match=r"/pixelError: value -1 is outside \[0, 100\]"):
        cutaway.from_dict(dict(cube_scene(), pixelError=-1))


def test_the_context_goes_with_the_last_renderer():
    scene = cutaway.from_dict(cube_scene(cutters={}))
    fds = len(os.listdir("/proc/self/fd"))
    for _ in range(100):
        renderer = cutaway.Renderer(scene)
        assert cutaway.live_contexts() == 1
        renderer.render()
        del renderer
        assert cutaway.live_contexts() == 0
    assert len(os.listdir("/proc/self/fd")) <= fds + 2


def test_renderers_work_from_any_thread():
    # The context is current on the calling thread for each call: a frame, a second renderer
    # and the last reference dropped in other threads (each aborted in libepoxy before).
    scene = cutaway.from_dict(cube_scene())
    renderer = cutaway.Renderer(scene)
    expected = renderer.render()
    results = {}

    def elsewhere():
        results["same"] = renderer.render()
        second = cutaway.Renderer(scene)
        results["second"] = second.render()
        results["aovs"] = sorted(second.aovs())
        del second

    worker = threading.Thread(target=elsewhere)
    worker.start()
    worker.join()
    assert np.array_equal(results["same"], expected)
    assert np.array_equal(results["second"], expected)
    assert "objectId" in results["aovs"]
    dropper = threading.Thread(target=lambda r=[renderer]: r.clear())
    del renderer
    dropper.start()
    dropper.join()
    assert cutaway.live_contexts() == 0
    assert np.array_equal(cutaway.Renderer(scene).render(), expected)


def test_a_forked_child_is_told_its_context_did_not_come_along():
    # fork() with a renderer alive (multiprocessing's default on Linux): the child's first
    # OpenGL call waited forever for the driver's threads, which stay in the parent.
    scene = cutaway.from_dict(cube_scene())
    renderer = cutaway.Renderer(scene)
    renderer.render()
    read, write = os.pipe()
    child = os.fork()
    if child == 0:
        os.close(read)
        try:
            cutaway.Renderer(scene)
            message = "made a renderer"
        except cutaway.Error as e:
            message = str(e)
        try:
            renderer.render()
        except cutaway.Error as e:
            message += "\n" + str(e)
        os.write(write, message.encode())
        os._exit(0)
    os.close(write)
    deadline = time.monotonic() + 60
    while os.waitpid(child, os.WNOHANG) == (0, 0):
        if time.monotonic() > deadline:
            os.kill(child, signal.SIGKILL)
            os.waitpid(child, 0)
            pytest.fail("the forked child hung")
        time.sleep(0.05)
    with os.fdopen(read) as pipe:
        lines = pipe.read().splitlines()
    assert len(lines) == 2, lines
    assert all("the OpenGL driver does not survive fork()" in line for line in lines), lines
    renderer.render()  # the parent's renderer goes on


FORK_AFTER_THE_LAST = """
import os, sys
import cutaway

scene = cutaway.from_dict({"resolution": [24, 18], "samples": 1,
                           "camera": {"eye": [2, 1.5, 3], "target": [0.5, 0.5, 0.5], "fov": 40},
                           "objects": [{"name": "m", "file": sys.argv[1]}]})
cutaway.Renderer(scene).render()
assert cutaway.live_contexts() == 0
child = os.fork()
if child == 0:
    try:
        cutaway.Renderer(scene).render()
        print("rendered")
    except cutaway.Error as e:
        print(e)
    sys.stdout.flush()
    os._exit(0)
os.waitpid(child, 0)
"""


def test_a_child_forked_after_the_last_renderer_is_refused_too(tmp_path):
    # llvmpipe keeps its threads and screen after the last context is gone: a child forked
    # then waited forever in its first frame.
    script = tmp_path / "fork.py"
    script.write_text(FORK_AFTER_THE_LAST)
    run = subprocess.run(["/usr/bin/python3", str(script), CUBE], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    assert "the OpenGL driver does not survive fork()" in run.stdout, run.stdout


def test_instances_made_without_init_are_refused():
    # Scene.__new__ gave a scene of unset memory (garbage sizes, segmentation faults), and so
    # did the native renderer's.
    with pytest.raises(TypeError, match="cutaway.load"):
        cutaway.Scene.__new__(cutaway.Scene)
    bare = cutaway._cutaway.Renderer.__new__(cutaway._cutaway.Renderer)
    for call in (lambda: bare.render(0.0), bare.aovs, bare.timings, lambda: bare.device):
        with pytest.raises(TypeError, match="not made by Renderer"):
            call()


def test_an_error_message_keeps_bytes_that_are_not_utf8(tmp_path):
    path = tmp_path / "latin1.json"
    path.write_bytes(b'{"objects": [{"name": "caf\xe9", "file": "x.obj"}]}')
    with pytest.raises(cutaway.Error) as raised:
        cutaway.load(str(path))
    assert str(raised.value), "the message was empty"
    assert str(path) in str(raised.value)


def test_a_memory_error_while_an_array_converts_stays_one():
    class Exhausting:
        def __array__(self, *args, **kwargs):
            raise MemoryError("no room")

    scene = cutaway.from_dict(cube_scene())
    with pytest.raises(MemoryError, match="no room"):
        scene.add_mesh("m", Exhausting(), np.array([[0, 1, 2]]))
    assert scene.objects == ["outer", "inner"]


FORK_POOL = """
import hashlib, multiprocessing as mp, sys
import cutaway

FILES = sys.argv[1:]

def frame(path):
    scene = cutaway.from_dict({"resolution": [24, 18], "samples": 1,
                               "camera": {"eye": [2, 1.5, 3], "target": [0.5, 0.5, 0.5], "fov": 40},
                               "objects": [{"name": "m", "file": path}]})
    return hashlib.md5(cutaway.Renderer(scene).render().tobytes()).hexdigest()

def work(i):
    path = FILES[i % len(FILES)]
    try:
        return path, frame(path)
    except cutaway.Error as e:
        return path, "error: " + str(e)

if __name__ == "__main__":
    with mp.get_context("fork").Pool(4) as pool:
        got = pool.map(work, range(16))
    reference = {path: frame(path) for path in FILES}
    for path, digest in got:
        if digest != reference[path]:
            print(path, digest)
"""


def test_forked_workers_read_their_own_files(tmp_path):
    # A worker pool forked from a process whose mesh importer's helper was running: the
    # workers shared its socket and read each other's meshes (or "the importer crashed").
    script = tmp_path / "pool.py"
    script.write_text(FORK_POOL)
    files = [CUBE, os.path.join(DATA, "meshes", "tetra.obj")]
    run = subprocess.run(["/usr/bin/python3", str(script)] + files, capture_output=True,
                         text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert run.stdout == "", run.stdout


def test_a_number_json_cannot_hold_is_named_by_its_place():
    camera = dict(cube_scene()["camera"], fov=float("nan"))
    with pytest.raises(cutaway.Error, match=r"^<dict>: /camera/fov: nan is not a finite number$"):
        cutaway.from_dict(cube_scene(camera=camera))
    camera = dict(cube_scene()["camera"], eye=np.array([3.0, np.inf, 4.0]))
    with pytest.raises(cutaway.Error, match=r"^<dict>: /camera/eye/1: inf is not a finite number$"):
        cutaway.from_dict(cube_scene(camera=camera))
    # A dict that holds itself, and one nested past the recursion limit: named, not a
    # RecursionError.
    scene = cube_scene()
    scene["camera"]["self"] = scene["camera"]
    with pytest.raises(cutaway.Error, match=r"^<dict>: /camera/self: holds itself \(a cycle\)"):
        cutaway.from_dict(scene)
    deep = cube_scene()
    for _ in range(100000):
        deep = {"objects": deep}
    with pytest.raises(cutaway.Error, match=r"^<dict>: nested deeper than Python's recursion limit$"):
        cutaway.from_dict(deep)


def test_a_frame_comes_first_and_its_time_is_checked():
    renderer = cutaway.Renderer(cutaway.from_dict(cube_scene()))
    with pytest.raises(cutaway.Error, match=r"aovs: no frame yet: call render\(\) first"):
        renderer.aovs()
    with pytest.raises(cutaway.Error, match=r"timings: no frame yet"):
        renderer.timings()
    for bad in (float("nan"), -1, 1e300, 10**400):
        with pytest.raises(cutaway.Error, match=r"render: time: expected seconds in \[0, 1e6\]"):
            renderer.render(bad)
    for bad in ("2", b"2", True, None, [1.0]):
        with pytest.raises(cutaway.Error, match=r"render: time: expected seconds as a number"):
            renderer.render(bad)
    renderer.render(2.5)
    renderer.render(np.float32(1.5))
    assert "objectId" in renderer.aovs()


def test_the_frame_shows_itself_and_bench_reports_figures():
    renderer = cutaway.Renderer(cutaway.from_dict(cube_scene()))
    frame = renderer.render()
    png = frame._repr_png_()
    assert png.startswith(b"\x89PNG")
    # The first frame's pass times: believable or unknown (llvmpipe's first query gave the
    # time since boot).
    for t in renderer.timings():
        assert np.isnan(t["gpu_ms"]) or t["gpu_ms"] < 60_000, t
    # What arithmetic and reductions make of a frame is plain data, not a picture of raw bytes.
    assert type(frame / 255.0) is np.ndarray and type(frame[..., 3] > 0) is np.ndarray
    assert not isinstance(frame.sum(), np.ndarray) and frame.sum() == frame.view(np.ndarray).sum()
    for bad in (0, 2.5, "3", True):
        with pytest.raises(cutaway.Error, match=r"bench: frames: expected a whole number"):
            renderer.bench(frames=bad)
    figures = renderer.bench(frames=2)
    assert figures["frames"] == 2 and figures["frame_ms"]["median"] > 0
    assert "geometry" in figures["passes_gpu_ms"] and figures["device"]


def test_a_nul_in_an_argument_is_shown_not_the_end_of_the_message():
    scene = cutaway.from_dict(cube_scene())
    with pytest.raises(cutaway.Error) as e:
        scene.set("cutters.adaptive.angle\0x", 30)
    assert "cutters.adaptive.angle\\0x" in str(e.value) and len(str(e.value)) > 30, str(e.value)
    with pytest.raises(cutaway.Error, match="cannot hold a NUL"):
        cutaway.load("/tmp/x\0.json")
    # In a value too, which the message quotes whole, and the choices after it.
    with pytest.raises(cutaway.Error) as e:
        scene.set("style.name", "gooch\0x")
    assert 'unknown value "gooch\\0x" (expected one of' in str(e.value), str(e.value)


def test_a_value_python_cannot_turn_into_text_is_named():
    scene = cutaway.from_dict(cube_scene())
    for bad in (["gooch"], [10**400, 0, 0]):
        with pytest.raises(cutaway.Error, match=r"style.name: expected a number, a name"):
            scene.set("style.name", bad)


def test_numpy_values_set_options():
    scene = cutaway.from_dict(cube_scene())
    scene.set("cutters.adaptive.outlines", np.False_)
    scene.set("cutters.adaptive.angle", np.array(30.0))
    scene.set("cutters.adaptive.angle", np.float32(25.0))
    changed = cutaway.from_dict(cube_scene())
    changed.set("cutters.adaptive.outlines", False)
    changed.set("cutters.adaptive.angle", 25.0)
    assert np.array_equal(cutaway.Renderer(scene).render(), cutaway.Renderer(changed).render())


CUBE_VERTICES = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                          [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], dtype=np.float64)
# tests/data/meshes/cube.obj's faces, 0-based: counter-clockwise seen from outside.
CUBE_FACES = np.array([[0, 3, 2], [0, 2, 1], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                       [3, 7, 6], [3, 6, 2], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]])


def test_a_numpy_mesh_is_the_same_object_as_its_file():
    from_files = cutaway.Renderer(cutaway.from_dict(cube_scene()))
    expected = from_files.render()
    # The outer cube from arrays instead of cube.obj (a scene needs one object of its own).
    base = cube_scene()
    base["objects"] = [base["objects"][1]]
    scene = cutaway.from_dict(base)
    scene.add_mesh("outer", CUBE_VERTICES * 1.5 - 0.75, CUBE_FACES)
    renderer = cutaway.Renderer(scene)
    image = renderer.render()
    differ = np.abs(image.astype(int) - expected.astype(int)).max(axis=2) > 2
    assert differ.mean() < 0.005, differ.sum()
    # Every visible point of its surface (not of its cut) lies on the cube: one coordinate at
    # ±0.75.
    position, ids = renderer.aov("position"), renderer.aov("objectId")
    on = position[(ids == 1) & (renderer.aov("cutMask") == 0)]
    assert len(on) > 200
    assert np.all(np.abs(np.abs(on) - 0.75).min(axis=1) < 1e-4)
    assert np.all(np.abs(on) <= 0.75 + 1e-4)


def test_a_bad_numpy_mesh_is_refused():
    scene = cutaway.from_dict(cube_scene())
    with pytest.raises(cutaway.Error, match=r"add_mesh: m: face 1 has vertex index 8 out of "
                                            r"range \(8 vertices\)"):
        scene.add_mesh("m", CUBE_VERTICES, np.array([[0, 1, 2], [0, 2, 8]]))
    with pytest.raises(cutaway.Error, match=r"vertices must be real numbers of shape \(N, 3\)"):
        scene.add_mesh("m", CUBE_VERTICES[:, :2], CUBE_FACES)
    # Kinds that a cast would take silently: 0.5 as index 0, a complex number as its real part,
    # 2⁶³ as −2⁶³.
    with pytest.raises(cutaway.Error, match=r"faces must be integers of shape \(M, 3\)"):
        scene.add_mesh("m", CUBE_VERTICES, CUBE_FACES + 0.5)
    with pytest.raises(cutaway.Error, match=r"vertices must be real numbers"):
        scene.add_mesh("m", CUBE_VERTICES + 1j, CUBE_FACES)
    huge = CUBE_FACES.astype(np.uint64)
    huge[2, 1] = 2**63
    with pytest.raises(cutaway.Error, match=r"face 2 has vertex index 9223372036854775808 out"):
        scene.add_mesh("m", CUBE_VERTICES, huge)
    with pytest.raises(cutaway.Error, match=r"face 0 has vertex index -1 out of range"):
        scene.add_mesh("m", CUBE_VERTICES, np.array([[-1, 1, 2]]))
    # What a scene file's reader refuses: colours outside [0, 1], names too long or with NUL.
    for color in ([2, 0, 0], [-5, 0, 0], [np.nan, 0, 0]):
        with pytest.raises(cutaway.Error, match=r"\"m\" has the colour .* outside \[0, 1\]"):
            scene.add_mesh("m", CUBE_VERTICES, CUBE_FACES, color=color)
    with pytest.raises(cutaway.Error, match=r"an object name of 2000 characters \(1 to 1024\)"):
        scene.add_mesh("m" * 2000, CUBE_VERTICES, CUBE_FACES)
    with pytest.raises(cutaway.Error, match=r"an object name holds a NUL character \(at 1\)"):
        scene.add_mesh("a\0b", CUBE_VERTICES, CUBE_FACES)
    bad = CUBE_VERTICES.copy()
    bad[3, 1] = np.nan
    with pytest.raises(cutaway.Error, match="vertex 3 is not finite"):
        scene.add_mesh("m", bad, CUBE_FACES)
    with pytest.raises(cutaway.Error, match="add_mesh: /objects: two objects are named \"inner\""):
        scene.add_mesh("inner", CUBE_VERTICES, CUBE_FACES)
    with pytest.raises(cutaway.Error, match="unknown role \"inside\""):
        scene.add_mesh("m", CUBE_VERTICES, CUBE_FACES, role="inside")
    assert scene.objects == ["outer", "inner"]  # nothing half-added
    scene.add_mesh("m", CUBE_VERTICES, CUBE_FACES, role="interest", color=[0.1, 0.8, 0.2])
    assert scene.objects == ["outer", "inner", "m"]


def test_roles_by_pattern():
    scene = cutaway.from_dict(cube_scene())
    renderer = cutaway.Renderer(scene)
    renderer.render()
    assert (renderer.aov("objectId") == 1).sum() > 50  # the inner cube through the cut
    assert scene.set_role("out.*", "interest") == 1
    renderer = cutaway.Renderer(scene)
    renderer.render()
    # The outer cube, now of interest too, is not cut: it hides the inner one.
    assert (renderer.aov("objectId") == 1).sum() == 0
    with pytest.raises(cutaway.Error, match="unknown role \"inside\""):
        scene.set_role("inner", "inside")
    with pytest.raises(cutaway.Error,
                       match="^set_role: nope: matches no object's name or group, nor a"):
        scene.set_role("nope", "context")
    with pytest.raises(cutaway.Error, match=r"^set_role: invalid regular expression \"\(\""):
        scene.set_role("(", "context")
    with pytest.raises(cutaway.Error, match=r"^set_importance: invalid regular expression"):
        scene.set_importance("(", 0.5)
    # Checked as a scene file is: the cutout needs an exterior object.
    cutout = cube_scene(cutters={"cutout": {}})
    cutout["objects"][0]["role"] = "exterior"
    cutout["objects"][1]["role"] = "interior"
    scene = cutaway.from_dict(cutout)
    with pytest.raises(cutaway.Error, match="set_role: /cutters/cutout: no object has role "
                                            "\"exterior\""):
        scene.set_role("outer", "context")
    assert scene.objects == ["outer", "inner"]
    assert scene.set_role("outer", "exterior") == 1
