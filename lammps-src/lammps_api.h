#ifndef MELTDEM_LAMMPS_API_H
#define MELTDEM_LAMMPS_API_H
// The LAMMPS calls whose form changed between the releases MeltDEM builds against (29 Sep 2021,
// Debian bookworm; 4 Feb 2025, Debian trixie), each in the form of the headers' version
// (MELTDEM_LAMMPS_VERSION, YYYYMMDD, set by cmake/MeltDEMLammps.cmake from version.h). Headers
// newer than 29 Sep 2021 get the 4 Feb 2025 form; the releases between are not tested.
#include "atom.h"
#include "atom_vec.h"
#include "domain.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "region.h"
#include "utils.h"
#include "write_restart.h"

#include <string>
#include <vector>

#ifndef MELTDEM_LAMMPS_VERSION
#error "MELTDEM_LAMMPS_VERSION (YYYYMMDD of the LAMMPS headers) must be defined by the build"
#endif
#define MELTDEM_LAMMPS_2025_API (MELTDEM_LAMMPS_VERSION > 20210929)

namespace meltdem::lammps_api {

// the region with this ID, nullptr when there is none
inline LAMMPS_NS::Region *region(LAMMPS_NS::Domain *domain, const std::string &id)
{
#if MELTDEM_LAMMPS_2025_API
  return domain->get_region_by_id(id);
#else
  const int i = domain->find_region(id);
  return i < 0 ? nullptr : domain->regions[i];
#endif
}

// atom style sphere (radius, rmass, omega, torque per atom)
inline bool sphere_style(const LAMMPS_NS::Atom *atom)
{
#if MELTDEM_LAMMPS_2025_API
  return atom->radius_flag && atom->rmass_flag && atom->omega_flag && atom->torque_flag;
#else
  return atom->sphere_flag && atom->radius_flag && atom->rmass_flag;
#endif
}

// the per-atom fields the atom style sends to ghosts every step
inline std::vector<std::string> comm_fields(const LAMMPS_NS::AtomVec *avec)
{
#if MELTDEM_LAMMPS_2025_API
  return avec->fields_comm;
#else
  return avec->fields_comm ? LAMMPS_NS::utils::split_words(avec->fields_comm) : std::vector<std::string>();
#endif
}

// an occasional half neighbor list with size cutoffs for a compute (as compute contact/atom)
template <class Requestor>
void request_occasional_size_list(LAMMPS_NS::Neighbor *neighbor, Requestor *requestor, int instance)
{
#if MELTDEM_LAMMPS_2025_API
  (void)instance;
  neighbor->add_request(requestor, LAMMPS_NS::NeighConst::REQ_SIZE | LAMMPS_NS::NeighConst::REQ_OCCASIONAL);
#else
  const int irequest = neighbor->request(requestor, instance);
  neighbor->requests[irequest]->size = 1;
  neighbor->requests[irequest]->pair = 0;
  neighbor->requests[irequest]->compute = 1;
  neighbor->requests[irequest]->occasional = 1;
#endif
}

// one restart file written by processor 0 (no multiproc files)
inline void single_file_restart(LAMMPS_NS::WriteRestart &restart)
{
#if MELTDEM_LAMMPS_2025_API
  restart.multiproc_options(0, 0, nullptr);
#else
  restart.multiproc_options(0, 0, 0, nullptr);
#endif
}

}  // namespace meltdem::lammps_api

#endif
