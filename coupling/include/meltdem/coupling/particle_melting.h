#pragma once
// Heating and melting of one particle over one time step (Codina2019 eq. 2.3, 2.9, 2.13).
//
// State: specific enthalpy h [J/kg], mass m, diameter d. Below melting T = h / cp; once
// h reaches cp Tm the particle stays at Tm and every joule of heat melts mass, which is
// handed to the continuum with the enthalpy cp Tm + L per kilogram (eq. 2.9). The solid
// remainder keeps its density, so it shrinks.
//
// The fluid state and Nu are frozen over the step; within it the ODEs are integrated
// exactly, so the result does not depend on the step size:
//  - sensible: m cp dT/dt = G (Tf - T), G = h_conv A = k Nu pi d -> exponential relaxation;
//  - melting:  L dm/dt = -G (Tf - Tm) with G ~ d -> d^2 falls linearly in time (d^2 law),
//    i.e. eq. 2.3's m_melt = min(m_p, Q dt / L) with Q integrated over the shrinking step.
// Bookkeeping is exact by construction: m_old h_old + heat = m_new h_new + enthalpy_out.

#include "meltdem/coupling/fluid_state.h"

#include <cstddef>

namespace meltdem::coupling {

struct MeltMaterial {
  double cp = 0.0;      // specific heat capacity of the solid [J/(kg K)]
  double Tmelt = 0.0;   // melting temperature [K]
  double latent = 0.0;  // latent heat of melting [J/kg]
};

// throws std::invalid_argument unless cp, Tmelt, latent > 0
void check_material(const MeltMaterial &mat);

// T = min(h, cp Tm) / cp
double particle_temperature(const MeltMaterial &mat, double h);

// h = cp T; throws unless 0 <= T <= Tm (a solid particle above Tm does not exist here)
double specific_enthalpy(const MeltMaterial &mat, double T);

// k_f Nu of Ranz-Marshall (eq. 2.13), Nu = 2 + 0.6 Re^1/2 Pr^1/3, Pr = cp_f mu_f / k_f
double ranz_marshall_k_nu(const FluidState &fluid, double Re);

struct MeltStepResult {
  double h = 0.0;             // specific enthalpy at the end of the step [J/kg]
  double m = 0.0;             // mass at the end of the step [kg] (0 when fully molten)
  double d = 0.0;             // diameter at the end of the step [m] (0 when fully molten)
  double heat = 0.0;          // heat absorbed over the step [J] (negative when cooling)
  double mass_melted = 0.0;   // m_old - m_new [kg], handed to the continuum (eq. 2.3)
  double enthalpy_out = 0.0;  // mass_melted (cp Tm + L) [J] (eq. 2.9)
  bool fully_molten = false;
  double T_fluid = 0.0;  // temperature of the fluid parcel at the end of the step [K]
};

// Energy [J] from outside the fluid (a laser) absorbed at once: it heats the particle up
// to Tm, then melts it (L per kilogram); what is left once it has melted completely goes
// with the melt (enthalpy_out). heat = energy; m h + energy = m' h' + enthalpy_out exactly.
MeltStepResult absorb_heat(const MeltMaterial &mat, double h, double m, double d, double energy);

// Heat [J] of either sign handed to the particle at once: gained as absorb_heat(), lost as
// sensible heat (never below 0 K: the rest is refused, heat = what was taken). m h + heat =
// m' h' + out exactly.
MeltStepResult exchange_heat(const MeltMaterial &mat, double h, double m, double d, double energy);

// The factor (1 - exp(-x)) / x, x = dt G / C_p, by which a particle of heat capacity C_p and
// conductance G takes the mean of the heat flux G (T_f - T_p) over a step dt against a fluid
// at T_f: with it the particle ends the step exactly where it would relax to over dt, never
// past T_f, however long the step (1 for x -> 0; 1 / x for x >> 1).
double relaxation_factor(double x);

// One step of length dt with k_nu = k_f Nu [W/(m K)] and fluid temperature T_fluid.
MeltStepResult heat_melt_step(const MeltMaterial &mat, double h, double m, double d, double k_nu, double T_fluid,
                              double dt);

// The same step against a fluid parcel of finite heat capacity C_fluid [J/K] at T_fluid (the
// particle's share of its cells, FluidState::capacity) as two bodies: the heat the particle
// takes, the parcel loses. While the particle is solid below Tm both relax towards their
// common temperature exactly, Delta(t) = Delta_0 exp(-G (1/C_p + 1/C_fluid) t); once it is at
// Tm the parcel feeds the melting, theta = T_fluid - Tm decaying as exp(-G t / C_fluid) in
// pieces that melt at most 3 % of the mass, G at the piece's mid diameter. Neither body passes
// the other for any dt (the step is stable however long), and m h + heat = m' h' + out.
// C_fluid <= 0: an unbounded fluid, heat_melt_step(). T_fluid of the result: the parcel's end.
MeltStepResult heat_melt_step_two_body(const MeltMaterial &mat, double h, double m, double d, double k_nu,
                                       double T_fluid, double C_fluid, double dt);

// --- The explicit exchange and the cells that pay for it (a particle melting within
// one step). Over a fluid step each particle heats with the fluid frozen; its cells lose that
// heat. A cell of heat capacity C = rho cp V [J/K] feeding particles of conductance G [W/K]
// loses G (Tf - Tp) dt, so on its own it passes the particles' temperature once dt > C / G and
// the step after it swings back (an explicit instability: the balances stay closed, the
// temperatures do not stay bounded). Conduction and flow resupply the cell, so C / G is the
// time scale of the trouble, not a sharp limit; the continuum's temperature range after the
// step is the test.

// k_f Nu pi d [W/K]: a particle's convective conductance (eq. 2.13) at the slip velocity U_f - v
double particle_conductance(const FluidState &fluid, double d, const double v[3]);

// min over cells of C[i] / G[i] [s]; cells with G[i] <= 0 are skipped (+infinity if none)
double heat_exchange_time(const double *C, const double *G, std::size_t n);

// How far [K] the continuum's range [Tmin, Tmax] after a step lies outside [lo, hi], the range
// of the continuum and the particles before it (no exchange can leave it: heat only flows from
// hot to cold), beyond the numerical allowance tol (hi - lo) + 1e-9 max(|lo|, |hi|); 0 when
// bounded. upper = false
// skips the upper bound (a laser heats the continuum above both).
double temperature_overshoot(double lo, double hi, double Tmin, double Tmax, double tol, bool upper);

}  // namespace meltdem::coupling
