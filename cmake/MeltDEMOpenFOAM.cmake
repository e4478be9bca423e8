# Build OpenFOAM (Debian v1912, label 32, double) applications and libraries with CMake.
# Mirrors wmake's linux64Gcc rules: defines, flags, include order (the Make/options dirs
# first, then lnInclude and '.', then OpenFOAM and OSspecific), and the link flags.
# Include dirs are plain -I on purpose: lnInclude dirs share file names, order matters.

set(MELTDEM_FOAM_SRC "${MELTDEM_DEPS_DIR}/openfoam-src/src")
if(NOT EXISTS "${MELTDEM_FOAM_SRC}/OpenFOAM/lnInclude/fvCFD.H" AND NOT EXISTS "${MELTDEM_FOAM_SRC}/finiteVolume/lnInclude/fvCFD.H")
  message(FATAL_ERROR "OpenFOAM lnInclude headers not found under ${MELTDEM_FOAM_SRC}: "
                      "run 'sudo scripts/install-deps.sh' first (or set MELTDEM_DEPS_DIR)")
endif()
set(MELTDEM_FOAM_APPLICATIONS "${MELTDEM_DEPS_DIR}/openfoam-src/applications")
set(MELTDEM_FOAM_LIBDIR "/usr/lib" CACHE PATH "Folder holding Debian's OpenFOAM libraries")
set(MELTDEM_FOAM_PROJECT_DIR "/usr/share/openfoam" CACHE PATH "WM_PROJECT_DIR at run time")

set(MELTDEM_FOAM_DEFINES OPENFOAM=1912 WM_DP WM_LABEL_SIZE=32 NoRepository)
set(MELTDEM_FOAM_OPTIONS -std=c++17 -m64 -pthread -ftemplate-depth-100 -O3
    -Wall -Wextra -Wold-style-cast -Wnon-virtual-dtor -Wno-unused-parameter
    -Wno-invalid-offsetof -Wno-attributes -Wno-unknown-pragmas
    -Wno-deprecated-declarations)  # C++17: OpenFOAM v1912 still derives from std::iterator

# One imported target per Debian OpenFOAM library; they carry no SONAME.
function(meltdem_foam_import_lib name)
  if(NOT TARGET OpenFOAM::${name})
    set(path "${MELTDEM_FOAM_LIBDIR}/lib${name}.so")
    if(NOT EXISTS "${path}")
      message(FATAL_ERROR "OpenFOAM library ${path} not found (Debian package libopenfoam)")
    endif()
    add_library(OpenFOAM::${name} SHARED IMPORTED GLOBAL)
    set_target_properties(OpenFOAM::${name} PROPERTIES
      IMPORTED_LOCATION "${path}" IMPORTED_NO_SONAME TRUE)
  endif()
endfunction()

# meltdem_foam_target(<target> [APPDIR <dir>]
#                     INCLUDES <dirs relative to OpenFOAM src/ or absolute>
#                     LIBS <OpenFOAM library names without lib/.so>)
# APPDIR plays wmake's '.' (default: the target's source dir).
function(meltdem_foam_target target)
  cmake_parse_arguments(ARG "" "APPDIR" "INCLUDES;LIBS" ${ARGN})
  set(incs)
  foreach(d IN LISTS ARG_INCLUDES)
    if(IS_ABSOLUTE "${d}")
      list(APPEND incs "${d}")
    else()
      list(APPEND incs "${MELTDEM_FOAM_SRC}/${d}")
    endif()
  endforeach()
  if(ARG_APPDIR)
    set(srcdir "${ARG_APPDIR}")
  else()
    get_target_property(srcdir ${target} SOURCE_DIR)
  endif()
  list(APPEND incs "${srcdir}/lnInclude" "${srcdir}"
       "${MELTDEM_FOAM_SRC}/OpenFOAM/lnInclude" "${MELTDEM_FOAM_SRC}/OSspecific/POSIX/lnInclude")
  # plain -I in wmake's order, kept ahead of anything a linked target adds
  foreach(d IN LISTS incs)
    target_compile_options(${target} PRIVATE "-I${d}")
  endforeach()
  target_compile_definitions(${target} PRIVATE ${MELTDEM_FOAM_DEFINES})
  target_compile_options(${target} PRIVATE ${MELTDEM_FOAM_OPTIONS})
  set(libs)
  foreach(l IN LISTS ARG_LIBS ITEMS OpenFOAM Pstream)
    meltdem_foam_import_lib(${l})
    list(APPEND libs OpenFOAM::${l})
  endforeach()
  target_link_libraries(${target} PRIVATE -Wl,--add-needed -Wl,--no-as-needed ${libs} dl m)
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "SHARED_LIBRARY")
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
endfunction()
