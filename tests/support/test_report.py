#!/usr/bin/python3
"""meltdem.testing.report's verdicts, the rules every Python validation row follows: a pass,
a miss, a known miss (XFAIL, or XPASS when it passes), a known miss beyond its own bound
(FAIL), a value that is not finite (FAIL, with or without a known-miss reason), and a number
for information (INFO). Each case is booked in a scratch report and read back."""
import contextlib
import io
import math
import os
import sys
import tempfile

from meltdem.testing import report as r

CASES = [
    # (what, call, returned, verdict starts with)
    ("pass", lambda t: r.check_relative(t, "x", 1.005, 1.0, 0.01), True, "PASS"),
    ("miss", lambda t: r.check_relative(t, "x", 1.05, 1.0, 0.01), False, "FAIL"),
    ("known miss", lambda t: r.check_relative(t, "x", 1.05, 1.0, 0.01, xfail="why"), True, "XFAIL (why)"),
    ("known miss that passes", lambda t: r.check_relative(t, "x", 1.0, 1.0, 0.01, xfail="why"), True, "XPASS"),
    ("known miss within its bound", lambda t: r.check_relative(t, "x", 1.05, 1.0, 0.01, xfail="why",
                                                               miss_within=0.1), True, "XFAIL"),
    ("known miss beyond its bound", lambda t: r.check_relative(t, "x", 1.5, 1.0, 0.01, xfail="why",
                                                               miss_within=0.1), False, "FAIL (a miss beyond"),
    ("absolute miss beyond its bound", lambda t: r.check_absolute(t, "x", 3.0, 1.0, 0.5, xfail="why",
                                                                  miss_within=1.0), False, "FAIL (a miss beyond"),
    ("at most, within the slack", lambda t: r.check_at_most(t, "x", 1.5, 1.0, xfail="why", miss_within=1.0),
     True, "XFAIL"),
    ("at most, beyond the slack", lambda t: r.check_at_most(t, "x", 2.5, 1.0, xfail="why", miss_within=1.0),
     False, "FAIL (a miss beyond"),
    ("at least, beyond the slack", lambda t: r.check_at_least(t, "x", 0.0, 10.0, xfail="why", miss_within=4.0),
     False, "FAIL (a miss beyond"),
    ("inf with a known-miss reason", lambda t: r.check_relative(t, "x", math.inf, 1.0, 0.01, xfail="why"), False,
     "FAIL (measured value not finite)"),
    ("nan", lambda t: r.check_absolute(t, "x", math.nan, 1.0, 0.5), False, "FAIL (measured value not finite)"),
    ("inf above a lower bound", lambda t: r.check_at_least(t, "x", math.inf, 1.0), False,
     "FAIL (measured value not finite)"),
    ("information", lambda t: r.report_info(t, "x", 2.5), True, "INFO"),
    ("information, not finite", lambda t: r.report_info(t, "x", math.nan), False, "FAIL (measured value not finite)"),
]


def main():
    ok = True
    with tempfile.TemporaryDirectory() as d:
        os.environ["MELTDEM_REPORT_DIR"] = d
        for i, (what, call, returned, verdict) in enumerate(CASES):
            test = f"case{i}"
            with contextlib.redirect_stdout(io.StringIO()):
                got = call(test)
            row = open(os.path.join(d, test + ".tsv")).read().rstrip("\n").split("\t")
            good = got is returned and row[5].startswith(verdict)
            print(f"{'ok  ' if good else 'BAD '} {what}: returned {got} (expected {returned}), verdict {row[5]!r} "
                  f"(expected {verdict!r}...), tolerance {row[4]!r}")
            ok &= good
    print(f"{sum(1 for _ in CASES)} cases: {'all as expected' if ok else 'SOME NOT AS EXPECTED'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
