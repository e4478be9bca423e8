"""The `meltdem` command: list | check CASE | run EXAMPLE-OR-CASE | post CASE."""
import argparse
import os
import sys

from . import check as chk
from . import examples as ex
from . import run as run_mod
from .examples import StepError

USAGE = """examples:
  meltdem list                          the examples, their kind and CI run time
  meltdem run powder-pour               build ./powder-pour from the example and run it
  meltdem run slm-track --np 2          the CI size of a coupled scene on 2 MPI ranks
  meltdem run slm-track --full --case /scratch/slm
  meltdem check ./slm-track             validate a case before launch
  meltdem run ./slm-track               run a case folder as it is
  meltdem run ./slm-track --resume      continue from its latest checkpoint
  meltdem post ./slm-track              (re)write VTK series, plots and summary"""


def cmd_list(a):
    rows = ex.describe()
    w = max(len(r["name"]) for r in rows)
    print(f"{'example':<{w}}  {'kind':<14}  {'CI run time':<28}  title")
    for r in rows:
        print(f"{r['name']:<{w}}  {ex.KINDS[r['kind']]:<14}  {(r['ci_time'] or '-'):<28}  {r['title']}")
        if r["full_time"]:
            print(f"{'':<{w}}  {'':<14}  full size: {r['full_time']}")
    print(f"\n{len(rows)} examples in {ex.examples_dir()}; run one with: meltdem run <example> [--np N]")
    return 0


def cmd_check(a):
    rep, kind = chk.check(a.case)
    return chk.print_report(os.path.abspath(a.case), rep, kind)


def cmd_run(a):
    return run_mod.run(a.target, case=a.case, np_=a.np, resume=a.resume, size="full" if a.full else "ci",
                       check_first=not a.no_check, analyse=not a.no_analyse, checkpoint_every=a.checkpoint_every)


def cmd_post(a):
    case = os.path.abspath(a.case)
    if not os.path.isdir(case):
        raise StepError(f"no case folder {case}")
    s = run_mod.postprocess(case, example=a.example)
    if s is None:
        return 1
    for f in ("summary.md", "summary.json"):
        if os.path.isfile(os.path.join(case, f)):
            print(f"meltdem: summary: {os.path.join(case, f)}")
            break
    return 0


def parser():
    ap = argparse.ArgumentParser(prog="meltdem", description="MeltDEM: run and check powder-AM cases "
                                 "(LAMMPS DEM + OpenFOAM melt pool).", epilog=USAGE,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", metavar="{list,check,run,post}")
    sub.required = True
    p = sub.add_parser("list", help="the examples (DEM-only / coupled / continuum-only, CI run time)")
    p.set_defaults(func=cmd_list)
    p = sub.add_parser("check", help="validate a case before launch (files, SI units, domains, materials, laser path)")
    p.add_argument("case")
    p.set_defaults(func=cmd_check)
    p = sub.add_parser("run", help="build (example) or take (case folder), check, mesh, decompose, run, post-process",
                       description=run_mod.__doc__,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("target", help="an example name (meltdem list) or a case folder")
    p.add_argument("--np", type=int, default=1, help="MPI ranks (default 1)")
    p.add_argument("--resume", action="store_true", help="continue from the latest complete checkpoint (coupled cases)")
    p.add_argument("--case", help="case folder of an example (default ./<example>)")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--ci", action="store_true", help="the example's CI size, minutes (default)")
    size.add_argument("--full", action="store_true",
                      help="the example's full (paper/thesis) size; meltdem list gives its run time")
    p.add_argument("--no-check", action="store_true", help="skip meltdem check before the launch")
    p.add_argument("--no-analyse", action="store_true", help="skip the example's analysis (its scene's analyse step)")
    p.add_argument("--checkpoint-every", type=int, default=None, metavar="N",
                   help="DEM-only cases: a checkpoint every N steps (default 10000)")
    p.set_defaults(func=cmd_run)
    p = sub.add_parser("post", help="post-process a case: VTK (.pvd) series, plots, summary")
    p.add_argument("case")
    p.add_argument("--example", help="the example the case was built from (adds its analysis)")
    p.set_defaults(func=cmd_post)
    return ap


def os_error_text(e):
    """An operating-system error in words: what failed on which file."""
    import errno
    where = f" ({e.filename})" if getattr(e, "filename", None) else ""
    if e.errno == errno.ENOSPC:
        return (f"the disk is full: no space left to write{where}. Free disk space; a coupled run resumes "
                f"from its last complete checkpoint with: meltdem run CASE --resume")
    if e.errno in (errno.EACCES, errno.EPERM):
        return f"permission denied{where}: the file or folder cannot be read or written by this user"
    if e.errno == errno.EROFS:
        return f"read-only file system{where}"
    return f"{e.strerror or e}{where}"


def main(argv=None):
    a = parser().parse_args(argv)
    if getattr(a, "np", 1) < 1:
        print("meltdem: --np must be >= 1", file=sys.stderr)
        return 2
    if getattr(a, "checkpoint_every", None) is not None and a.checkpoint_every < 1:
        print("meltdem: --checkpoint-every must be >= 1 (steps between two checkpoints)", file=sys.stderr)
        return 2
    try:
        return a.func(a)
    except StepError as e:
        print(f"meltdem: ERROR: {e}", file=sys.stderr, flush=True)
        return 1
    except BrokenPipeError:          # `meltdem list | head`: a reader that stopped is no error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except OSError as e:
        print(f"meltdem: ERROR: {os_error_text(e)}", file=sys.stderr, flush=True)
        return 1
    except KeyboardInterrupt:
        print("\nmeltdem: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":          # `python3 -m meltdem.cli.main`, as tools/meltdem does
    from .. import paths
    paths.set_tool_environment()
    sys.exit(main())
