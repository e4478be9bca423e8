"""Which sources and solver build a benchmark measured (the machines are shared: a rebuild
during a long run would mix two builds in one table)."""
import os
import subprocess
import time


def build_stamp(root, bin_dir):
    """git commit of the sources and modification time of the meltdemFoam used"""
    def git(*args):
        try:
            return subprocess.run(["git", "-C", root] + list(args), capture_output=True, text=True).stdout.strip()
        except FileNotFoundError:  # no git (a copied tree, a chroot without it)
            return ""
    head = git("rev-parse", "--short", "HEAD") or "(not a git checkout)"
    dirty = git("status", "--porcelain", "--untracked-files=no", "coupling", "foam-src", "lammps-src")
    mtime = time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime(os.path.getmtime(os.path.join(bin_dir, "meltdemFoam"))))
    return (f"sources at the start {head}{' + uncommitted coupling changes' if dirty else ''}, "
            f"meltdemFoam built {mtime}")


def stamp_line(root, bin_dir, at_start):
    """at_start (the stamp taken when the run began), flagged if the solver was rebuilt since"""
    now = build_stamp(root, bin_dir)
    if now.split("built")[1] == at_start.split("built")[1]:
        return at_start
    return at_start + " -- REBUILT DURING THE RUN (now: " + now + "): mixed results"
