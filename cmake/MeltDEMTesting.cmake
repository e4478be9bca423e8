# Every validation writes "name | measured | reference | tolerance | verdict" rows into
# MELTDEM_REPORT_DIR; scripts/run-tests.sh prints them as one table after ctest.
set(MELTDEM_REPORT_DIR "${CMAKE_BINARY_DIR}/validation-report")
file(MAKE_DIRECTORY "${MELTDEM_REPORT_DIR}")

function(meltdem_test_environment test)
  # a temporary folder per test: Open MPI 4's isolated singletons (below) all take job family
  # 0, so a singleton ending in one test could remove the session folder of one starting in
  # another (/tmp/ompi.<host>.<uid>/jf.0/1/0, "mkdir ... File exists" and MPI_Init fails)
  string(MD5 _hash "${CMAKE_BINARY_DIR}/${test}")
  string(SUBSTRING "${_hash}" 0 12 _hash)
  set(_tmp "/tmp/meltdem-test-${_hash}")
  file(MAKE_DIRECTORY "${_tmp}")
  set_property(TEST ${test} APPEND PROPERTY ENVIRONMENT "TMPDIR=${_tmp}")
  set_property(TEST ${test} APPEND PROPERTY ENVIRONMENT
    "MELTDEM_REPORT_DIR=${MELTDEM_REPORT_DIR}"
    "MELTDEM_BIN=${CMAKE_BINARY_DIR}/bin"
    "MELTDEM_SOURCE_DIR=${CMAKE_SOURCE_DIR}"
    "PYTHONPATH=${CMAKE_SOURCE_DIR}/python"
    "WM_PROJECT_DIR=${MELTDEM_FOAM_PROJECT_DIR}"
    "OMPI_ALLOW_RUN_AS_ROOT=1" "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1"
    "OMPI_MCA_rmaps_base_oversubscribe=1"
    # one node: no UCX probing and no singleton daemon (Open MPI 4 start-up 0.46 -> 0.09 s)
    "OMPI_MCA_pml=ob1" "OMPI_MCA_ess_singleton_isolated=1"
    # (Open MPI 5's launcher, PRRTE, reads its own variable)
    "PRTE_MCA_rmaps_default_mapping_policy=:oversubscribe")
endfunction()

# meltdem_add_script_test(NAME n LABELS l... COMMAND cmd args...)
function(meltdem_add_script_test)
  cmake_parse_arguments(ARG "" "NAME;TIMEOUT" "LABELS;COMMAND" ${ARGN})
  add_test(NAME ${ARG_NAME} COMMAND ${ARG_COMMAND})
  meltdem_test_environment(${ARG_NAME})
  set_property(TEST ${ARG_NAME} PROPERTY LABELS ${ARG_LABELS})
  if(ARG_TIMEOUT)
    set_property(TEST ${ARG_NAME} PROPERTY TIMEOUT ${ARG_TIMEOUT})
  endif()
  # a 2-rank test takes both of ctest -j2's slots: two of them side by side would put 4
  # busy-polling MPI ranks on 2 cores
  if(ARG_NAME MATCHES "np2" OR "mpi" IN_LIST ARG_LABELS OR "--np" IN_LIST ARG_COMMAND
     OR "-np" IN_LIST ARG_COMMAND)
    set_property(TEST ${ARG_NAME} PROPERTY PROCESSORS 2)
  endif()
endfunction()
