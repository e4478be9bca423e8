/* -*- c++ -*- ----------------------------------------------------------
   MeltDEM: fix powder/insert -- overlap-free powder insertion with a pending
   queue (Codina2019 §3.2.2). Size distributions and the random stream live in coupling/.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
// no trailing semicolon: meltdem_styles.cpp expands this inside an array initializer
FixStyle(powder/insert,FixPowderInsert)
// clang-format on
#else

#ifndef MELTDEM_FIX_POWDER_INSERT_H
#define MELTDEM_FIX_POWDER_INSERT_H

#include "fix.h"

#include "meltdem/coupling/size_distribution.h"

#include <deque>
#include <vector>

namespace LAMMPS_NS {

class FixPowderInsert : public Fix {
 public:
  FixPowderInsert(class LAMMPS *, int, char **);
  ~FixPowderInsert() override;
  int setmask() override;
  void init() override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  void post_integrate() override;
  void end_of_step() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // for pair styles that size their cutoff before any particle exists (granular/powder):
  // the atom type inserted and the largest diameter still to come (pending ones included)
  int insert_type() const { return ntype; }
  double max_new_diameter() const
  {
    double d = dist.dmax();
    for (double p : pending) d = p > d ? p : d;
    return d;
  }
  // the state new particles get, for the coupling's ledger of fed and pending powder
  const double *new_velocity() const { return vnew; }
  bool sets_temperature() const { return tempflag != 0; }  // else fix powder/melt's temp
  double new_temperature() const { return temp; }

 private:
  bigint ninsert;               // N requested
  int ntype;                    // atom type of the new particles
  class Region *insert_region;  // the insertion region (looked up again at init)
  char *idregion;
  double density;
  int ratemode;  // ALL, RATE (particles/time) or MASSRATE (mass/time)
  double rate;
  double vnew[3];
  int tempflag;
  double temp;
  int maxattempt;
  double gap;
  int insert_every;    // insertion tried at most every insert_every steps
  bigint stall_limit;  // insertion tries in a row that place nothing before the stall message
  int stall_error;     // 1: the stall message stops the run, 0: it is a warning
  bigint nstall;       // insertion tries in a row that placed nothing (not in restarts)

  meltdem::coupling::SizeDistribution dist;
  meltdem::coupling::Rng64 rng_size;  // draws diameters only: same sequence on any #procs
  meltdem::coupling::Rng64 rng_pos;   // draws positions

  // state (saved in restart files)
  std::deque<double> pending;  // diameters drawn and due, not yet placed (FIFO)
  bigint ndrawn;               // diameters drawn so far (= inserted + pending)
  bigint ninserted;
  bigint nfailed;  // rejected trial positions
  double mass_inserted;
  double credit;         // accumulated rate*dt (particles or mass) not yet drawn
  double dt_step = 0.0;  // the step being taken (post_integrate)
  double lookahead;      // massrate: next diameter, drawn but not yet due (0: none)
  bigint last_insert_step;
  tagint last_tag;  // the largest atom ID this fix has given (never reused)

  class FixPowderMelt *fixmelt;

  double particle_mass(double d) const;
  void draw_due();
  void schedule();
  int region_fits(double *, double);
  int wall_overlap(double *, double);
};

}  // namespace LAMMPS_NS

#endif
#endif
