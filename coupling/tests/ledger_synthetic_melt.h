#pragma once
// A synthetic coupled melt for the ledger tests, built the way the solver will book it:
// particles heat and melt with heat_melt_step (Codina2019 eq. 2.3, 2.9, 2.13) in a column of gas
// cells; each particle's melt goes into three cells (weights 0.5/0.3/0.2), the heat it absorbs
// is taken from its cell, gravity acts on it (an external particle source); gas flows through
// the column (boundary in = out) and the molten metal leaves through the outlet at 10 % of
// each cell's metal per step. The continuum inventory is the plain sum over cells, so every
// cell update rounds as a solver's would. Particles and cells are owned round-robin by rank.
#include "meltdem/coupling/conservation_ledger.h"
#include "meltdem/coupling/particle_melting.h"

#include <cmath>
#include <functional>
#include <vector>

namespace meltdem::coupling::testing {

// Codina2019 table 2.3 particle: m = 9.069e-7 kg, cp 48.35, Tm 1000 K, L = 0.248611 J / m,
// falling at M / m = 1.81408e-6 / 9.069e-7 m/s (eq. 2.37)
inline MeltMaterial thesis_steel()
{
  return {48.35, 1000.0, 0.248611 / 9.069e-7};
}
constexpr double kThesisMass = 9.069e-7, kThesisRho = 8020.0, kThesisMomentum = 1.81408e-6;
constexpr double kGasT = 1500.0, kGasK = 100.0, kKNu = 2.0 * kGasK;  // Nu = 2 as in test_particle_melting

struct SyntheticOptions {
  int particles = 1;                   // particle p has mass kThesisMass * (1 + 0.37 p) and melts in cell 3 p + 1
  int melt_steps = 200;                // steps of the melting phase (dt chosen so the first particle melts)
  int outflow_steps = 50;              // steps after the melt, metal leaving through the outlet
  int rank = 0, size = 1;              // ownership of particles and cells (round robin)
  int skip_cell_update_step = -1;      // a deliberately missing booking: the melt of this step never reaches the cells
  int skip_outflow_booking_step = -1;  // the outflow of this step leaves the cells but is not booked
  int lose_particle_step = -1;         // particle 0 leaves the mesh at this step (booked as lost)
  bool drop_lost_silently = false;     // ... or vanishes without booking (the defect the ledger must catch)
  double gravity = -9.81;
  std::function<void(const LedgerStep &)> on_step;  // called after every end_step
};

struct Cell {
  double gas_m = 0.0, gas_h = 0.0, gas_u = 0.0;  // gas: mass, specific enthalpy, y velocity
  double metal_m = 0.0, metal_H = 0.0;           // metal mass and enthalpy
  double metal_P[3] = {0.0, 0.0, 0.0};           // metal momentum
  double heat_taken = 0.0;                       // heat given to particles (gas loses it)
  double gas_P[3] = {0.0, 0.0, 0.0};             // gas momentum change from drag (none here)
};

inline Amounts cell_amounts(const Cell &c)
{
  return {c.gas_m + c.metal_m, c.gas_m * c.gas_h + c.metal_H - c.heat_taken, c.metal_P[0],
          c.gas_m * c.gas_u + c.metal_P[1], c.metal_P[2]};
}

// Runs the case through 'ledger' (on whatever communicator it reduces over).
inline void run_synthetic_melt(ConservationLedger &ledger, const SyntheticOptions &o)
{
  const MeltMaterial mat = thesis_steel();
  const int ncells = 3 * o.particles + 2;
  std::vector<Cell> cells(ncells);
  for (int i = 0; i < ncells; ++i) cells[i] = {1e-9 * (1.0 + 0.01 * i), 1004.5 * 300.0, -0.5};
  const double v0 = -kThesisMomentum / kThesisMass;

  struct P {
    double m, d, h;
    Eigen::Vector3d v;
    bool alive, lost;
  };
  std::vector<P> ps;
  for (int p = 0; p < o.particles; ++p) {
    const double m = kThesisMass * (1.0 + 0.37 * p);
    ps.push_back(
        {m, std::cbrt(6.0 * m / (M_PI * kThesisRho)), 0.0, Eigen::Vector3d(0.01 * p, v0, -0.02 * p), true, false});
  }
  const double dt = 2.2e-3 / o.melt_steps;  // the Codina2019 particle melts in ~2.1 ms at Nu = 2
  const auto owns_cell = [&](int i) { return i % o.size == o.rank; };
  const auto owns_particle = [&](int p) { return p % o.size == o.rank; };
  const double weights[3] = {0.5, 0.3, 0.2};
  const double gas_flux = 0.05;  // part of each cell's gas exchanged through the boundaries per step

  const int nsteps = o.melt_steps + o.outflow_steps;
  for (int step = 0; step <= nsteps; ++step) {
    ledger.begin_step(step * dt, dt);
    std::vector<ExchangeRecord> records;
    if (step > 0) {
      for (int p = 0; p < o.particles; ++p) {
        P &q = ps[p];
        if (!q.alive) continue;
        const double m_old = q.m;
        ExchangeRecord r;
        r.id = p;
        // gravity: an external source into the particle
        q.v.y() += o.gravity * dt;
        if (owns_particle(p)) ledger.book(kParticleSource, kMomY, m_old * o.gravity * dt);
        const auto s = heat_melt_step(mat, q.h, q.m, q.d, kKNu, kGasT, dt);
        r.mass_out = s.mass_melted;
        r.enthalpy_out = s.enthalpy_out;
        r.momentum_out = s.mass_melted * q.v;
        r.heat_absorbed = s.heat;
        q.m = s.m, q.d = s.d, q.h = s.h;
        r.mass = q.m, r.h = q.h, r.v = q.v, r.radius = 0.5 * q.d, r.T = particle_temperature(mat, q.h);
        r.x = Eigen::Vector3d(0.0, -1e-3 * (3 * p + 1), 0.0);
        // the continuum side: the cell holding the particle gives the heat, three cells get the melt
        const int c0 = 3 * p + 1;
        cells[c0].heat_taken += s.heat;
        if (step != o.skip_cell_update_step)
          for (int k = 0; k < 3; ++k) {
            Cell &c = cells[c0 - 1 + k];
            c.metal_m += weights[k] * r.mass_out;
            c.metal_H += weights[k] * r.enthalpy_out;
            for (int d = 0; d < 3; ++d) c.metal_P[d] += weights[k] * r.momentum_out[d];
          }
        if (s.fully_molten) q.alive = false;
        if (p == 0 && step == o.lose_particle_step && q.alive) {
          q.alive = false;
          q.lost = true;
          if (owns_particle(p) && !o.drop_lost_silently) ledger.book_lost(r);
          continue;
        }
        if (owns_particle(p)) records.push_back(r);
      }
    }
    ledger.book_particles(records);

    // boundaries: gas through-flow (in = out, counted both ways) and metal leaving the outlet
    for (int i = 0; i < ncells; ++i) {
      Cell &c = cells[i];
      if (step == 0 || !owns_cell(i)) continue;
      const Amounts gas{gas_flux * c.gas_m, gas_flux * c.gas_m * c.gas_h, 0.0, gas_flux * c.gas_m * c.gas_u, 0.0};
      ledger.book(kBoundaryIn, gas);
      ledger.book(kBoundaryOut, gas);
      if (step > o.melt_steps) {
        const Amounts out{0.1 * c.metal_m, 0.1 * c.metal_H, 0.1 * c.metal_P[0], 0.1 * c.metal_P[1], 0.1 * c.metal_P[2]};
        c.metal_m -= out[kMass];
        c.metal_H -= out[kEnthalpy];
        for (int d = 0; d < 3; ++d) c.metal_P[d] -= out[kMomX + d];
        if (step != o.skip_outflow_booking_step) ledger.book(kBoundaryOut, out);
      }
    }
    for (int i = 0; i < ncells; ++i)
      if (owns_cell(i)) ledger.book(kContinuum, cell_amounts(cells[i]));
    // particles not yet inserted are none here; the pending store stays empty but is booked
    if (o.rank == 0) ledger.book(kPending, Amounts{});
    if (step == 0)  // the initial state: particles present, nothing exchanged yet
      for (int p = 0; p < o.particles; ++p)
        if (owns_particle(p)) {
          ExchangeRecord r;
          r.id = p, r.mass = ps[p].m, r.h = ps[p].h, r.v = ps[p].v, r.radius = 0.5 * ps[p].d;
          ledger.book_particle(r);
        }
    const LedgerStep &s = ledger.end_step();
    if (o.on_step) o.on_step(s);
  }
}

}  // namespace meltdem::coupling::testing
