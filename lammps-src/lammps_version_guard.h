#pragma once
// The project compiles against the headers of the Debian LAMMPS source package but links
// Debian's liblammps: a different library version would mean a different class layout.
#include <string>

namespace LAMMPS_NS {
class LAMMPS;
}

namespace meltdem {

// Empty when the running library's version equals header_version (a LAMMPS date string
// such as "29 Sep 2021"); otherwise the message to print before refusing to start.
std::string lammps_version_mismatch(LAMMPS_NS::LAMMPS *lmp, const char *header_version);

}  // namespace meltdem
