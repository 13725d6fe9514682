"""`pip install .` and `pip wheel .` from the source tree (setup.py, pyproject.toml; docs/python.md):
offline with Debian's setuptools (--no-build-isolation --no-index), into a fresh virtual
environment that sees the system's numpy (--system-site-packages); the package is imported from
another folder with no PYTHONPATH, from the environment's site-packages, and runs a rig given as a
dict. The C++ core is the CMake build tree's (METROSYNC_CMAKE_BUILD_DIR), brought up to date, not
built again: ctest runs this after the build."""
import json
import os
import re
import subprocess
import sys
import zipfile

import pytest

SRC = os.path.abspath(os.environ["METROSYNC_SOURCE_DIR"])
BUILD = os.path.abspath(os.environ["METROSYNC_CMAKE_BUILD_DIR"])
SYSTEM_PYTHON = sys.executable  # the interpreter the build tree's module was made for

RIG = {"units": "scaled", "name": "from-a-dict", "epsilon": 0.05,
       "platform": {"friction": {"law": "coulomb", "mu": 0.3}},
       "metronomes": [{"nu": 0.5, "J": 2.0, "theta_c": 0.9, "start": {"A": 2.0, "phi": 0.0}},
                      {"nu": 0.5, "J": 2.0, "theta_c": 0.9, "start": {"A": 2.0, "phi": 3.0}}],
       "simulation": {"tau": 30}}


def pip(scratch, *args):
    env = dict(os.environ, METROSYNC_CMAKE_BUILD_DIR=BUILD,
               METROSYNC_BUILD_BASE=str(scratch / "setuptools"), PIP_NO_CACHE_DIR="1")
    env.pop("PYTHONPATH", None)
    done = subprocess.run([SYSTEM_PYTHON, "-m", "pip", *args, "--no-build-isolation",
                           "--no-index", "--disable-pip-version-check", SRC],
                          cwd=scratch, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return done


@pytest.fixture(scope="module")
def scratch(tmp_path_factory):
    return tmp_path_factory.mktemp("pip")


@pytest.fixture(scope="module")
def venv(scratch):
    """A fresh environment with the package installed by `pip install .`."""
    subprocess.run([SYSTEM_PYTHON, "-m", "venv", "--system-site-packages", "--without-pip",
                    str(scratch / "venv")], check=True)
    python = scratch / "venv" / "bin" / "python"
    pip(scratch, "--python", str(python), "install")
    return python


def test_pip_install_gives_a_module_importable_from_elsewhere(venv, scratch):
    elsewhere = scratch / "elsewhere"
    elsewhere.mkdir()
    code = ("import json, metrosync\n"
            "r = metrosync.run(json.loads(%r), model='slow')\n"
            "print(json.dumps({'file': metrosync.__file__, 'version': metrosync.version(),\n"
            "                  'regime': r.regime, 'rows': len(r.envelope['tau'])}))\n"
            % json.dumps(RIG))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run([str(venv), "-c", code], cwd=elsewhere, env=env, capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    got = json.loads(done.stdout)
    site = str(scratch / "venv" / "lib")
    assert got["file"].startswith(site), got["file"]  # not the build tree, not the sources
    assert got["rows"] > 10 and got["regime"]
    cmake = open(os.path.join(SRC, "CMakeLists.txt")).read()
    assert got["version"] == re.search(r"project\(metrosync VERSION ([0-9.]+)", cmake).group(1)
    pyproject = open(os.path.join(SRC, "pyproject.toml")).read()
    assert re.search(r'^version = "([0-9.]+)"', pyproject, re.M).group(1) == got["version"]


def test_pip_wheel_builds_a_wheel_with_the_module_and_its_stubs(scratch):
    pip(scratch, "wheel", "--no-deps", "-w", str(scratch / "dist"))
    wheels = list((scratch / "dist").glob("metrosync-*.whl"))
    assert len(wheels) == 1
    names = zipfile.ZipFile(wheels[0]).namelist()
    for name in ("metrosync/__init__.py", "metrosync/__init__.pyi", "metrosync/py.typed"):
        assert name in names
    assert any(re.fullmatch(r"metrosync/_metrosync\.cpython-.*\.so", n) for n in names), names
