"""`pip install .` (pyproject.toml and its in-tree backend, python/build_backend) into a new
virtual environment with pip offline, reusing the CTest build's CMake folder: the installed
package is the environment's, not the build tree's, and renders."""
import os
import subprocess
import sys

SOURCE = os.environ["CUTAWAY_SOURCE_DIR"]
BUILD = os.environ["CUTAWAY_BUILD_DIR"]


def test_pip_installs_the_package_offline(tmp_path):
    venv = tmp_path / "venv"
    # NumPy and Pillow come from Debian's packages, as docs/python.md says.
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)],
                   check=True)
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    install = subprocess.run(
        [str(venv / "bin" / "pip"), "install", "--no-index", "--no-cache-dir",
         "--config-settings", "build-dir=" + BUILD, SOURCE],
        env=env, capture_output=True, text=True)
    assert install.returncode == 0, install.stdout + install.stderr
    assert "Successfully installed cutaway-" in install.stdout
    check = ("import cutaway, numpy as np\n"
             "print(cutaway.__file__)\n"
             "scene = cutaway.from_dict({'resolution': [40, 30], 'samples': 1, 'objects': [\n"
             "    {'name': 'tri', 'vertices': np.eye(3), 'faces': [[0, 1, 2]]}]})\n"
             "image = cutaway.Renderer(scene).render()\n"
             "print(image.shape, int((image[:, :, :3] < 200).any(axis=2).sum()))\n")
    run = subprocess.run([str(venv / "bin" / "python"), "-c", check], env=env, cwd=tmp_path,
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    where, shape = run.stdout.splitlines()[:2]
    assert where.startswith(str(venv)), where
    assert shape.startswith("(30, 40, 4)") and int(shape.split()[-1]) > 50, shape
