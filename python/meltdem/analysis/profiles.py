"""Where a sampled 1D profile crosses a level: the melt-pool widths and depths of the scenes and
of `meltdem post` (linear interpolation between samples)."""
import numpy as np


def first_fall(s, f, level):
    """First s where f (sampled at increasing s, f[0] >= level expected) falls below level;
    0 when f[0] < level, s[-1] when it never falls."""
    if f[0] < level:
        return 0.0
    for i in range(1, len(f)):
        if f[i] < level:
            return float(s[i - 1] + (f[i - 1] - level) / (f[i - 1] - f[i]) * (s[i] - s[i - 1]))
    return float(s[-1])


def level_span(f, c, level, h=None):
    """(low, high) where the profile f over the sorted centres c crosses level, outermost on each
    side of its maximum's connected run; the outer face when the run reaches an end. h: the
    spacing of a uniform grid (else from c). None when f stays below level."""
    i = int(np.argmax(f))
    if f[i] < level:
        return None
    lo = i
    while lo > 0 and f[lo - 1] >= level:
        lo -= 1
    hi = i
    while hi < len(f) - 1 and f[hi + 1] >= level:
        hi += 1
    if h is not None:
        left = c[lo] - h / 2 if lo == 0 else c[lo - 1] + (level - f[lo - 1]) / (f[lo] - f[lo - 1]) * h
        right = c[hi] + h / 2 if hi == len(f) - 1 else c[hi] + (f[hi] - level) / (f[hi] - f[hi + 1]) * h
        return left, right
    if lo == 0:
        left = c[0] - ((c[1] - c[0]) / 2 if len(c) > 1 else 0.0)
    else:
        left = c[lo - 1] + (level - f[lo - 1]) / (f[lo] - f[lo - 1]) * (c[lo] - c[lo - 1])
    if hi == len(f) - 1:
        right = c[-1] + ((c[-1] - c[-2]) / 2 if len(c) > 1 else 0.0)
    else:
        right = c[hi] + (f[hi] - level) / (f[hi] - f[hi + 1]) * (c[hi + 1] - c[hi])
    return float(left), float(right)
