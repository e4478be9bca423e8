"""Python side of the validation report (see validation_report.h / report.sh).

    from meltdem.testing.report import check_relative, check_absolute, report
    ok = check_relative("dem.restitution", "e (prescribed 0.5)", measured, 0.5, 0.01)

Each call prints 'VALIDATION test | what | measured | reference | tolerance | verdict'
and appends the row to $MELTDEM_REPORT_DIR/<test>.tsv; it returns True when it passes.
"""
import os


def report(test, what, measured, reference, tolerance, ok, xfail=None):
    """xfail: the reason a known miss is expected; a miss is then booked XFAIL (and the
    call returns True), a pass is booked XPASS so the stale reason gets noticed."""
    if xfail:
        verdict = "XPASS" if ok else f"XFAIL ({xfail})"
        ok = True
    else:
        verdict = "PASS" if ok else "FAIL"

    def fmt(v):
        return f"{v:.10g}" if isinstance(v, float) else str(v)
    print(f"VALIDATION {test} | {what} | measured {fmt(measured)} | reference {fmt(reference)}"
          f" | tolerance {tolerance} | {verdict}", flush=True)
    d = os.environ.get("MELTDEM_REPORT_DIR")
    if d:
        with open(os.path.join(d, test + ".tsv"), "a") as f:
            f.write(f"{test}\t{what}\t{fmt(measured)}\t{fmt(reference)}\t{tolerance}\t{verdict}\n")
    return ok


def check_relative(test, what, measured, reference, tol, xfail=None):
    ok = abs(measured - reference) <= tol * abs(reference)
    return report(test, what, float(measured), float(reference), f"{tol:g} relative", ok, xfail)


def check_absolute(test, what, measured, reference, tol, xfail=None):
    ok = abs(measured - reference) <= tol
    return report(test, what, float(measured), float(reference), f"{tol:g} absolute", ok, xfail)


def check_at_most(test, what, measured, bound, xfail=None):
    ok = measured <= bound
    return report(test, what, float(measured), f"<= {bound:g}", "bound", ok, xfail)


def check_at_least(test, what, measured, bound, xfail=None):
    ok = measured >= bound
    return report(test, what, float(measured), f">= {bound:g}", "bound", ok, xfail)
