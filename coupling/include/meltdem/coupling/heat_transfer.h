#pragma once
// Convective heat transfer between a sphere and the surrounding fluid (Codina2019 eq. 2.13).

namespace meltdem::coupling {

// Ranz-Marshall: Nu = 2 + 0.6 Re^(1/2) Pr^(1/3)
double ranz_marshall_nusselt(double Re, double Pr);

// Prandtl number Pr = cp mu / k of the fluid
double prandtl_number(double cp, double mu, double k);

// h = k_f Nu / d
double heat_transfer_coefficient(double k_fluid, double Nu, double d);

// Q_{c->p} = h A_p (T_f - T_p), A_p = pi d^2 (positive when the particle is heated)
double convective_heat_rate(double h, double d, double T_fluid, double T_particle);

}  // namespace meltdem::coupling
