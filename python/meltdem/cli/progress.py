"""Progress line of a running solver, read from its log as it grows:

    t = 1.23e-05 / 4.00e-05 s (31 %)  12.4 steps/s  ETA 0:01:05

meltdemFoam: the 'Time = ' lines of log.meltdemFoam (end time from system/controlDict).
meltdem-lmp: the thermo rows of log.lammps (step x timestep; the run length from the echoed
'run N' command). Rewritten in place with \\r on a terminal, otherwise one line every ~10 s
(MELTDEM_PROGRESS_INTERVAL overrides), plus a first and a last line.
"""
import os
import re
import sys
import time

_FOAM_TIME = re.compile(r"^Time = (\S+)\s*$", re.M)


def fmt_eta(seconds):
    if seconds is None or seconds != seconds or seconds < 0 or seconds > 1e7:
        return "--:--:--"
    s = int(round(seconds))
    return f"{s // 3600}:{s // 60 % 60:02d}:{s % 60:02d}"


def line(t, t_end, steps_per_s, eta):
    pct = f" ({100 * t / t_end:.0f} %)" if t_end else ""
    end = f" / {t_end:.2e}" if t_end else ""
    return f"t = {t:.2e}{end} s{pct}  {steps_per_s:.1f} steps/s  ETA {fmt_eta(eta)}"


class LogFollower:
    """Reads the new text of a log file each poll (the file may not exist yet)."""

    def __init__(self, path):
        self.path, self.pos, self.rest = path, 0, ""

    def new_lines(self):
        try:
            with open(self.path, errors="replace") as f:
                f.seek(self.pos)
                text = f.read()
                self.pos = f.tell()
        except OSError:
            return []
        text = self.rest + text
        lines = text.split("\n")
        self.rest = lines.pop()
        return lines


class FoamProgress:
    """Simulated time from 'Time = t' lines (one per fluid step)."""

    def __init__(self, log, t_end, t_start=0.0):
        self.f = LogFollower(log)
        self.t_end, self.t0 = t_end, t_start
        self.t, self.steps = t_start, 0

    def poll(self):
        for ln in self.f.new_lines():
            if ln.startswith("Time = "):
                try:
                    self.t = float(ln.split()[2])
                    self.steps += 1
                except (IndexError, ValueError):
                    pass
        return self.steps > 0

    def fraction(self):
        span = (self.t_end or 0) - self.t0
        return (self.t - self.t0) / span if span > 0 else None


class LammpsProgress:
    """Step from the thermo rows after each 'Step ...' header; the run length from the echoed
    'run N' line; time = step x timestep (the 'timestep dt' line; a Time column when printed)."""

    def __init__(self, log, dt=None, runs=None, run_dts=None):
        self.f = LogFollower(log)
        self.dt, self.run_len, self.run_start = dt, None, None
        self.runs, self.n_headers = list(runs or []), 0   # run lengths read from the input
        self.run_dts = list(run_dts or [])                # and the timestep of each run
        self.step, self.steps, self.in_thermo, self.cols = None, 0, False, []
        self.t_col = None
        self.t0 = 0.0
        self.t = 0.0
        self.t_end = None

    def poll(self):
        for ln in self.f.new_lines():
            w = ln.split()
            if not w:
                continue
            if w[0] == "timestep" and len(w) > 1:
                try:
                    self.dt = float(w[1])
                except ValueError:
                    pass
            elif w[0] == "run" and len(w) > 1:
                try:
                    self.run_len = int(float(w[1]))
                    self.run_start = None
                except ValueError:
                    pass
            elif w[0] == "Step":
                self.in_thermo, self.cols = True, w
                # a new run: its length from the input (the screen does not echo 'run N'); the
                # i-th thermo header belongs to the i-th run command (no loops in the input)
                if self.n_headers < len(self.runs):
                    self.run_len = self.runs[self.n_headers]
                if self.n_headers < len(self.run_dts) and self.run_dts[self.n_headers]:
                    self.dt = self.run_dts[self.n_headers]
                self.run_start = None
                self.n_headers += 1
                self.t_col = next((i for i, c in enumerate(w) if c in ("Time", "time", "v_t", "v_time")), None)
            elif self.in_thermo and w[0].lstrip("-").isdigit():
                try:
                    step = int(w[0])
                except ValueError:
                    continue
                # without a Time column: the time so far plus the steps since at this run's step
                t_steps = (self.t + (step - self.step) * (self.dt or 0) if self.step is not None
                           else step * (self.dt or 0))
                if self.run_start is None:
                    self.run_start = step
                    if self.run_len is not None and self.run_len < 0:   # run N upto
                        self.run_len = max(-self.run_len - step, 0)
                    self.t0 = float(w[self.t_col]) if self.t_col is not None else t_steps
                if self.step is not None and step > self.step:
                    self.steps += step - self.step
                self.step = step
                self.t = float(w[self.t_col]) if self.t_col is not None and len(w) > self.t_col else t_steps
                if self.run_len and self.dt:
                    self.t_end = self.t0 + self.run_len * self.dt
            elif w[0] == "Loop":
                self.in_thermo = False
        return self.step is not None

    def fraction(self):
        if self.run_len and self.step is not None and self.run_start is not None:
            return (self.step - self.run_start) / self.run_len
        return None


class Reporter:
    """Prints the progress line: \\r-rewritten on a tty, else every `interval` seconds."""

    def __init__(self, tracker, out=None, interval=None):
        self.p, self.out = tracker, out or sys.stdout
        self.tty = self.out.isatty()
        self.interval = float(os.environ.get("MELTDEM_PROGRESS_INTERVAL", interval or 10.0))
        self.start = time.time()
        self.last_print = None
        self.samples = []   # (wall, t, steps) for the rate over the last minute
        self.printed = 0

    def text(self):
        now = time.time()
        self.samples.append((now, self.p.t, self.p.steps))
        while len(self.samples) > 2 and now - self.samples[0][0] > 60:
            self.samples.pop(0)
        w0, t0, s0 = self.samples[0]
        dw = now - w0 if now > w0 else now - self.start
        rate_steps = (self.p.steps - s0) / dw if dw > 0 else 0.0
        if rate_steps == 0 and now > self.start:
            rate_steps = self.p.steps / (now - self.start)
        eta = None
        frac = self.p.fraction()
        if frac is not None and frac > 0:
            eta = (now - self.start) * (1 - frac) / frac
            if dw > 5 and self.p.t > t0 and self.p.t_end:
                eta = (self.p.t_end - self.p.t) * dw / (self.p.t - t0)
        return line(self.p.t, self.p.t_end, rate_steps, None if eta is None else max(eta, 0.0))

    def update(self, final=False):
        if self.p.poll():
            self.seen = True
        if not getattr(self, "seen", False):
            return          # nothing in the log yet (or a run that failed before its first step)
        now = time.time()
        if self.tty:
            if final or self.last_print is None or now - self.last_print >= 0.5:
                self.out.write("\r" + self.text().ljust(70) + ("\n" if final else ""))
                self.out.flush()
                self.last_print = now
                self.printed += 1
        elif final or self.last_print is None or now - self.last_print >= self.interval:
            self.out.write(self.text() + "\n")
            self.out.flush()
            self.last_print = now
            self.printed += 1
