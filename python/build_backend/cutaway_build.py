"""The build backend of `pip install .` (PEP 517), in the tree so that pip downloads nothing:
Debian 12 has no scikit-build-core. It builds the `_cutaway` module with the project's own
CMake (the same build as `cmake --build`) and packs it with python/cutaway/ into a wheel
whose metadata come from pyproject.toml.

Settings (`pip install --config-settings KEY=VALUE .`; Debian 12's pip 23.0 has no `-C`):
    build-dir=PATH  a CMake build folder to build in or reuse (default build/pip, kept between
                    installs so a second install only rebuilds what changed)
    jobs=N          parallel compile jobs (default: the number of CPUs)
"""
import base64
import hashlib
import os
import re
import subprocess
import sys
import sysconfig
import tomllib
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _project():
    # pyproject.toml's [project], with the version of CMakeLists.txt's project().
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        project = tomllib.load(f)["project"]
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        version = re.search(r"project\(cutaway VERSION ([0-9.]+)", f.read())
    return dict(project, version=version.group(1))


def _dist_info():
    project = _project()
    return "%s-%s.dist-info" % (project["name"], project["version"])


def _tag():
    # A CPython extension for this interpreter and platform: cp311-cp311-linux_x86_64.
    python = "cp%d%d" % sys.version_info[:2]
    return "%s-%s-%s" % (python, python,
                         sysconfig.get_platform().replace("-", "_").replace(".", "_"))


def _metadata_files():
    project = _project()
    lines = ["Metadata-Version: 2.1", "Name: " + project["name"],
             "Version: " + project["version"], "Summary: " + project["description"],
             "Requires-Python: " + project["requires-python"]]
    lines += ["Requires-Dist: " + d for d in project.get("dependencies", [])]
    metadata = "\n".join(lines) + "\n"
    wheel = ("Wheel-Version: 1.0\nGenerator: cutaway_build\nRoot-Is-Purelib: false\n"
             "Tag: %s\n" % _tag())
    return {"METADATA": metadata.encode(), "WHEEL": wheel.encode()}


def _build(settings):
    build = os.path.abspath(settings.get("build-dir") or os.path.join(ROOT, "build", "pip"))
    if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        # The module for the interpreter pip runs, whose tag the wheel carries.
        subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                        "-DCUTAWAY_PYTHON=ON", "-DCUTAWAY_BUILD_TESTS=OFF",
                        "-DPython3_EXECUTABLE=" + sys.executable], check=True,
                       stdout=sys.stderr)
    jobs = str(settings.get("jobs") or os.cpu_count() or 1)
    subprocess.run(["cmake", "--build", build, "--target", "_cutaway", "--parallel", jobs],
                   check=True, stdout=sys.stderr)
    return os.path.join(build, "python", "cutaway")


def _record_line(name, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (name, digest, len(data))


def get_requires_for_build_wheel(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    folder = os.path.join(metadata_directory, _dist_info())
    os.makedirs(folder, exist_ok=True)
    for name, data in _metadata_files().items():
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data)
    return _dist_info()


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    package = _build(config_settings or {})
    files = {}
    # This interpreter's module only (a reused build folder may hold another Python's too).
    for name in ("__init__.py", "_cutaway" + sysconfig.get_config_var("EXT_SUFFIX")):
        path = os.path.join(package, name)
        if not os.path.exists(path):
            raise RuntimeError("the build left no %s in %s (a build folder configured for "
                               "another Python?)" % (name, package))
        with open(path, "rb") as f:
            files["cutaway/" + name] = f.read()
    dist_info = _dist_info()
    for name, data in _metadata_files().items():
        files[dist_info + "/" + name] = data
    record = [_record_line(name, data) for name, data in files.items()]
    record.append(dist_info + "/RECORD,,")
    files[dist_info + "/RECORD"] = ("\n".join(record) + "\n").encode()
    project = _project()
    wheel = "%s-%s-%s.whl" % (project["name"], project["version"], _tag())
    with zipfile.ZipFile(os.path.join(wheel_directory, wheel), "w",
                         zipfile.ZIP_DEFLATED) as z:
        for name, data in files.items():
            z.writestr(name, data)
    return wheel
