# Compile against Debian's liblammps with the headers of the matching Debian source package.
# /usr/include/lammps lacks fmt/ and the style headers, so the source tree's src/ (and
# src/GRANULAR) goes first on the include path. LAMMPS_EXCEPTIONS must stay undefined:
# it changes the layout of class Error relative to Debian's build.
find_package(LAMMPS REQUIRED CONFIG)

set(MELTDEM_LAMMPS_SRC "${MELTDEM_DEPS_DIR}/lammps-src/src")
if(NOT EXISTS "${MELTDEM_LAMMPS_SRC}/version.h" OR NOT EXISTS "${MELTDEM_LAMMPS_SRC}/GRANULAR/pair_granular.h")
  message(FATAL_ERROR "LAMMPS source headers not found in ${MELTDEM_LAMMPS_SRC}: "
                      "run 'sudo scripts/install-deps.sh' first (or set MELTDEM_DEPS_DIR)")
endif()

add_library(meltdem_lammps_headers INTERFACE)
target_include_directories(meltdem_lammps_headers BEFORE INTERFACE
  "${MELTDEM_LAMMPS_SRC}" "${MELTDEM_LAMMPS_SRC}/GRANULAR")
target_link_libraries(meltdem_lammps_headers INTERFACE LAMMPS::lammps MPI::MPI_CXX)
target_compile_features(meltdem_lammps_headers INTERFACE cxx_std_17)
