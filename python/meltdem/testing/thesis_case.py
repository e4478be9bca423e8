"""The Codina2019 §2.3 channel particle (tests/coupling/thesis_particle/thesis_particle.py), the
coupled case several tests build on, as a module."""
import os

from meltdem import paths
from meltdem.loader import load_module


def thesis_particle():
    """tests/coupling/thesis_particle/thesis_particle.py, loaded once."""
    return load_module(os.path.join(paths.source_dir(), "tests", "coupling", "thesis_particle", "thesis_particle.py"),
                       "thesis_particle")
