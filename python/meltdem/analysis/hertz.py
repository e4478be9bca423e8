"""Independent references for the restitution tests (scipy, not coupling/):
e(alpha) of the Hertz contact with Tsuji damping, dimensionless form
x'' = -x^(3/2) - alpha x^(1/4) x', x(0) = 0, x'(0) = 1, e = -x'(end), and the Hertz
contact time of Codina2019 eq. 3.1."""
from scipy.integrate import solve_ivp


def restitution_for_alpha(alpha):
    def rhs(t, y):
        x = max(y[0], 0.0)
        return [y[1], -x ** 1.5 - alpha * x ** 0.25 * y[1]]

    def out(t, y):
        return y[0]
    out.terminal, out.direction = True, -1
    sol = solve_ivp(rhs, (0.0, 50.0), [0.0, 1.0], events=out, rtol=1e-11, atol=1e-13, first_step=1e-6)
    return -sol.y_events[0][0][1]


def hertz_contact_time(m_eff, r_eff, e_eff, u):
    """Codina2019 eq. 3.1"""
    return 2.87 * (m_eff ** 2 / (r_eff * e_eff ** 2 * u)) ** 0.2
