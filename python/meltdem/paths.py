"""Where MeltDEM is: the source tree, the build's binaries, and the environment its scenes and
tools run in (the launcher and ctest set MELTDEM_SOURCE_DIR and MELTDEM_BIN; without them the
tree this package lives in and its build/bin)."""
import os

PACKAGE_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))   # <source>/python


def source_dir():
    return os.environ.get("MELTDEM_SOURCE_DIR") or os.path.dirname(PACKAGE_ROOT)


def bin_dir():
    return os.environ.get("MELTDEM_BIN") or os.path.join(source_dir(), "build", "bin")


def binary(name):
    """A MeltDEM executable of the build (meltdemFoam, meltdem-lmp, meltdemLaserCheck, ...)."""
    return os.path.join(bin_dir(), name)


def examples_dir():
    return os.path.join(source_dir(), "examples")


def tool_env(extra=None):
    """The environment of MeltDEM's tools and scenes: the source, the binaries, OpenFOAM's project
    folder, mpirun as root, and this package on the path."""
    e = dict(os.environ)
    e.setdefault("MELTDEM_SOURCE_DIR", source_dir())
    e.setdefault("MELTDEM_BIN", bin_dir())
    e.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    e.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    e.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    path = e.get("PYTHONPATH", "")
    if PACKAGE_ROOT not in path.split(os.pathsep):
        e["PYTHONPATH"] = PACKAGE_ROOT + (os.pathsep + path if path else "")
    e.update(extra or {})
    return e


def set_tool_environment():
    """This process's environment completed as tool_env() does (a scene run as a script)."""
    os.environ.update(tool_env())
