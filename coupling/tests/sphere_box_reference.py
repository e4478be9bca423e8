#!/usr/bin/python3
"""Reference volumes of the unit sphere inside boxes, to 30 digits with mpmath: the slice
area (disk ∩ rectangle, integrated in y) integrated in x between its kinks. Prints the C++
table test_sphere_box_overlap.cpp holds; run it to regenerate that table."""
import mpmath as mp

mp.mp.dps = 40

# lo, hi of each box (unit sphere at the origin): planes through the centre, tangent planes,
# a slice circle just clearing an edge, tiny and thin cells, corners in each octant
BOXES = [
    ((0.0, 0.0, 0.0), (2.0, 2.0, 2.0)),
    ((0.3, 0.5, 0.7), (2.0, 2.0, 2.0)),
    ((-0.61064024782648252, -1.2509781158427484, -0.0074228645278879846),
     (1.1405487852103491, -0.36073179451739534, 0.99497457472752582)),
    ((-0.2, -0.3, -0.4), (0.1, 0.25, 0.05)),
    ((0.5, 0.5, 0.5), (0.6, 0.6, 0.6)),
    ((0.57, 0.57, 0.57), (0.9, 0.9, 0.9)),
    ((-1.0, -1.0, 0.999), (1.0, 1.0, 1.0)),
    ((0.7, -0.1, -0.1), (1.5, 0.1, 0.1)),
    ((-0.9, 0.4, -0.3), (-0.2, 0.9, 0.6)),
    ((-0.05, -0.05, -0.05), (0.05, 0.05, 0.05)),
    ((0.0, 0.0, -1.5), (1.5, 1.5, 1e-6)),
    ((-0.3, 0.2, 0.95), (0.3, 0.3, 1.2)),
]


def disk_rect(rho, y0, y1, z0, z1):
    if rho <= 0:
        return mp.mpf(0)
    a, b = max(y0, -rho), min(y1, rho)
    if a >= b:
        return mp.mpf(0)

    def f(y):
        s = mp.sqrt(rho * rho - y * y)
        return max(mp.mpf(0), min(z1, s) - max(z0, -s))
    pts = {a, b}
    for z in (z0, z1):
        if z * z < rho * rho:
            for p in (-mp.sqrt(rho * rho - z * z), mp.sqrt(rho * rho - z * z)):
                if a < p < b:
                    pts.add(p)
    return mp.quad(f, sorted(pts))


def box_volume(lo, hi):
    lo = [mp.mpf(v) for v in lo]
    hi = [mp.mpf(v) for v in hi]
    xa, xb = max(lo[0], -1), min(hi[0], 1)
    if xa >= xb:
        return mp.mpf(0)
    pts = {xa, xb}
    for y in (lo[1], hi[1], 0):
        for z in (lo[2], hi[2], 0):
            d = (y * y if y else 0) + (z * z if z else 0)
            if d < 1:
                for x in (-mp.sqrt(1 - d), mp.sqrt(1 - d)):
                    if xa < x < xb:
                        pts.add(x)
    return mp.quad(lambda x: disk_rect(mp.sqrt(max(0, 1 - x * x)), lo[1], hi[1], lo[2], hi[2]), sorted(pts))


if __name__ == "__main__":
    for lo, hi in BOXES:
        v = box_volume(lo, hi)
        lo_text, hi_text = ", ".join(repr(x) for x in lo), ", ".join(repr(x) for x in hi)
        print("    {{{%s}, {%s}, %s}," % (lo_text, hi_text, mp.nstr(v, 20)))
