"""Reference solutions for foam.rosenthal: Rosenthal's quasi-steady moving point source on a
semi-infinite body (adiabatic surface) and, for information, the exact transient solution of a
moving Gaussian surface source switched on at t = 0 (superposed instantaneous Gaussian sources,
surface image doubled)."""
import numpy as np


def rosenthal(xi, y, z, q, k, a, v, T0):
    """T of the thick-plate point source q = eta P [W] at xi = x - x_source (xi > 0 ahead)."""
    R = np.sqrt(xi ** 2 + y ** 2 + z ** 2)
    return T0 + q / (2 * np.pi * k * R) * np.exp(-v * (xi + R) / (2 * a))


def width_at_depth(Tfun, Tm, z, xi_range, y_max, n=4000):
    """Melt-pool width 2 max y of the isotherm T = Tm in the plane z (bisection in y for each xi)."""
    best = 0.0
    for xi in np.linspace(xi_range[0], xi_range[1], n):
        if Tfun(xi, 0.0, z) < Tm:
            continue
        lo, hi = 0.0, y_max
        if Tfun(xi, hi, z) >= Tm:
            return np.inf
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if Tfun(xi, mid, z) >= Tm:
                lo = mid
            else:
                hi = mid
        best = max(best, lo)
    return 2 * best


def gaussian_transient(x, y, z, t, q, k, a, rho_cp, T0, r, x0, v, nt=4000):
    """T at time t of a Gaussian surface source (1/e^2 radius r, power q) moving from x0 at v along x
    since t = 0 on a semi-infinite body z < 0 with an adiabatic surface."""
    # tau = t - t' on a grid refined near 0 (u = sqrt(tau))
    u = np.linspace(0.0, np.sqrt(t), nt + 1)[1:]
    tau = u ** 2
    dtau = 2 * u * (u[1] - u[0])
    xs = x0 + v * (t - tau)
    s2 = 2 * a * tau + r * r / 4  # lateral variance of the spread source
    lat = np.exp(-((x - xs) ** 2 + y ** 2) / (2 * s2)) / (2 * np.pi * s2)
    vert = 2 * np.exp(-z * z / (4 * a * tau)) / np.sqrt(4 * np.pi * a * tau)
    return T0 + q / rho_cp * np.sum(lat * vert * dtau)
