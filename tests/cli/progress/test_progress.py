"""The progress trackers of `meltdem run` on logs written piece by piece (as a running solver
does, lines cut in the middle): meltdemFoam 'Time = ' lines from a resumed start, LAMMPS thermo
rows of two runs (the second 'run N upto') with a Time column absent (t = step x dt), and the
line format `t = 1.23e-05 / 4.00e-05 s (31 %)  12.4 steps/s  ETA 0:01:05`."""
import os
import re
import sys
import tempfile

from meltdem.testing.cli import check_absolute

from meltdem.cli.progress import FoamProgress, LammpsProgress, fmt_eta, line

T = "cli.progress"
ok = True
d = tempfile.mkdtemp(prefix="cli_progress_")

# meltdemFoam, resumed at 1e-05 towards 4e-05: 30 steps of 1e-06, written in 7-byte pieces
foam = os.path.join(d, "log.meltdemFoam")
text = "".join(f"Courant Number mean: 0.01 max: 0.2\nTime = {1e-5 + k * 1e-6:g}\n\nPIMPLE: iteration 1\n"
               for k in range(1, 31))
p = FoamProgress(foam, 4e-5, 1e-5)
open(foam, "w").close()
seen = []
for i in range(0, len(text), 7):
    with open(foam, "a") as f:
        f.write(text[i:i + 7])
    p.poll()
    seen.append(p.t)
ok &= check_absolute(T, "foam: fluid steps counted", p.steps, 30, 0)
ok &= check_absolute(T, "foam: last simulated time [s]", p.t, 4e-5, 1e-18)
ok &= check_absolute(T, "foam: fraction of the resumed span", p.fraction(), 1.0, 1e-12)
ok &= check_absolute(T, "foam: times never decrease while reading pieces",
                     int(all(b >= a for a, b in zip(seen, seen[1:]))), 1, 0)
mid = FoamProgress(foam, 4e-5, 1e-5)
with open(foam, "w") as f:
    f.write(text[:text.index("Time = 2.5e-05")] + "Time = 2.5e-05\n")
mid.poll()
ok &= check_absolute(T, "foam: half-way fraction (t = 2.5e-05 of 1e-05 -> 4e-05)", mid.fraction(), 0.5, 1e-12)

# LAMMPS screen output: run 2000 then run 5000 upto, dt 1e-8, thermo every 500
lmp = os.path.join(d, "out.lammps")
rows = ["Step Atoms KinEng"] + [f"{s:8d} 10 1.0" for s in range(0, 2001, 500)] + ["Loop time of 0.1 on 1 procs"]
rows += ["Step Atoms KinEng"] + [f"{s:8d} 10 1.0" for s in range(2000, 3501, 500)]
open(lmp, "w").write("\n".join(rows) + "\n")
q = LammpsProgress(lmp, 1e-8, [2000, -5000])
q.poll()
ok &= check_absolute(T, "lammps: step of the last row", q.step, 3500, 0)
ok &= check_absolute(T, "lammps: simulated time = step x dt [s]", q.t, 3.5e-5, 1e-18)
ok &= check_absolute(T, "lammps: end of 'run 5000 upto' [s]", q.t_end, 5e-5, 1e-18)
ok &= check_absolute(T, "lammps: fraction of the second run", q.fraction(), 0.5, 1e-12)

# the same runs with the timestep changed to 2e-8 between them (`timestep 2e-8` is not on screen)
q = LammpsProgress(lmp, 2e-8, [2000, -5000], [1e-8, 2e-8])
q.poll()
ok &= check_absolute(T, "lammps, dt 1e-8 then 2e-8: simulated time [s] (2000 x 1e-8 + 1500 x 2e-8)", q.t, 5e-5,
                     1e-18)
ok &= check_absolute(T, "lammps, dt 1e-8 then 2e-8: end of the second run [s]", q.t_end, 8e-5, 1e-18)

s = line(1.23e-5, 4e-5, 12.4, 65)
print(s)
ok &= check_absolute(T, "line format", int(s == "t = 1.23e-05 / 4.00e-05 s (31 %)  12.4 steps/s  ETA 0:01:05"), 1, 0)
ok &= check_absolute(T, "ETA of an unknown rate", int(fmt_eta(None) == "--:--:--"), 1, 0)
ok &= check_absolute(T, "ETA over an hour", int(re.fullmatch(r"2:00:01", fmt_eta(7201)) is not None), 1, 0)
if ok:
    import shutil
    shutil.rmtree(d, ignore_errors=True)
sys.exit(0 if ok else 1)
