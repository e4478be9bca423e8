"""The examples (examples/<name>/): title, kind (DEM-only / coupled / continuum-only), CI run time
as the README states it, and building a case from one through the scene interface
(`examples/<scene>/scene.py build CASE [--ci|--full]`; powder-pour: its in.pour copied)."""
import os
import re
import shutil
import subprocess

KINDS = {"dem": "DEM-only", "coupled": "coupled", "continuum": "continuum-only"}


def source_dir():
    return os.environ.get("MELTDEM_SOURCE_DIR") or os.path.abspath(
        os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def examples_dir():
    return os.path.join(source_dir(), "examples")


def names():
    d = examples_dir()
    return sorted(n for n in os.listdir(d) if os.path.isdir(os.path.join(d, n)) and not n.startswith((".", "_"))
                  and (os.path.isfile(os.path.join(d, n, "scene.py"))
                       or any(f.startswith("in.") for f in os.listdir(os.path.join(d, n)))))


def _readme(name):
    p = os.path.join(examples_dir(), name, "README.md")
    try:
        return open(p, encoding="utf-8", errors="replace").read()
    except OSError:
        return ""


def title(name):
    for ln in _readme(name).splitlines():
        if ln.startswith("# "):
            return ln[2:].strip()
    return "(no README)"


def _table_kinds():
    """The 'coupled' column of the scenes table in the top-level README."""
    out = {}
    try:
        text = open(os.path.join(source_dir(), "README.md"), encoding="utf-8").read()
    except OSError:
        return out
    for ln in text.splitlines():
        m = re.match(r"\|\s*\[([\w-]+)\]\(examples/[\w-]+/README\.md\)(.*)", ln)
        if m:
            cells = [c.strip().lower() for c in ln.split("|")[1:-1]]
            if len(cells) >= 3:
                names_in_row = re.findall(r"\[([\w-]+)\]\(examples/", cells[0])
                for n in names_in_row:
                    out[n] = cells[2]
    return out


def kind(name):
    """'dem', 'coupled' or 'continuum'."""
    d = os.path.join(examples_dir(), name)
    if not os.path.isfile(os.path.join(d, "scene.py")):
        return "dem"          # a bare LAMMPS input (powder-pour)
    col = _table_kinds().get(name, "")
    text = (col + " " + _readme(name)[:600]).lower()
    if "dem only" in col or "dem-only" in col:
        return "dem"
    if "continuum only" in col or "continuum-only" in col:
        return "continuum"
    if col.startswith("yes") or "coupled" in col:
        return "coupled"
    if "dem only" in text:
        return "dem"
    if "continuum only" in text:
        return "continuum"
    return "coupled"


_D = r"(?:~|≈|about )?\d+(?:\.\d+)?\s*(?:min(?:utes?)?(?:\s+\d+\s*s)?|s)\b"
_DUR = re.compile(rf"(?:{_D}\s*(?:to|–)\s*)?{_D}(?:\s*(?:wall|serial|in ctest|\([^)]*machine\)))?")

def ci_time(name):
    """The CI run time as the README states it: the first wall-clock duration in a paragraph or
    table row about the CI variant or test (not one following 'full'); None when it states none."""
    text = _readme(name)
    chunks = []
    for para in re.split(r"\n\s*\n", text):
        rows = [ln for ln in para.splitlines() if ln.lstrip().startswith("|")]
        chunks += rows if rows else [para]
    for c in chunks:
        c1 = " ".join(c.split())
        if not re.search(r"\bCI\b", c1):
            continue
        for m in _DUR.finditer(c1):
            s = m.group(0)
            if re.search(r"full|medium", c1[max(0, m.start() - 60):m.start()].lower()):
                continue
            # a run time, not a simulated time: says wall/serial/ctest/machine, or is approximate
            if re.search(r"wall|serial|ctest|machine|~|≈|about", s):
                return s
    return None


def describe():
    rows = []
    for n in names():
        rows.append(dict(name=n, title=title(n), kind=kind(n), ci_time=ci_time(n),
                         readme=os.path.join("examples", n, "README.md")))
    return rows


def build(name, case, size="ci"):
    """Build CASE from example NAME (its scene.py build; powder-pour: the input copied); the
    scene's output goes to CASE/log.build. Returns the command line run."""
    src = os.path.join(examples_dir(), name)
    scene = os.path.join(src, "scene.py")
    if not os.path.isfile(scene):
        os.makedirs(case, exist_ok=True)
        for f in os.listdir(src):
            if f.startswith("in.") or f.endswith(".data"):
                shutil.copy(os.path.join(src, f), os.path.join(case, f))
        return f"copied {name}'s LAMMPS input into {case}"
    cmd = ["/usr/bin/python3", scene, "build", case, f"--{size}"]
    # the scene creates CASE itself (some refuse a folder they did not write): log beside it first
    parent = os.path.dirname(os.path.abspath(case))
    os.makedirs(parent, exist_ok=True)
    tmp = os.path.join(parent, f".meltdem-build-{os.path.basename(case)}.log")
    with open(tmp, "w") as f:
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, env=scene_env())
    logpath = os.path.join(case, "log.build") if os.path.isdir(case) else os.path.join(parent, f"log.build.{name}")
    shutil.move(tmp, logpath)
    if r.returncode != 0:
        raise StepError(f"building {name} failed (rc {r.returncode}): read {logpath}")
    return " ".join(cmd)


def analyse(name, case):
    """scene.py analyse CASE (writes CASE/summary.json); None for examples without scene.py."""
    scene = os.path.join(examples_dir(), name, "scene.py")
    if not os.path.isfile(scene):
        return None
    logpath = os.path.join(case, "log.analyse")
    with open(logpath, "w") as f:
        r = subprocess.run(["/usr/bin/python3", scene, "analyse", case], stdout=f, stderr=subprocess.STDOUT,
                           env=scene_env())
    if r.returncode != 0:
        raise StepError(f"{name} analysis failed (rc {r.returncode}): read {logpath}")
    return logpath


def scene_run(name, case, np_, log):
    """The scene's own run step (examples whose built case is not one solver case)."""
    scene = os.path.join(examples_dir(), name, "scene.py")
    cmd = ["/usr/bin/python3", scene, "run", case, "--np", str(np_)]
    f = open(log, "w")
    return subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, env=scene_env()), f


def scene_env():
    src = source_dir()
    e = dict(os.environ)
    e.setdefault("MELTDEM_SOURCE_DIR", src)
    e.setdefault("MELTDEM_BIN", os.path.join(src, "build", "bin"))
    e.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    e.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    e.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return e


class StepError(RuntimeError):
    """A step failed; the message is the one-line reason (it names the log to read)."""
