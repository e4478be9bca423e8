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

# the headers' version as YYYYMMDD (version.h has only the text): lammps-src/lammps_api.h
# selects each call's form by it
file(STRINGS "${MELTDEM_LAMMPS_SRC}/version.h" _lammps_version REGEX "^#define LAMMPS_VERSION ")
string(REGEX MATCH "\"([0-9]+) ([A-Za-z]+) ([0-9]+)\"" _ "${_lammps_version}")
set(_day ${CMAKE_MATCH_1})
set(_year ${CMAKE_MATCH_3})
set(_months Jan Feb Mar Apr May Jun Jul Aug Sep Oct Nov Dec)
list(FIND _months "${CMAKE_MATCH_2}" _month)
if(NOT _day OR _month LESS 0)
  message(FATAL_ERROR "cannot read the LAMMPS version from ${MELTDEM_LAMMPS_SRC}/version.h")
endif()
math(EXPR MELTDEM_LAMMPS_VERSION "${_year} * 10000 + (${_month} + 1) * 100 + ${_day}")
message(STATUS "LAMMPS headers: version ${MELTDEM_LAMMPS_VERSION}")

add_library(meltdem_lammps_headers INTERFACE)
target_compile_definitions(meltdem_lammps_headers INTERFACE MELTDEM_LAMMPS_VERSION=${MELTDEM_LAMMPS_VERSION})
target_include_directories(meltdem_lammps_headers BEFORE INTERFACE
  "${MELTDEM_LAMMPS_SRC}" "${MELTDEM_LAMMPS_SRC}/GRANULAR")
target_link_libraries(meltdem_lammps_headers INTERFACE LAMMPS::lammps MPI::MPI_CXX)
target_compile_features(meltdem_lammps_headers INTERFACE cxx_std_17)
