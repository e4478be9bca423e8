#include "lammps_version_guard.h"

#include "library.h"
#include "utils.h"

namespace meltdem {

std::string lammps_version_mismatch(LAMMPS_NS::LAMMPS *lmp, const char *header_version)
{
  // lammps_version() reads the number through the library itself, so it is valid even
  // when our view of class LAMMPS differs from the library's.
  const int library = lammps_version(lmp);
  const int headers = LAMMPS_NS::utils::date2num(header_version);
  if (library == headers) return {};
  return "MeltDEM was compiled against LAMMPS headers of version " + std::to_string(headers) + " (" + header_version +
         ") but the LAMMPS library loaded at run time is version " + std::to_string(library) +
         ". Rebuild MeltDEM after 'sudo scripts/install-deps.sh' so that headers and library match.";
}

}  // namespace meltdem
