#pragma once
// Drag on a sphere (Codina2019 eq. 2.11, 2.14) and the particle Reynolds number.

namespace meltdem::coupling {

enum class DragModel { Thesis, SchillerNaumann };

// Re_p = rho_f |U_f - U_p| d / mu_f
double particle_reynolds(double rho_f, double slip_speed, double d, double mu_f);

// Codina2019 eq. 2.14 (solid spheres): Cd = 24/Re + 4 Re^(-1/3) for Re <= 1000, 0.424 above.
// Codina2019 prints "4 Re^(1/3)"; the exponent must be -1/3 (= 24/Re * Re^(2/3)/6, the
// sphere-drag law OpenFOAM uses), the only choice continuous with 0.424 at Re = 1000.
double drag_coefficient_thesis(double Re);

// Schiller-Naumann: Cd = 24/Re (1 + 0.15 Re^0.687) for Re <= 1000, 0.44 above.
double drag_coefficient_schiller_naumann(double Re);

double drag_coefficient(DragModel model, double Re);

// Drag momentum-transfer coefficient beta [kg/s] of F = beta (U_f - U_p):
// beta = 3/4 m_p Cd Re mu_f / (rho_p d^2) = 3 pi mu_f d (Cd Re / 24).
// Codina2019 eq. 2.14 omits mu_f; with it, Stokes flow (Cd Re = 24) gives 3 pi mu d.
// Finite as Re -> 0 because Cd Re is evaluated as one product.
double drag_beta(DragModel model, double Re, double mu_f, double d);

}  // namespace meltdem::coupling
