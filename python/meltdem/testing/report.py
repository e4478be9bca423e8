"""Python side of the validation report (see validation_report.h / report.sh).

    from meltdem.testing.report import check_relative, check_absolute, report, report_info
    ok = check_relative("dem.restitution", "e (prescribed 0.5)", measured, 0.5, 0.01)

Each call prints 'VALIDATION test | what | measured | reference | tolerance | verdict'
and appends the row to $MELTDEM_REPORT_DIR/<test>.tsv; it returns True when it passes.
"""
import math
import os


def _finite(v):
    return not isinstance(v, float) or math.isfinite(v)


def _book(test, what, measured, reference, tolerance, verdict):
    def fmt(v):
        return f"{v:.10g}" if isinstance(v, float) else str(v)
    print(f"VALIDATION {test} | {what} | measured {fmt(measured)} | reference {fmt(reference)}"
          f" | tolerance {tolerance} | {verdict}", flush=True)
    d = os.environ.get("MELTDEM_REPORT_DIR")
    if d:
        with open(os.path.join(d, test + ".tsv"), "a") as f:
            f.write(f"{test}\t{what}\t{fmt(measured)}\t{fmt(reference)}\t{tolerance}\t{verdict}\n")


def report(test, what, measured, reference, tolerance, ok, xfail=None, expected_miss=True):
    """xfail: the reason a known miss is expected; a miss is then booked XFAIL (and the
    call returns True), a pass is booked XPASS so the stale reason gets noticed. expected_miss:
    whether a miss lies within the bound given for the known one (the check_* functions'
    miss_within); a miss beyond it fails whatever the reason. A measured value that is not
    finite (inf, nan) fails whatever the reason: it is no measurement."""
    if not _finite(measured):
        verdict, ok = "FAIL (measured value not finite)", False
    elif xfail and not ok and not expected_miss:
        verdict = "FAIL (a miss beyond the bound of the known one)"
    elif xfail:
        verdict = "XPASS" if ok else f"XFAIL ({xfail})"
        ok = True
    else:
        verdict = "PASS" if ok else "FAIL"
    _book(test, what, measured, reference, tolerance, verdict)
    return ok


def report_info(test, what, measured, reference="-"):
    """A number shown for information, compared with nothing (verdict INFO); a value that is
    not finite fails. Returns True when it is finite."""
    ok = _finite(measured)
    _book(test, what, measured, reference, "info", "INFO" if ok else "FAIL (measured value not finite)")
    return ok


def _within(tol, miss_within, kind):
    """The tolerance column; with miss_within (only with xfail), the known miss's bound too."""
    return f"{tol:g} {kind}" + (f"; known miss within {miss_within:g}" if miss_within is not None else "")


# miss_within (with xfail): the bound of the known miss, of the same kind as the tolerance (relative,
# absolute, or the slack past the bound): a miss beyond it fails, so a known miss that gets worse
# is seen. Without it an xfail row books any miss, however large, as XFAIL.
def check_relative(test, what, measured, reference, tol, xfail=None, miss_within=None):
    err = abs(measured - reference)
    return report(test, what, float(measured), float(reference), _within(tol, miss_within, "relative"),
                  err <= tol * abs(reference), xfail, miss_within is None or err <= miss_within * abs(reference))


def check_absolute(test, what, measured, reference, tol, xfail=None, miss_within=None):
    err = abs(measured - reference)
    return report(test, what, float(measured), float(reference), _within(tol, miss_within, "absolute"),
                  err <= tol, xfail, miss_within is None or err <= miss_within)


def check_at_most(test, what, measured, bound, xfail=None, miss_within=None):
    tol = "bound" + (f"; known miss within {miss_within:g} of it" if miss_within is not None else "")
    return report(test, what, float(measured), f"<= {bound:g}", tol, measured <= bound, xfail,
                  miss_within is None or measured <= bound + miss_within)


def check_at_least(test, what, measured, bound, xfail=None, miss_within=None):
    tol = "bound" + (f"; known miss within {miss_within:g} of it" if miss_within is not None else "")
    return report(test, what, float(measured), f">= {bound:g}", tol, measured >= bound, xfail,
                  miss_within is None or measured >= bound - miss_within)
