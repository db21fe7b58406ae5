"""Scenes given as NumPy arrays (python/cutaway: from_dict's "vertices"/"faces" and "values",
Scene.add_volume) against the same data read from files by the library's own importers:
equal frames and AOVs, whatever the array's layout, byte order or dtype, and bad arrays
refused with a message naming the entry."""
import json
import os
import subprocess

import numpy as np
import pytest

import cutaway
from test_module import CLI, CUBE_FACES, CUBE_VERTICES, cube_scene

SPACING, ORIGIN = [0.5, 0.75, 1.0], [-6.0, -7.5, -8.0]
TRANSFER = [{"value": 200, "color": [0.2, 0.4, 0.9], "opacity": 0.0},
            {"value": 900, "color": [0.9, 0.5, 0.3], "opacity": 0.5, "importance": 0.9}]


def blob():
    # Values indexed [i, j, k] (24 × 20 × 16): an off-centre ellipsoid with a ramp along i, so
    # that any axis swapped or flipped changes the picture.
    i, j, k = np.meshgrid(np.arange(24), np.arange(20), np.arange(16), indexing="ij")
    r = np.sqrt(((i - 14) / 7.0) ** 2 + ((j - 9) / 6.0) ** 2 + ((k - 7) / 5.0) ** 2)
    return (1000 * np.exp(-r ** 2) + 10 * i).astype(np.int16)


def volume_scene(entry):
    return {"resolution": [72, 54], "samples": 1,
            "camera": {"eye": [14, 10, 18], "target": [0, 0, 0], "fov": 40},
            "volumes": [dict({"name": "blob", "transferFunction": TRANSFER, "jitter": False},
                             **entry)]}


@pytest.fixture(scope="module")
def from_file(tmp_path_factory):
    # The blob as raw big-endian voxels (i fastest) behind a JSON header with its spacing and
    # origin, read by the library's importer.
    folder = tmp_path_factory.mktemp("raw")
    (folder / "blob.raw").write_bytes(blob().astype(">i2").tobytes(order="F"))
    (folder / "blob.json").write_text(json.dumps(
        {"file": "blob.raw", "dims": [24, 20, 16], "type": "i16", "spacing": SPACING,
         "origin": ORIGIN, "endianness": "big"}))
    renderer = cutaway.Renderer(cutaway.from_dict(volume_scene({"file": str(folder / "blob.json")})))
    return renderer.render(), renderer.aovs()


def check_equal(scene, expected):
    renderer = cutaway.Renderer(scene)
    image, aovs = expected
    assert (renderer.render() == image).all()
    got = renderer.aovs()
    assert set(got) == set(aovs)
    for name in aovs:
        np.testing.assert_array_equal(got[name], aovs[name], err_msg=name)
    return renderer


@pytest.mark.parametrize("layout", ["c", "fortran", "reversed", "big-endian", "float64",
                                    "fortran-big-endian"])
def test_a_volume_from_an_array_is_the_volume_from_its_file(from_file, layout):
    values = blob()
    values = {"c": values,
              "fortran": np.asfortranarray(values),
              "reversed": values[::-1].copy()[::-1],  # negative strides along i
              "big-endian": values.astype(">i2"),
              "float64": values.astype(np.float64),
              # rows along i converted whole, each byte-swapped
              "fortran-big-endian": np.asfortranarray(values.astype(">i2"))}[layout]
    renderer = check_equal(cutaway.from_dict(volume_scene(
        {"values": values, "spacing": SPACING, "origin": ORIGIN})), from_file)
    covered = (renderer.aov("volumeOpacity") > 0.05).mean()
    assert 0.1 < covered < 0.9  # the blob is in the frame, not all of it


def test_an_affine_places_it_as_spacing_and_origin_do(from_file):
    affine = np.diag(SPACING + [1.0])
    affine[:3, 3] = ORIGIN
    check_equal(cutaway.from_dict(volume_scene({"values": blob(), "affine": affine})), from_file)


def test_add_volume_is_the_dict_entry(from_file):
    scene = cutaway.from_dict(cube_scene(cutters={}))
    scene.add_volume("blob", blob(), spacing=SPACING, origin=ORIGIN,
                     transferFunction=TRANSFER, jitter=False)
    dict_scene = cube_scene(cutters={})
    dict_scene["volumes"] = [{"name": "blob", "values": blob(), "spacing": SPACING,
                              "origin": ORIGIN, "transferFunction": TRANSFER, "jitter": False}]
    expected = cutaway.Renderer(cutaway.from_dict(dict_scene))
    check_equal(scene, (expected.render(), expected.aovs()))
    assert scene.objects == ["outer", "inner"] and scene.volumes == ["blob"]
    assert scene.set_role("blo.", "interest") == 1  # volumes by name


def test_a_scene_of_arrays_alone_draws_as_its_files():
    expected = cutaway.Renderer(cutaway.from_dict(cube_scene())).render()
    scene = cube_scene()
    for o in scene["objects"]:
        del o["file"]
        o["vertices"], o["faces"] = CUBE_VERTICES, CUBE_FACES
    image = cutaway.Renderer(cutaway.from_dict(scene)).render()
    differ = np.abs(image.astype(int) - expected.astype(int)).max(axis=2) > 2
    assert differ.mean() < 0.005, differ.sum()


@pytest.mark.parametrize("entry,message", [
    ({"values": np.zeros((4, 4))}, "/volumes/0: values must be a 3-D array, got 2 dimensions"),
    ({"values": np.zeros((2, 2, 2), complex)}, "/volumes/0: unsupported voxel type 'c128'"),
    ({"values": np.zeros((2, 2, 2), bool)}, "/volumes/0: unsupported voxel type 'b8'"),
    ({"values": np.zeros((0, 2, 2))}, r"/volumes/0: dims must be positive, got 0×2×2"),
    ({"values": np.zeros((2, 2, 2)), "affine": np.diag([1, 0, 1, 1])}, "transform is singular"),
    ({"values": np.zeros((2, 2, 2)), "spacing": [1, np.inf, 1]}, "transform is not finite"),
    ({"values": np.zeros((2, 2, 2)), "spacing": [1, 2]}, "spacing must be 3 numbers"),
    ({"values": np.zeros((2, 2, 2)), "affine": np.eye(3)}, "affine must be a 4×4 matrix"),
    ({"values": np.zeros((2, 2, 2)), "affine": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0],
                                                [0, 0, 0.5, 1]]}, "last row is not 0 0 0 1"),
    ({"values": np.zeros((2, 2, 2)), "affine": np.eye(4), "origin": [0, 0, 0]},
     "give \"affine\" or \"spacing\" and \"origin\", not both"),
    ({"values": np.zeros((2, 2, 2)), "file": "x.nii"}, "one of \"file\" or \"arrays\", not both"),
    ({"values": np.zeros((2, 2, 2)), "mode": "isosurface"}, "needs an \"isoValue\""),
])
def test_bad_volume_arrays_are_refused(entry, message):
    with pytest.raises(cutaway.Error, match="<dict>: .*" + message):
        cutaway.from_dict(volume_scene(entry))


def test_bad_mesh_arrays_are_refused_and_add_volume_leaves_the_scene(tmp_path):
    scene = cube_scene()
    scene["objects"][0] = {"name": "outer", "vertices": CUBE_VERTICES}
    with pytest.raises(cutaway.Error, match="<dict>: /objects/0: an object from arrays needs"):
        cutaway.from_dict(scene)
    scene["objects"][0]["faces"] = CUBE_FACES + 1
    with pytest.raises(cutaway.Error, match="<dict>: /objects/0: face 3 has vertex index 8"):
        cutaway.from_dict(scene)
    scene["objects"][0]["faces"] = [["a", "b", "c"]]
    with pytest.raises(cutaway.Error, match="faces must be integers of shape"):
        cutaway.from_dict(scene)
    cubes = cutaway.from_dict(cube_scene())
    with pytest.raises(cutaway.Error, match="add_volume: .*the name \"inner\" is taken"):
        cubes.add_volume("inner", blob(), transferFunction=TRANSFER)
    with pytest.raises(cutaway.Error, match=r"add_volume: /transferFunction/0/opacity: value 3"):
        cubes.add_volume("v", blob(), transferFunction=[{"value": 1, "opacity": 3}])
    with pytest.raises(cutaway.Error, match=r"add_volume: /colour: unknown key"):
        cubes.add_volume("v", blob(), transferFunction=TRANSFER, colour=1)
    assert cubes.volumes == []
    # A scene file cannot name arrays: only the Python module gives them.
    file = tmp_path / "arrays.json"
    file.write_text(json.dumps({"objects": [{"name": "a", "arrays": "/objects/0"}]}))
    cli = subprocess.run([CLI, "info", str(file)], capture_output=True, text=True)
    assert cli.returncode != 0
    assert "/objects/0/arrays: no arrays named \"/objects/0\" were given" in cli.stderr


def test_numpy_numbers_in_a_dict_are_numbers():
    scene = cube_scene()
    scene["cutters"]["adaptive"]["angle"] = np.float32(20)
    scene["objects"][1]["color"] = np.array([0.9, 0.3, 0.2])
    cutaway.from_dict(scene)
    with pytest.raises(cutaway.Error, match="<dict>: .*object is not a number"):
        cutaway.from_dict(dict(cube_scene(), samples=object()))
