"""A Python file loaded as a module by its path, once: the scenes' files and the helpers beside
them, which live outside the package (examples/<scene>/scene.py, pbf.py)."""
import importlib.util
import os
import sys

_MODULES = {}


def load_module(path, name=None):
    """A scene file (or a helper beside it) as a module, loaded once; its folder is importable
    while it loads (helpers of the same scene)."""
    path = os.path.abspath(path)
    if path in _MODULES:
        return _MODULES[path]
    name = name or "meltdem_scene_" + os.path.basename(os.path.dirname(path)).replace("-", "_") + "_" + \
        os.path.splitext(os.path.basename(path))[0]
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    folder = os.path.dirname(path)
    added = folder not in sys.path
    if added:
        sys.path.insert(0, folder)
    try:
        spec.loader.exec_module(mod)
    finally:
        if added:
            sys.path.remove(folder)
    _MODULES[path] = mod
    return mod
