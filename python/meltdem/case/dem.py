"""DEM-only scenes (examples/powder-bed, examples/powder-spread): a LAMMPS input copied into the
case with its -var overrides in CASE/scene.json, run by meltdem-lmp, and the command line every
scene.py offers (build|run|analyse|all CASE [--ci | --full] [--np N])."""
import argparse
import json
import os
import shutil
import subprocess

from .. import paths


def write_case(case, scene, variant, source_input, variables):
    """CASE/ with the input and scene.json (scene name, variant, the input's -var overrides)"""
    os.makedirs(case, exist_ok=True)
    shutil.copy(source_input, case)
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump({"scene": scene, "variant": variant, "vars": variables}, f, indent=1)


def run_input(case, input_name, np_=1):
    """meltdem-lmp -in INPUT with the case's -var overrides (mpirun -np N for N > 1)"""
    spec = json.load(open(os.path.join(case, "scene.json")))
    cmd = [paths.binary("meltdem-lmp"), "-in", input_name, "-log", "log.lammps", "-screen", "none"]
    for k, v in spec["vars"].items():
        cmd += ["-var", k, str(v)]
    if np_ > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_)] + cmd
    subprocess.run(cmd, cwd=case, check=True)


def scene_parser(doc):
    """the scene command line: action, case, --ci/--full (dest 'variant'), --np"""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--ci", action="store_const", dest="variant", const="ci")
    size.add_argument("--full", action="store_const", dest="variant", const="full")
    ap.add_argument("--np", type=int, default=1)
    return ap


def run_actions(args, build, run, analyse):
    """the parsed command's steps: build(case), run(case, np), analyse(case), in that order"""
    case = os.path.abspath(args.case)
    if args.action in ("build", "all"):
        build(case)
    if args.action in ("run", "all"):
        run(case, args.np)
    if args.action in ("analyse", "all"):
        analyse(case)
